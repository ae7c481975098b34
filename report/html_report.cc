#include "report/html_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/provenance.h"
#include "core/rendered_regions.h"
#include "io/atomic_file.h"
#include "report/rendered_colors.h"
#include "report/report_charts.h"

namespace brdfit::report {

using nlohmann::json;
namespace fs = std::filesystem;

// ---- helpers ------------------------------------------------------------------------------

std::filesystem::path ChartJsPath() {
  if (const char* env = std::getenv("BRDFIT_CHART_JS"); env && *env) return env;
  return kDefaultChartJs;
}

namespace {
bool ReadBytes(const fs::path& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return false;
  *out = ss.str();
  return true;
}
}  // namespace

std::string ReadChartJs(const fs::path& path) {
  const std::string fix =
      "the HTML report inlines Chart.js from Debian's libjs-chart.js: run "
      "scripts/setup-deps.sh (or apt-get install libjs-chart.js), or set BRDFIT_CHART_JS to "
      "chart.min.js";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "Chart.js not found; " + fix);
  std::string js;
  if (!ReadBytes(path, &js)) throw InputError(path, "cannot read Chart.js; " + fix);
  if (js.find("Chart") == std::string::npos || js.size() < 1000) {
    throw InputError(path, "does not look like Chart.js; " + fix);
  }
  // Inlined into a <script> element: the text must not close it.
  if (js.find("</script") != std::string::npos || js.find("</SCRIPT") != std::string::npos) {
    throw InputError(path, "contains '</script' and cannot be inlined");
  }
  return js;
}

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default:
        // C0 controls other than tab, LF and CR, and DEL, are parse errors in HTML text (HTML
        // Living Standard, 13.2.5 "control-character-in-input-stream"): shown as U+FFFD.
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') ||
            c == '\x7f') {
          out += "&#xFFFD;";
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string Base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string ScriptSafeJson(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (const char c : json_text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

namespace {

std::string Num(double v, const char* spec = "{:.4g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : "–";
}

// The error metrics' columns (core/metrics.h kErrorMetrics): headers, and each metric's cell
// made by cell(value), in the table's order.
std::string ErrorMetricHeaders() {
  std::string s;
  for (const ErrorMetricField& f : kErrorMetrics) s += fmt::format("<th>{}</th>", f.name);
  return s;
}
template <class Cell>
std::string ErrorMetricCells(const FitMetrics& m, Cell cell) {
  std::string s;
  for (const ErrorMetricField& f : kErrorMetrics) s += cell(m.*f.value);
  return s;
}

// Anchor-safe id from a name.
std::string Slug(const std::string& name) {
  std::string s;
  for (const char c : name) {
    s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  }
  return s;
}

bool Usable(const Entry& e) { return !e.Failed() && e.metrics.ok; }
bool HasRendered(const Entry& e) { return Usable(e) && e.metrics.rendered.ok; }
bool AnyChosen(const Report& r) {
  for (const Material& m : r.materials) {
    for (const Entry& e : m.entries) {
      if (Usable(e) && e.chosen) return true;
    }
  }
  return false;
}
bool AnyRendered(const Report& r) {
  for (const Material& m : r.materials) {
    for (const Entry& e : m.entries) {
      if (HasRendered(e)) return true;
    }
  }
  return false;
}
// "33.41" dB and "79.0 %", or "–" without a rendered error.
std::string Psnr(const Entry& e) {
  return HasRendered(e) ? fmt::format("{:.2f}", e.metrics.rendered.psnr_db) : "–";
}
std::string LumPct(const Entry& e) {
  return HasRendered(e) ? fmt::format("{:.1f} %", 100 * e.metrics.rendered.median_rel_error) : "–";
}

// The rendered metric's PSNR per region of the domain ("48.9 · 36.0 · 23.7 · 40.2", "–" for a
// region without lights; core/rendered_regions.h), or "–" without a rendered error.
std::string RegionsText(const Entry& e) {
  if (!HasRendered(e)) return "–";
  std::string out;
  for (const RegionError& g : RenderedRegions(e.metrics.rendered)) {
    out += (out.empty() ? "" : " · ") + (g.lights > 0 ? fmt::format("{:.1f}", g.psnr_db) : "–");
  }
  return out;
}

// The cost columns of an entry: a factorization's texture memory and fetches per light and per
// fragment (core/factor_form.h), a fit's parameter count, "–" where unknown.
std::string CostCells(const Entry& e) {
  if (e.kind == Entry::Kind::kFactor && e.has_cost) {
    return fmt::format("<td>{}</td><td>{}</td><td>{}</td>", BytesText(e.cost.texture_bytes),
                       e.cost.fetches_per_light, e.cost.fetches_per_fragment);
  }
  if (e.kind == Entry::Kind::kFit && !e.params.empty()) {
    return fmt::format("<td>{} params</td><td>–</td><td>–</td>", e.params.size());
  }
  return "<td>–</td><td>–</td><td>–</td>";
}

// ---- page assembly ------------------------------------------------------------------------

constexpr const char* kStyle = R"css(
:root { --fg:#1d232a; --muted:#5b6570; --line:#d9dee3; --best:#dff3e2; --bad:#fbe4e4; }
* { box-sizing: border-box; }
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: var(--fg);
       margin: 0 auto; max-width: 1280px; padding: 16px 24px 48px; }
h1 { font-size: 24px; margin: 8px 0 4px; } h2 { font-size: 20px; margin: 32px 0 8px;
  border-bottom: 2px solid var(--line); padding-bottom: 4px; } h3 { font-size: 16px; margin: 20px 0 6px; }
.muted, .note { color: var(--muted); } .note { font-style: italic; }
table { border-collapse: collapse; margin: 8px 0; font-variant-numeric: tabular-nums; }
th, td { border-bottom: 1px solid var(--line); padding: 4px 6px; text-align: right; white-space: nowrap; }
th { background: #f3f5f7; position: sticky; top: 0; } td.l, th.l { text-align: left; }
tr.best td { background: var(--best); } td.bestv { font-weight: 700; }
tr.failed td { background: var(--bad); }
.charts { display: grid; grid-template-columns: repeat(auto-fit, minmax(520px, 1fr)); gap: 16px; }
.chart { position: relative; height: 340px; border: 1px solid var(--line); border-radius: 6px; padding: 6px; }
.renders { display: flex; flex-wrap: wrap; gap: 16px; } figure { margin: 0; }
figure img { max-width: 100%; border: 1px solid var(--line); } figcaption { color: var(--muted); }
#report-errors { display: none; background: var(--bad); border: 1px solid #d33; padding: 8px; }
nav a { margin-right: 12px; } code { background: #f3f5f7; padding: 0 3px; }
details { margin: 6px 0; } summary { cursor: pointer; color: var(--muted); }
.scroll { overflow-x: auto; max-width: 100%; } td.stages { white-space: normal; min-width: 16em; max-width: 30em; text-align: left; font-size: 12px; }
th.wrap { white-space: normal; min-width: 6em; max-width: 11em; vertical-align: bottom; }
.views { display: flex; flex-wrap: wrap; gap: 12px 28px; align-items: flex-start; margin: 8px 0; }
.view { display: grid; grid-template-columns: repeat(3, 160px); gap: 4px 6px; }
.view .cap { grid-column: 1 / 4; color: var(--muted); }
.view img { width: 160px; height: 160px; border: 0; display: block; cursor: zoom-in; }
#lightbox { display: none; position: fixed; inset: 0; z-index: 10; background: rgba(0,0,0,0.88);
  flex-direction: column; align-items: center; justify-content: center; gap: 12px; cursor: zoom-out; }
#lightbox .row { display: flex; gap: 12px; } #lightbox p { color: #eee; margin: 0; }
#lightbox img { width: min(31vw, 78vh); height: min(31vw, 78vh); image-rendering: pixelated; }
td.status { white-space: normal; text-align: left; min-width: 14em; }
.view span { color: var(--muted); font-size: 12px; text-align: center; }
.legend { display: flex; align-items: center; gap: 8px; flex-wrap: wrap; color: var(--muted); font-size: 12px; }
.legend .bar { width: 300px; height: 12px; border: 1px solid var(--line); }
.legend .ticks { display: flex; justify-content: space-between; width: 300px; white-space: nowrap; }
.swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid var(--line); vertical-align: middle; margin: 0 3px 0 8px; }
)css";

// First script of the page: collects errors before anything else runs.
constexpr const char* kErrorCapture = R"js(
window.__errors = [];
window.__brdfitError = function (msg) {
  window.__errors.push(String(msg));
  if (document.body) {
    document.body.setAttribute('data-errors', JSON.stringify(window.__errors));
    var box = document.getElementById('report-errors');
    if (box) { box.style.display = 'block'; box.textContent = 'Errors on this page: ' + window.__errors.join(' | '); }
  }
};
window.addEventListener('error', function (e) {
  window.__brdfitError((e && e.message) ? e.message : 'error loading ' + (e && e.target && e.target.src));
}, true);
window.addEventListener('unhandledrejection', function (e) { window.__brdfitError('unhandled rejection: ' + e.reason); });
(function () {
  var original = console.error;
  console.error = function () {
    window.__brdfitError(Array.prototype.map.call(arguments, String).join(' '));
    return original.apply(console, arguments);
  };
})();
)js";

// Last script: draws every chart from its JSON configuration and records what it drew.
constexpr const char* kBootstrap = R"js(
(function () {
  if (typeof Chart === 'undefined') { window.__brdfitError('Chart.js did not load'); return; }
  var specs = document.querySelectorAll('script[type="application/json"][data-chart]');
  var rendered = 0;
  function tooltipLabel(ctx) {
    var r = ctx.raw;
    if (r && typeof r === 'object' && r.label) return r.label;
    return ctx.dataset.label + ': ' + ctx.formattedValue;
  }
  function drewSomething(chart) {
    var points = 0;
    chart.data.datasets.forEach(function (d) {
      d.data.forEach(function (v) {
        var y = (v !== null && typeof v === 'object') ? v.y : v;
        if (typeof y === 'number' && isFinite(y)) points++;
      });
    });
    var c = chart.canvas, g = c.getContext('2d');
    var px = g.getImageData(0, 0, c.width, c.height).data, inked = 0;
    for (var i = 3; i < px.length; i += 4) if (px[i] > 0) inked++;
    return points > 0 && inked > 0.002 * c.width * c.height;
  }
  // Log axes: label 1, 2 and 5 times powers of ten, in exponent form far from 1.
  function logTick(value) {
    if (!(value > 0)) return '';
    var e = Math.floor(Math.log10(value) + 1e-9), m = value / Math.pow(10, e);
    m = Math.round(m * 1000) / 1000;
    if (m !== 1 && m !== 2 && m !== 5) return '';
    return (e < -3 || e > 4) ? m + 'e' + e : String(Number(value.toPrecision(3)));
  }
  specs.forEach(function (s) {
    var id = s.getAttribute('data-chart');
    try {
      var cfg = JSON.parse(s.textContent);
      cfg.options = cfg.options || {};
      cfg.options.plugins = cfg.options.plugins || {};
      cfg.options.plugins.tooltip = { callbacks: { label: tooltipLabel } };
      Object.keys(cfg.options.scales || {}).forEach(function (k) {
        var sc = cfg.options.scales[k];
        if (sc.type === 'logarithmic') { sc.ticks = sc.ticks || {}; sc.ticks.callback = logTick; }
      });
      var canvas = document.getElementById(id);
      var chart = new Chart(canvas, cfg);
      if (drewSomething(chart)) { rendered++; canvas.setAttribute('data-rendered', '1'); }
      else window.__brdfitError('chart ' + id + ' drew no data');
    } catch (e) {
      window.__brdfitError('chart ' + id + ': ' + e);
    }
  });
  document.body.setAttribute('data-charts-rendered', String(rendered));
  document.body.setAttribute('data-errors', JSON.stringify(window.__errors));
})();
)js";

// Last script of the page, independent of Chart.js: a click on a render shows its view's three
// pictures enlarged (a click or Escape closes them); <body data-wide-tables> counts the tables
// wider than the page at the window's width (the browser tests read it).
constexpr const char* kPageScript = R"js(
(function () {
  var box = document.createElement('div');
  box.id = 'lightbox';
  box.setAttribute('role', 'dialog');
  function close() { box.style.display = 'none'; box.textContent = ''; }
  box.addEventListener('click', close);
  document.addEventListener('keydown', function (e) { if (e.key === 'Escape') close(); });
  document.body.appendChild(box);
  document.querySelectorAll('.view').forEach(function (view) {
    var imgs = view.querySelectorAll('img'), cap = view.querySelector('.cap');
    imgs.forEach(function (img) {
      img.title = 'click to enlarge';
      img.addEventListener('click', function () {
        box.textContent = '';
        var row = document.createElement('div');
        row.className = 'row';
        imgs.forEach(function (i) { var c = i.cloneNode(); c.removeAttribute('title'); row.appendChild(c); });
        var p = document.createElement('p');
        p.textContent = (cap ? cap.textContent + ' \u2014 ' : '') +
            'measured, fit, luminance error (click or Escape to close)';
        box.appendChild(row);
        box.appendChild(p);
        box.style.display = 'flex';
      });
    });
  });
  var wide = 0;
  document.querySelectorAll('.scroll').forEach(function (d) { if (d.scrollWidth > d.clientWidth + 1) wide++; });
  document.body.setAttribute('data-wide-tables', String(wide));
})();
)js";

