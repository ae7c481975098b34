// `brdfit report RESULTS... -o report.html`: one self-contained HTML page from fit reports,
// factorizations, bench CSVs, renders and tables (report/report_inputs.h, report/html_report.h), with
// θh slices of every material whose table is at hand. Also the demo's last step (order 90).
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/progress.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "fit/metrics.h"
#include "io/atomic_file.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "pipeline/factor_export.h"
#include "pipeline/inputs.h"
#include "pipeline/rendered_views.h"
#include "report/html_report.h"
#include "report/report_inputs.h"
#include "report/report_slices.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;
using report::Entry;

struct ReportCliOptions {
  std::vector<std::string> inputs;
  std::string out = "report.html";
  std::string title;
  std::vector<double> theta_d = report::DefaultSliceThetaD();
  double phi_d = 90;
  bool no_slices = false;
  std::vector<double> render_lights = pipeline::DefaultViewLights();
  bool no_renders = false;
  std::string chart_js;
  bool keep_going = false;
  bool quiet = false;
};

// What could not be read. Without --keep-going the first problem ends the run (exit 2, nothing
// written); with it, each becomes a note on the page and an error on stderr, and the run exits
// 2 after writing the page.
class Problems {
 public:
  explicit Problems(bool keep_going) : keep_going_(keep_going) {}
  // Throws e unless keep-going; else records it and returns its text for a note.
  std::string Add(const InputError& e) {
    if (!keep_going_) throw e;
    all_.push_back(e.what());
    return e.what();
  }
  std::vector<std::string>* Sink() { return keep_going_ ? &all_ : nullptr; }
  const std::vector<std::string>& All() const { return all_; }

 private:
  bool keep_going_;
  std::vector<std::string> all_;
};

// Slices of one material: its table against its best results (the pick, then by
// report::RankEntries), at most kMaxSliceResults of them: a material with thousands of fits
// would otherwise draw thousands of lines per slice.
constexpr std::size_t kMaxSliceResults = 8;

void AddSlices(const report::ReportSources& src, const ReportCliOptions& o, const Table& table,
               report::Material* m) {
  std::map<std::string, int> uses;  // entries per name: a shared name gets budget and loss
  for (const Entry& e : m->entries) ++uses[e.name];
  std::vector<std::size_t> order = report::RankEntries(m->entries);
  const int best = report::BestEntry(m->entries);
  if (best >= 0) {
    std::stable_partition(order.begin(), order.end(),
                          [&](std::size_t i) { return static_cast<int>(i) == best; });
  }
  std::vector<report::NamedPredictor> predictors;
  std::size_t drawable = 0;
  for (const std::size_t i : order) {
    const Entry& e = m->entries[i];
    if (e.Failed() || (e.kind == Entry::Kind::kFit && e.params.empty())) continue;
    if (++drawable > kMaxSliceResults) continue;  // counted for the note, not drawn
    try {
      if (e.kind == Entry::Kind::kFit) {
        const std::string label =
            uses[e.name] > 1 ? e.name + " (" + e.budget + ", " + e.loss + ")" : e.name;
        predictors.push_back({label, "fitted", report::ModelPredictor(e.Model(), e.params)});
        continue;
      }
      const auto f = std::find_if(src.factors.begin(), src.factors.end(), [&](const auto& r) {
        return r.material == m->name && r.label == e.name;
      });
      if (f == src.factors.end()) continue;
      auto brdf = std::make_shared<FactoredBrdf>(LoadFactoredBrdf(f->sidecar));
      predictors.push_back(
          {f->label, "factored", [brdf](const HalfDiffAngles& a) { return brdf->Eval(a); }});
    } catch (const InputError& err) {
      m->notes.push_back(fmt::format("{}: not drawn in the slices: {}", e.name, err.what()));
    }
  }
  if (drawable > kMaxSliceResults) {
    m->notes.push_back(fmt::format(
        "The θh slices draw the best {} of this material's {} results (the ★ one first, then "
        "in the table's order).",
        kMaxSliceResults, drawable));
  }
  m->slices = report::ComputeThetaHSlices(table, o.theta_d, o.phi_d, predictors);
}