class Page {
 public:
  explicit Page(const Report& r) : report_(r), palette_(r) {}

  std::string Build(const std::string& chart_js) {
    Header();
    Summary();
    Bench();
    for (const Material& m : report_.materials) MaterialSection(m);
    Renders();
    // Provenance (core/provenance.h): version, command line, date.
    const RunProvenance run = CurrentRunProvenance(true);
    std::string made = "Made by brdfit " + HtmlEscape(run.version);
    if (!run.created.empty()) made += " on " + HtmlEscape(run.created);
    if (!run.command_line.empty()) made += ": <code>" + HtmlEscape(run.command_line) + "</code>";
    body_ += fmt::format(
        "<footer class=\"muted\"><p id=\"provenance\">{}.</p><p>Plots drawn by Chart.js 3 (MIT "
        "licence, chartjs.org), inlined from Debian's libjs-chart.js; the page loads nothing "
        "from the network.</p></footer>\n",
        made);
    std::string out;
    out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    out += "<title>" + HtmlEscape(report_.title) + "</title>\n";
    out += "<style>" + std::string(kStyle) + "</style>\n";
    out += "<script>" + std::string(kErrorCapture) + "</script>\n";
    out += "<script>\n" + chart_js + "\n</script>\n</head>\n";
    out += fmt::format("<body data-charts-expected=\"{}\" data-charts-rendered=\"0\" "
                       "data-errors=\"[]\">\n",
                       charts_);
    out += "<div id=\"report-errors\"></div>\n";
    out += body_;
    out += "<script>" + std::string(kBootstrap) + "</script>\n";
    out += "<script>" + std::string(kPageScript) + "</script>\n</body>\n</html>\n";
    return out;
  }

 private:
  // True if some dataset holds a finite value (Chart.js would draw an empty frame otherwise).
  static bool HasData(const json& config) {
    for (const json& d : config["data"]["datasets"]) {
      for (const json& v : d["data"]) {
        const json& y = v.is_object() ? v["y"] : v;
        if (y.is_number() && std::isfinite(y.get<double>())) return true;
      }
    }
    return false;
  }

  void Chart(const json& config, const std::string& aria) {
    if (!HasData(config)) {
      body_ += "<p class=\"note\">No data to plot: " + HtmlEscape(aria) + ".</p>\n";
      return;
    }
    const std::string id = fmt::format("chart-{}", charts_++);
    body_ += fmt::format(
        "<div class=\"chart\"><canvas id=\"{}\" role=\"img\" aria-label=\"{}\"></canvas></div>\n"
        "<script type=\"application/json\" data-chart=\"{}\">{}</script>\n",
        id, HtmlEscape(aria), id, ScriptSafeJson(config.dump(-1, ' ', false, json::error_handler_t::replace)));
  }

  void Header() {
    body_ += "<header><h1>" + HtmlEscape(report_.title) + "</h1>\n";
    if (!report_.inputs.empty()) {
      body_ += fmt::format("<details><summary>Made from {} input{}</summary><p>",
                           report_.inputs.size(), report_.inputs.size() == 1 ? "" : "s");
      for (std::size_t i = 0; i < report_.inputs.size(); ++i) {
        body_ += (i ? ", " : "") + ("<code>" + HtmlEscape(report_.inputs[i]) + "</code>");
      }
      body_ += "</p></details>\n";
    }
    if (!report_.metric_definition.empty()) {
      body_ += "<p class=\"muted\"><b>Metrics.</b> " + HtmlEscape(report_.metric_definition) +
               "</p>\n";
    }
    if (!report_.materials.empty()) {
      body_ +=
          "<p class=\"muted\"><b>Rendered error.</b> PSNR: linear PSNR of a sphere rendered "
          "under directional lights all around it (front: up to 80° from the view; side: "
          "up to 125°; rim: behind it), the fit against the measured table; lum. err.: "
          "median relative luminance error over its pixels (docs/accuracy.md). <b>Best</b> "
          "(★) per "
          "material: " +
          (AnyChosen(report_) ? HtmlEscape(BestRule(BestBy::kChosen)) +
                                    "; for a material "
                                    "without a chosen fit, "
                              : std::string()) +
          HtmlEscape(BestRule(AnyRendered(report_) ? BestBy::kRendered : BestBy::kLogRmse)) +
          ".</p>\n";
    }
    for (const auto& n : report_.notes) body_ += "<p class=\"note\">" + HtmlEscape(n) + "</p>\n";
    if (report_.materials.size() > 1) {
      body_ += "<nav>Materials: ";
      for (const Material& m : report_.materials) {
        body_ += fmt::format("<a href=\"#m-{}\">{}</a>", Slug(m.name), HtmlEscape(m.name));
      }
      body_ += "</nav>\n";
    }
    body_ += "</header>\n";
  }