void CheckOptions(const ReportCliOptions& o) {
  for (const double td : o.theta_d) {
    if (!(td >= 0 && td < 90)) throw InputError(fmt::format("--theta-d {} outside [0, 90)", td));
  }
  if (!(o.phi_d >= 0 && o.phi_d < 180)) {
    throw InputError(fmt::format("--phi-d {} outside [0, 180)", o.phi_d));
  }
  if (!o.no_renders) pipeline::CheckViewLights(o.render_lights);
  if (fs::is_directory(o.out)) throw InputError(o.out, "is a folder; give the HTML file name");
}

int RunReport(const ReportCliOptions& o) {
  CheckOptions(o);
  const fs::path chart_js = o.chart_js.empty() ? report::ChartJsPath() : fs::path(o.chart_js);
  const std::vector<std::string> given = pipeline::ExpandInputs(o.inputs);  // nbrdf:all
  std::vector<fs::path> read = pipeline::InputFiles(given);
  read.push_back(chart_js);
  CheckOutputs(read, {{o.out, "-o"}});
  const std::string js = report::ReadChartJs(chart_js);  // fail before any work
  std::vector<fs::path> inputs(given.begin(), given.end());
  Problems problems(o.keep_going);
  report::ReportSources src = report::ReadReportInputs(inputs, problems.Sink());
  report::Report& r = src.report;
  for (const std::string& p : problems.All()) r.notes.push_back("Left out (unreadable): " + p);
  if (!o.title.empty()) r.title = o.title;
  r.metric_definition = MetricsDefinition();
  if (r.materials.empty() && r.bench.empty() && r.renders.empty()) {
    throw InputError(
        "nothing to report: no fit report, factorization, bench CSV, render or table "
        "among the inputs");
  }
  if (!o.no_slices || !o.no_renders) {
    Progress bar(r.materials.size(), "slices and renders", !o.quiet);
    for (report::Material& m : r.materials) {
      bar.Step(m.name);
      const auto t = src.tables.find(m.name);
      if (t == src.tables.end()) {
        std::string why =
            "the table of this material was not given and the results do not name "
            "a readable one";
        if (const auto u = src.unloadable_tables.find(m.name); u != src.unloadable_tables.end()) {
          std::error_code ec;
          if (fs::exists(u->second, ec)) {
            // A device, a folder, a socket where a table should be: bad input, like a damaged one.
            why = problems.Add(InputError(u->second, "named as the table of material '" + m.name +
                                                         "' but not a regular file"));
          } else {
            // Results moved without their tables still report their numbers; said, not silent.
            why = "its table " + u->second.string() + " (named by the results) is missing";
            if (!o.quiet) {
              fmt::print(stderr, "brdfit: warning: material '{}': {}: no slices or renders\n",
                         TerminalSafe(m.name), TerminalSafe(why));
            }
          }
        }
        if (!o.no_slices) m.notes.push_back(fmt::format("No θh slices: {}.", why));
        if (!o.no_renders) m.views.missing = fmt::format("No renders: {}.", why);
        continue;
      }
      // A table that is there but cannot be read is an error, not a note.
      Table table;
      try {
        table = pipeline::LoadInput(t->second);
      } catch (const InputError& e) {
        const std::string why = problems.Add(e);
        if (!o.no_slices) m.notes.push_back(fmt::format("No θh slices: {}", why));
        if (!o.no_renders) m.views.missing = fmt::format("No renders: {}", why);
        continue;
      }
      if (!o.no_slices) {
        try {
          AddSlices(src, o, table, &m);
        } catch (const InputError& e) {
          m.notes.push_back(fmt::format("No θh slices: {}", problems.Add(e)));
        }
      }
      if (!o.no_renders) {
        try {
          m.views = pipeline::RenderMaterialViews(table, m, src.factors, o.render_lights);
        } catch (const InputError& e) {
          m.views.missing = fmt::format("No renders: {}", problems.Add(e));
        }
      }
    }
  }
  const std::string html = report::RenderHtml(r, js);
  WriteTextAtomically(o.out, html);
  if (!o.quiet) {
    std::size_t entries = 0, views = 0;
    for (const auto& m : r.materials) {
      entries += m.entries.size();
      views += m.views.lights.size();
    }
    // The sphere renders of the metric's scene, and the PNG renders given as inputs.
    fmt::print(
        "wrote {} ({} materials, {} results, {} bench points, {} sphere renders, {} "
        "renders given)\n",
        fs::absolute(o.out).string(), r.materials.size(), entries, r.bench.size(), views,
        r.renders.size());
  }
  if (!problems.All().empty()) {
    for (const std::string& p : problems.All()) {
      fmt::print(stderr, "brdfit: error: {}\n", TerminalSafe(p));
    }
    fmt::print(stderr, "brdfit: {} problem{} noted in {} (--keep-going)\n", problems.All().size(),
               problems.All().size() == 1 ? "" : "s", o.out);
    return kExitBadInput;
  }
  return kExitOk;
}