  // Materials x approximations: each material's best result (PickBest), and the best result of
  // each model or factorization over its losses and budgets (the same rule within the name).
  void Summary() {
    std::vector<std::string> names;  // models and factorizations, in order of appearance
    std::set<std::string> seen;
    for (const Material& m : report_.materials) {
      for (const Entry& e : m.entries) {
        if (seen.insert(e.Model()).second) names.push_back(e.Model());
      }
    }
    if (names.empty()) return;
    const bool rendered = AnyRendered(report_);
    body_ += "<section id=\"summary\"><h2>Summary: best result per material</h2>\n";
    body_ += "<p class=\"muted\">Per material its best result (" +
             HtmlEscape(BestRule(rendered ? BestBy::kRendered : BestBy::kLogRmse)) +
             "), then the best of each model or factorization over its losses and budgets, by the "
             "same rule: PSNR (dB) · median luminance error" +
             std::string(rendered ? "" : " (none here: log_rmse instead)") +
             "; the material's best in bold. – : not run or failed.</p>\n";
    body_ += "<div class=\"scroll\"><table><tr><th class=\"l\">material</th>"
             "<th>PSNR (dB)</th><th class=\"wrap\">median lum. err.</th>"
             "<th class=\"l\">best</th><th>log_rmse</th>";
    // A model name breaks after its '+' (no cell is as wide as "lambert+cook-torrance").
    for (const auto& n : names) {
      std::string h = HtmlEscape(n);
      for (std::size_t at = h.find('+'); at != std::string::npos; at = h.find('+', at + 6)) {
        h.insert(at + 1, "<wbr>");
      }
      body_ += "<th class=\"wrap\">" + h + "</th>";
    }
    body_ += "</tr>\n";
    for (const Material& m : report_.materials) {
      const BestPick best = PickBest(m.entries);
      const Entry* b = best.index >= 0 ? &m.entries[static_cast<std::size_t>(best.index)] : nullptr;
      body_ += fmt::format("<tr><td class=\"l\"><a href=\"#m-{}\">{}</a></td>", Slug(m.name),
                           HtmlEscape(m.name));
      body_ += fmt::format("<td>{}</td><td>{}</td><td class=\"l\">{}</td><td>{}</td>",
                           b ? Psnr(*b) : "–", b ? LumPct(*b) : "–",
                           b ? HtmlEscape(b->name) : std::string("–"),
                           b ? Num(b->metrics.log_rmse) : std::string("–"));
      // The entries of each model, grouped in one pass.
      std::map<std::string, std::pair<std::vector<Entry>, std::vector<const Entry*>>> by_model;
      for (const Entry& e : m.entries) {
        auto& [of, from] = by_model[e.Model()];
        of.push_back(e);
        from.push_back(&e);
      }
      for (const auto& n : names) {
        static const std::pair<std::vector<Entry>, std::vector<const Entry*>> kNone;
        const auto it = by_model.find(n);
        const auto& [of, from] = it == by_model.end() ? kNone : it->second;
        const BestPick p = PickBest(of);
        std::string text = "–";
        bool bold = false;
        if (p.index >= 0) {
          const Entry& e = of[static_cast<std::size_t>(p.index)];
          text = HasRendered(e) ? Psnr(e) + " · " + LumPct(e)
                                : "log " + Num(e.metrics.log_rmse);
          bold = from[static_cast<std::size_t>(p.index)] == b;
        }
        body_ += fmt::format("<td{}>{}</td>", bold ? " class=\"bestv\"" : "", text);
      }
      body_ += "</tr>\n";
    }
    body_ += "</table></div>\n<div class=\"charts\">\n";
    if (rendered) {
      Chart(PsnrSummaryChart("Best rendered PSNR per material and model", report_, palette_),
            "bar chart of the best rendered PSNR per material and model");
    } else {
      Chart(SummaryChart("Best log_rmse per material and model", report_, palette_),
            "bar chart of the best log_rmse per material and model");
    }
    body_ += "</div>\n</section>\n";
  }

  void Bench() {
    if (report_.bench.empty()) return;
    body_ += "<section id=\"bench\"><h2>Run time against error (bench)</h2>\n";
    body_ += "<p class=\"muted\">Each point is one fit: time from a loaded table to the fitted "
             "parameters against log_rmse on all valid cells inside the cut-off. Colour: model; "
             "marker: sample budget; dashed: the Pareto front (nothing is both faster and more "
             "accurate than a point on it).</p>\n<div class=\"charts\">\n";
    std::vector<std::string> mats;
    std::map<std::string, std::vector<BenchPoint>> of;  // per material, in one pass
    for (const auto& b : report_.bench) {
      auto& points = of[b.material];
      if (points.empty()) mats.push_back(b.material);
      points.push_back(b);
    }
    for (const auto& mat : mats) {
      Chart(ParetoChart("Run time against error: " + mat, BenchPoints(of[mat], mat), palette_),
            "scatter plot of run time against log_rmse for " + mat);
    }
    body_ +=
        "</div>\n<details><summary>All bench points</summary>\n<div class=\"scroll\"><table><tr>"
        "<th class=\"l\">material</th><th class=\"l\">model</th><th class=\"l\">loss</th>"
        "<th class=\"l\">budget</th><th class=\"l\">status</th><th>time (ms)</th>"
        "<th>PSNR (dB)</th><th>lum. err.</th>" +
        ErrorMetricHeaders() + "</tr>\n";
    for (const auto& b : report_.bench) {
      const RenderedError& re = b.metrics.rendered;
      body_ += fmt::format(
          "<tr{}><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td>"
          "<td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td>"
          "{}</tr>\n",
          b.status == "failed" ? " class=\"failed\"" : "", HtmlEscape(b.material),
          HtmlEscape(b.model), HtmlEscape(b.loss), HtmlEscape(b.budget), HtmlEscape(b.status),
          Num(b.time_ms, "{:.1f}"), re.ok ? fmt::format("{:.2f}", re.psnr_db) : "–",
          re.ok ? fmt::format("{:.1f} %", 100 * re.median_rel_error) : "–",
          ErrorMetricCells(b.metrics, [](double v) { return "<td>" + Num(v) + "</td>"; }));
    }
    body_ += "</table></div></details>\n</section>\n";
  }