Registrar reg{
    "report", "One self-contained HTML page of metrics, Pareto plots, slices and renders",
    [](CLI::App& sub) {
      auto o = std::make_shared<ReportCliOptions>();
      sub.add_option("results", o->inputs,
                     "fit reports, .factor.json sidecars, bench .csv, .png renders, tables "
                     "(files or nbrdf:NAME), or folders holding them")
          ->required();
      sub.add_option("-o,--out", o->out, "output HTML file")->capture_default_str();
      sub.add_option("--title", o->title, "page title");
      sub.add_option("--theta-d", o->theta_d,
                     "theta_d of the slices in degrees (each snaps to its bin's centre)")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_option("--phi-d", o->phi_d, "phi_d of the slices in degrees")->capture_default_str();
      sub.add_flag("--no-slices", o->no_slices, "skip the theta_h slices");
      sub.add_option("--render-lights", o->render_lights,
                     "lights of the renders beside each material, degrees from the view (among "
                     "the rendered-image metric's 0,30,45,60,70,80)")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_flag("--no-renders", o->no_renders,
                   "skip the renders (with --no-slices: no table is read)");
      sub.add_option("--chart-js", o->chart_js,
                     "Chart.js to inline (default $BRDFIT_CHART_JS or "
                     "/usr/share/javascript/chart.js/chart.min.js)");
      sub.add_flag("--keep-going", o->keep_going,
                   "write the page despite unreadable inputs or tables (each noted on it and "
                   "printed), then exit 2");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line, no progress bar");
      sub.footer(
          "The page needs no network: Chart.js (Debian's libjs-chart.js) and the renders are "
          "inlined.\nSlices and renders need each material's table: the one a result names, or give "
          "it.\nBest result per material: highest min(PSNR, 60 dB) - 20 x median luminance error of the "
          "rendered-image\nmetric; lowest log_rmse when no result has it (docs/accuracy.md).\n"
          "Exit codes: 0 written, 2 bad input (a file missing, unreadable, damaged or of no known "
          "kind: nothing written; with --keep-going the page is written, then exit 2).\n"
          "Examples:\n"
          "  brdfit report fits.h5 -o report.html\n"
          "  brdfit report fits.h5 factor/*.factor.json bench.csv compare.png -o report.html\n"
          "  brdfit report demo-out/ demo-out/factor -o report.html --theta-d 0,20,45,70\n"
          "  brdfit report gold.h5 nbrdf:gold-metallic-paint -o report.html");
      return [o] { return RunReport(*o); };
    }};

// Demo step 90: everything the demo wrote, in one page.
int DemoReport(DemoContext& ctx) {
  ReportCliOptions o;
  for (const auto& p : ctx.outputs) {
    const std::string name = p.filename().string();
    const bool factor = name.size() > 12 && name.ends_with(".factor.json");
    const bool table = std::find(ctx.tables.begin(), ctx.tables.end(), p) != ctx.tables.end();
    const bool fits = p.extension() == ".h5" && !table;  // the fit step's report
    const bool known = factor || fits || p.extension() == ".csv" || p.extension() == ".png";
    if (known) o.inputs.push_back(p.string());
  }
  for (const auto& t : ctx.tables) o.inputs.push_back(t.string());
  o.out = (ctx.out_dir / "report.html").string();
  o.title = "brdfit demo report";
  o.quiet = true;
  const int code = RunReport(o);
  if (code == kExitOk) {
    ctx.outputs.push_back(o.out);
    ctx.report = o.out;
    fmt::print("report: {}\n", fs::absolute(o.out).string());
  }
  return code;
}

DemoStepRegistrar demo_step{90, "report", DemoReport};

}  // namespace
}  // namespace brdfit::cli