  void MaterialSection(const Material& m) {
    body_ += fmt::format("<section id=\"m-{}\"><h2>{}</h2>\n", Slug(m.name), HtmlEscape(m.name));
    if (!m.source.empty()) {
      body_ += "<p class=\"muted\">Table <code>" + HtmlEscape(m.source) + "</code></p>\n";
    }
    for (const auto& n : m.notes) body_ += "<p class=\"note\">" + HtmlEscape(n) + "</p>\n";
    if (!m.entries.empty()) {
      MetricsTable(m);
      Views(m);
      ParamsTable(m);
    }
    body_ += "<div class=\"charts\">\n";
    if (!m.entries.empty()) {
      Chart(ParetoChart("Run time against error: " + m.name, EntryPoints(m), palette_),
            "scatter plot of fit time against log_rmse for " + m.name);
      const auto usable = static_cast<std::size_t>(
          std::count_if(m.entries.begin(), m.entries.end(), [](const Entry& e) { return Usable(e); }));
      const std::string of =
          usable > kMaxMetricBars ? fmt::format(" (the best {} of {})", kMaxMetricBars, usable) : "";
      const json regions = RegionPsnrChart("Rendered PSNR per region: " + m.name + of, m);
      if (!regions.is_null()) {
        Chart(regions, "bar chart of the rendered PSNR per region of " + m.name);
      }
      for (std::size_t k = 0; k < kNumErrorMetrics; ++k) {
        Chart(MetricsChart(fmt::format("{}: {}{}", kErrorMetrics[k].name, m.name, of), m, k),
              fmt::format("bar chart of {} of {}", kErrorMetrics[k].name, m.name));
      }
    }
    for (const Slice& s : m.slices) {
      Chart(SliceChart(fmt::format("{}: θd = {:.1f}°, φd = {:.1f}°", m.name, s.theta_d_deg,
                                   s.phi_d_deg),
                       s, palette_),
            fmt::format("theta_h slice at theta_d {:.1f} degrees", s.theta_d_deg));
    }
    body_ += "</div>\n";
    if (m.slices.empty()) {
      body_ += "<p class=\"note\">No θh slices for this material (its table was not "
               "available).</p>\n";
    } else {
      body_ += "<p class=\"muted\">θh slices: black points are the measured cells (cell "
               "centres of one θd and one φd bin); solid lines the fitted models, dashed lines "
               "the factorizations, evaluated at the same cell centres. Gaps: invalid cells or "
               "cells below the horizon.</p>\n";
    }
    body_ += "</section>\n";
  }

  void MetricsTable(const Material& m) {
    const BestPick pick = PickBest(m.entries);
    const int best = pick.index;
    // Rows best first: by the rule that picked the best (rendered score, or log_rmse when no
    // entry has a rendered error; entries without one after those with), failed and unscored last.
    const std::vector<std::size_t> order = RankEntries(m.entries);
    const auto front_v = ParetoFront(m.entries);
    const std::set<std::size_t> front(front_v.begin(), front_v.end());
    auto best_of = [&](auto get, bool rendered = false) {
      double b = NAN;
      for (const Entry& e : m.entries) {
        if (Usable(e) && (!rendered || HasRendered(e)) && !(b <= get(e))) b = get(e);
      }
      return b;
    };
    std::array<double, kNumErrorMetrics> best_error{};
    for (std::size_t k = 0; k < kNumErrorMetrics; ++k) {
      best_error[k] = best_of([k](const Entry& e) { return e.metrics.*kErrorMetrics[k].value; });
    }
    const double best_time = best_of([](const Entry& e) { return e.time_ms; });
    const double best_psnr = -best_of([](const Entry& e) { return -e.metrics.rendered.psnr_db; }, true);
    const double best_lum =
        best_of([](const Entry& e) { return e.metrics.rendered.median_rel_error; }, true);
    auto cell = [&](double v, double b, const char* spec = "{:.4g}") {
      return fmt::format("<td{}>{}</td>", std::isfinite(v) && v == b ? " class=\"bestv\"" : "",
                         Num(v, spec));
    };
    // Two tables of the same rows, so that each fits the page: accuracy, then cost.
    auto name_cell = [&](std::size_t i) {
      return fmt::format("<td class=\"l\">{}{}</td>", static_cast<int>(i) == best ? "★ " : "",
                         HtmlEscape(m.entries[i].name));
    };
    auto row_class = [&](std::size_t i) {
      return static_cast<int>(i) == best ? " class=\"best\""
             : m.entries[i].Failed()     ? " class=\"failed\""
                                         : "";
    };
    body_ +=
        "<div class=\"scroll\"><table><tr><th class=\"l\">approximation</th>"
        "<th>PSNR (dB)</th><th class=\"wrap\">median lum. err.</th>"
        "<th class=\"wrap\">front · side · rim · environment (dB)</th>" +
        ErrorMetricHeaders() +
        "<th class=\"l\">loss</th><th class=\"l\">budget</th><th class=\"l\">status</th></tr>\n";
    for (const std::size_t i : order) {
      const Entry& e = m.entries[i];
      const bool ok = Usable(e);
      const bool rendered = HasRendered(e);
      std::string status = HtmlEscape(e.status);
      if (!e.message.empty()) status += " <span class=\"muted\">(" + HtmlEscape(e.message) + ")</span>";
      const double psnr = rendered ? e.metrics.rendered.psnr_db : NAN;
      const double lum = rendered ? 100 * e.metrics.rendered.median_rel_error : NAN;
      body_ += fmt::format(
          "<tr{}>{}{}{}<td>{}</td>{}<td class=\"l\">{}</td><td class=\"l\">{}</td>"
          "<td class=\"status\">{}</td></tr>\n",
          row_class(i), name_cell(i), cell(psnr, best_psnr, "{:.2f}"),
          fmt::format("<td{}>{}</td>", rendered && lum == 100 * best_lum ? " class=\"bestv\"" : "",
                      rendered ? fmt::format("{:.1f} %", lum) : "–"),
          RegionsText(e),
          ErrorMetricCells(e.metrics,
                           [&, k = std::size_t{0}](double v) mutable {
                             return cell(ok ? v : NAN, best_error[k++]);
                           }),
          HtmlEscape(e.loss), HtmlEscape(e.budget), status);
    }
    body_ +=
        "</table></div>\n<div class=\"scroll\"><table><tr><th class=\"l\">approximation</th>"
        "<th>cells</th><th class=\"wrap\">memory · params</th><th class=\"wrap\">fetches / "
        "light</th><th class=\"wrap\">fetches / fragment</th><th>time (ms)</th>"
        "<th class=\"l\">stages (ms)</th><th>iter.</th><th>Pareto</th></tr>\n";
    for (const std::size_t i : order) {
      const Entry& e = m.entries[i];
      std::string stages;
      for (const auto& [name, ms] : e.times_ms) {
        stages += (stages.empty() ? "" : " · ") + fmt::format("{} {}", name, Num(ms, "{:.1f}"));
      }
      body_ += fmt::format(
          "<tr{}>{}<td>{}</td>{}{}<td class=\"stages\">{}</td><td>{}</td><td>{}</td></tr>\n",
          row_class(i), name_cell(i), e.metrics.cells, CostCells(e),
          cell(e.time_ms, Usable(e) ? best_time : NAN, "{:.1f}"), stages,
          e.kind == Entry::Kind::kFit ? std::to_string(e.iterations) : std::string("–"),
          front.count(i) ? "◆" : "");
    }
    std::string why;
    if (pick.by == BestBy::kChosen && !m.entries[static_cast<std::size_t>(best)].choice.empty()) {
      why = " (" + HtmlEscape(m.entries[static_cast<std::size_t>(best)].choice) + ")";
    }
    body_ += "</table></div>\n<p class=\"muted\">★ " + HtmlEscape(BestRule(pick.by)) + why +
             "; bold: best of each column; ◆ on the Pareto front of time against log_rmse. "
             "PSNR and lum. err.: the rendered-image metric (– : not computed); front, side, rim: "
             "its PSNR under light near the camera, from the side and from behind; environment: "
             "lit by a sky and a sun at once (docs/accuracy.md, \"Every light\", \"The "
             "environment\"). Time: from the "
             "loaded table to the result (fits: preparation, initializer and solve; "
             "factorizations: the whole solve). Memory: a factorization's float32 RGB textures "
             "and diffuse value; fetches: its texture reads per light, and per shaded fragment "
             "whatever the lights (docs/factorization.md); a fit's number of parameters instead.";
    const Entry* any = nullptr;
    for (const Entry& e : m.entries) {
      if (e.metrics.ok) any = any ? any : &e;
    }
    if (any) {
      body_ += fmt::format(" Metrics weighted by {}, cut-off {}°.", HtmlEscape(any->metrics.weighting),
                           Num(any->metrics.cutoff_deg));
    }
    body_ += "</p>\n";
  }

  // The best result rendered in the metric's scene beside the measured sphere, with the error map.
  void Views(const Material& m) {
    const MaterialViews& v = m.views;
    if (v.lights.empty()) {
      if (!v.missing.empty()) body_ += "<p class=\"note\">" + HtmlEscape(v.missing) + "</p>\n";
      return;
    }
    body_ += "<p class=\"muted\"><b>Renders</b> of <b>" + HtmlEscape(v.entry_key) +
             fmt::format(
                 "</b> (★) in the metric's scene: a sphere seen from above, one directional "
                 "light, {}² pixels (click to enlarge); exposure 1/Y₉₉ of the measured "
                 "images, clamped, sRGB (as the tone-mapped PSNR). PSNR and error are the "
                 "metric's, over its {}² images.</p>\n<div class=\"views\">\n",
                 v.resolution, v.metric_resolution);
    auto img = [](const std::string& png, const std::string& alt) {
      return fmt::format("<img alt=\"{}\" src=\"data:image/png;base64,{}\">", HtmlEscape(alt),
                         Base64(png));
    };
    for (const RenderedView& l : v.lights) {
      const std::string at = fmt::format("{:g}°", l.light_deg);
      body_ += "<div class=\"view\"><div class=\"cap\">" +
               fmt::format("light at {} from the view: PSNR {:.2f} dB, median lum. err. {:.1f} %",
                           at, l.psnr_db, 100 * l.median_rel_error) +
               "</div>" + img(l.measured_png, "measured, light " + at) +
               img(l.approx_png, "best fit, light " + at) +
               img(l.error_png, "relative luminance error, light " + at) +
               "<span>measured</span><span>fit</span><span>lum. error</span></div>\n";
    }
    body_ += "</div>\n";
    ErrorLegend();
  }

  // The error map's colour scale (report/rendered_colors.h): a CSS gradient through colours of
  // ErrorColor at the decades, where the scale is linear in log |s| between them.
  void ErrorLegend() {
    const double decades[] = {-1.0, -0.1, -0.01, 0.01, 0.1, 1.0};
    const double pos[] = {0, 25, 50, 50, 75, 100};
    std::string stops;
    for (int i = 0; i < 6; ++i) {
      stops += fmt::format("{}{} {}%", i ? ", " : "", HexColor(ErrorColor(decades[i])), pos[i]);
    }
    auto swatch = [](const Srgb& c) {
      return fmt::format("<span class=\"swatch\" style=\"background:{}\"></span>", HexColor(c));
    };
    body_ += "<div class=\"legend\"><span>lum. error (Y<sub>fit</sub> − Y<sub>meas</sub>) / "
             "Y<sub>meas</sub>:</span><span>fit darker</span><div><div class=\"bar\" style=\"background: "
             "linear-gradient(to right, " + stops + ")\"></div><div class=\"ticks\"><span>−100 %</span>"
             "<span>−10 %</span><span>±1 %</span><span>+10 %</span><span>≥ +100 %</span></div></div>"
             "<span>fit brighter</span><span>log scale, white ≤ 1 %, full colour ≥ 100 %;" +
             swatch(kViewBelowFloor) + "below the luminance floor" + swatch(kViewMasked) +
             "measurement masked" + swatch(kViewUnlit) + "unlit</span></div>\n";
  }

  void ParamsTable(const Material& m) {
    bool any = false;
    for (const Entry& e : m.entries) any = any || !e.params.empty();
    if (!any) return;
    body_ += "<details><summary>Parameters</summary>\n<table><tr><th class=\"l\">"
             "approximation</th><th class=\"l\">budget</th><th class=\"l\">parameters "
             "(<sup>b</sup>: on a bound)</th></tr>\n";
    for (const Entry& e : m.entries) {
      if (e.params.empty()) continue;
      std::string ps;
      for (std::size_t k = 0; k < e.params.size(); ++k) {
        const std::string name = k < e.param_names.size() ? e.param_names[k] : fmt::format("p{}", k);
        const bool bound = k < e.at_bound.size() && e.at_bound[k];
        ps += fmt::format("{}<code>{}</code> = {}{}", k ? ", " : "", HtmlEscape(name),
                          Num(e.params[k], "{:.5g}"), bound ? "<sup>b</sup>" : "");
      }
      body_ += fmt::format("<tr><td class=\"l\">{}</td><td class=\"l\">{}</td>"
                           "<td class=\"l\" style=\"white-space:normal\">{}</td></tr>\n",
                           HtmlEscape(e.name), HtmlEscape(e.budget), ps);
    }
    body_ += "</table></details>\n";
  }

  void Renders() {
    if (report_.renders.empty() && report_.materials.empty()) return;  // e.g. a bench page
    body_ += "<section id=\"renders\"><h2>Preview renders</h2>\n";
    if (report_.renders.empty()) {
      body_ += "<p class=\"note\">No renders were given (brdfit render writes them; pass the PNG "
               "files to brdfit report).</p>\n</section>\n";
      return;
    }
    body_ += "<div class=\"renders\">\n";
    for (const Render& r : report_.renders) {
      std::string png;
      if (!ReadBytes(r.png_path, &png) || png.size() < 8 || png.compare(1, 3, "PNG") != 0) {
        body_ += "<p class=\"note\">Render " + HtmlEscape(r.png_path) +
                 " could not be read as a PNG.</p>\n";
        continue;
      }
      body_ += fmt::format(
          "<figure><img alt=\"{}\" src=\"data:image/png;base64,{}\"><figcaption>{}</figcaption>"
          "</figure>\n",
          HtmlEscape(r.title), Base64(png), HtmlEscape(r.title));
    }
    body_ += "</div>\n</section>\n";
  }

  const Report& report_;
  Palette palette_;
  std::string body_;
  int charts_ = 0;
};

}  // namespace

std::string RenderHtml(const Report& report, const std::string& chart_js) {
  return Page(report).Build(chart_js);
}

void WriteHtmlReport(const fs::path& out, const Report& report, const fs::path& chart_js) {
  const std::string js = ReadChartJs(chart_js);
  WriteTextAtomically(out, RenderHtml(report, js));
}

}  // namespace brdfit::report
