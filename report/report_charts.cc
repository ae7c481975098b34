#include "report/report_charts.h"

#include "core/rendered_regions.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace brdfit::report {

using nlohmann::json;

namespace {

// Tableau 10 (Tableau Software, 2016), then darker variants for larger reports.
constexpr const char* kColors[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                   "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac",
                                   "#2f4b7c", "#a05195", "#d45087", "#665191", "#003f5c"};
constexpr const char* kPointStyles[] = {"circle", "triangle", "rect",  "rectRot",
                                        "star",   "crossRot", "cross", "rectRounded"};

json Value(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json Axis(const std::string& type, const std::string& title) {
  return {{"type", type}, {"title", {{"display", true}, {"text", title}}}};
}

json BaseOptions(const std::string& title) {
  return {{"animation", false},
          {"responsive", true},
          {"maintainAspectRatio", false},
          {"plugins",
           {{"title", {{"display", true}, {"text", title}}},
            {"legend", {{"position", "bottom"}, {"labels", {{"usePointStyle", true}}}}}}}};
}

}  // namespace

Palette::Palette(const Report& report) {
  std::size_t next = 0;
  auto add = [&](const std::string& name) {
    if (colors_.count(name)) return;
    colors_[name] = kColors[next++ % std::size(kColors)];
  };
  for (const Material& m : report.materials) {
    for (const Entry& e : m.entries) add(e.Model());
  }
  for (const BenchPoint& b : report.bench) add(b.model);
}

std::string Palette::Color(const std::string& name) const {
  const auto it = colors_.find(name);
  return it == colors_.end() ? "#555555" : it->second;
}

std::vector<ParetoPoint> EntryPoints(const Material& m) {
  std::vector<ParetoPoint> points;
  for (const Entry& e : m.entries) {
    ParetoPoint p;
    p.model = e.Model();
    p.budget = e.budget;
    p.time_ms = e.time_ms;
    p.error = e.metrics.log_rmse;
    p.usable = !e.Failed() && e.metrics.ok && e.time_ms > 0;
    p.label = fmt::format("{} ({}, loss {}): {:.4g} ms, log_rmse {:.4g}", e.name, e.budget, e.loss,
                          e.time_ms, e.metrics.log_rmse);
    points.push_back(std::move(p));
  }
  return points;
}

std::vector<ParetoPoint> BenchPoints(const std::vector<BenchPoint>& bench,
                                     const std::string& material) {
  std::vector<ParetoPoint> points;
  for (const BenchPoint& b : bench) {
    if (!material.empty() && b.material != material) continue;
    ParetoPoint p;
    p.model = b.model;
    p.budget = b.budget;
    p.time_ms = b.time_ms;
    p.error = b.metrics.log_rmse;
    p.usable = b.status != "failed" && b.metrics.ok && b.time_ms > 0;
    p.label = fmt::format("{} {} ({}, loss {}): {:.4g} ms, log_rmse {:.4g}", b.material, b.model,
                          b.budget, b.loss, b.time_ms, b.metrics.log_rmse);
    points.push_back(std::move(p));
  }
  return points;
}

json ParetoChart(const std::string& title, const std::vector<ParetoPoint>& points,
                 const Palette& palette, const std::string& error_name) {
  std::map<std::string, std::size_t> budgets;  // budget -> order of first appearance
  for (const auto& p : points) budgets.emplace(p.budget, budgets.size());
  auto style = [&](const std::string& budget) {
    return kPointStyles[budgets.at(budget) % std::size(kPointStyles)];
  };
  json datasets = json::array();
  std::map<std::string, std::size_t> index;  // "model\nbudget" -> dataset
  std::vector<CostError> ce;
  for (const auto& p : points) {
    ce.push_back({p.time_ms, p.error, p.usable});
    if (!p.usable) continue;
    const std::string key = p.model + "\n" + p.budget;
    if (!index.count(key)) {
      index[key] = datasets.size();
      const std::string color = palette.Color(p.model);
      datasets.push_back({{"label", p.model + " · " + p.budget},
                          {"data", json::array()},
                          {"backgroundColor", color},
                          {"borderColor", color},
                          {"pointStyle", style(p.budget)},
                          {"pointRadius", 6},
                          {"pointHoverRadius", 8}});
    }
    datasets[index[key]]["data"].push_back(
        {{"x", p.time_ms}, {"y", p.error}, {"label", p.label}});
  }
  json front = json::array();
  for (const std::size_t i : ParetoFront(ce)) {
    front.push_back({{"x", points[i].time_ms}, {"y", points[i].error}, {"label", points[i].label}});
  }
  datasets.push_back({{"label", "Pareto front"},
                      {"data", front},
                      {"showLine", true},
                      {"borderColor", "#333333"},
                      {"backgroundColor", "#333333"},
                      {"borderDash", {5, 4}},
                      {"borderWidth", 1},
                      {"pointRadius", 0},
                      {"pointStyle", "line"}});
  json options = BaseOptions(title);
  options["scales"] = {{"x", Axis("logarithmic", "time (ms, log scale)")},
                       {"y", Axis("logarithmic", error_name + " (log scale; lower is better)")}};
  // Log axes end at the extreme data values: pad them so that no marker sits on an edge.
  double x0 = INFINITY, x1 = 0, y0 = INFINITY, y1 = 0;
  for (const auto& p : points) {
    if (!p.usable || !(p.time_ms > 0) || !(p.error > 0)) continue;
    x0 = std::min(x0, p.time_ms), x1 = std::max(x1, p.time_ms);
    y0 = std::min(y0, p.error), y1 = std::max(y1, p.error);
  }
  // A margin of 6 % of the decades spanned, at least a factor 1.5.
  auto pad = [](double lo, double hi) { return std::pow(10.0, std::max(0.176, 0.06 * std::log10(hi / lo))); };
  if (x1 > 0 && y1 > 0) {
    const double px = pad(x0, x1), py = pad(y0, y1);
    options["scales"]["x"]["min"] = x0 / px;
    options["scales"]["x"]["max"] = x1 * px;
    options["scales"]["y"]["min"] = y0 / py;
    options["scales"]["y"]["max"] = y1 * py;
  }
  return {{"type", "scatter"}, {"data", {{"datasets", datasets}}}, {"options", options}};
}

json SliceChart(const std::string& title, const Slice& slice, const Palette& palette) {
  json datasets = json::array();
  for (const SliceSeries& s : slice.series) {
    json data = json::array();
    for (std::size_t i = 0; i < s.value.size() && i < slice.theta_h_deg.size(); ++i) {
      data.push_back({{"x", slice.theta_h_deg[i]}, {"y", Value(s.value[i])}});
    }
    json d = {{"label", s.label}, {"data", data}, {"spanGaps", false}};
    if (s.role == "measured") {
      d.update({{"showLine", false},
                {"pointRadius", 2.5},
                {"backgroundColor", "#000000"},
                {"borderColor", "#000000"},
                {"pointStyle", "circle"}});
    } else {
      const std::string color = palette.Color(s.label);
      d.update({{"showLine", true},
                {"pointRadius", 0},
                {"borderWidth", 2},
                {"borderColor", color},
                {"backgroundColor", color},
                {"pointStyle", "line"}});
      if (s.role == "factored") d["borderDash"] = {6, 3};
    }
    datasets.push_back(std::move(d));
  }
  json options = BaseOptions(title);
  options["scales"] = {{"x", Axis("linear", "θh (degrees)")},
                       {"y", Axis("logarithmic", "f_r, mean of R, G, B (1/sr, log scale)")}};
  options["scales"]["x"]["min"] = 0;
  options["scales"]["x"]["max"] = 90;
  return {{"type", "scatter"}, {"data", {{"datasets", datasets}}}, {"options", options}};
}

json MetricsChart(const std::string& title, const Material& m, std::size_t metric) {
  const ErrorMetricField& field = kErrorMetrics[metric];
  json labels = json::array();
  json data = json::array();
  std::size_t drawn = 0;
  for (const std::size_t i : RankEntries(m.entries)) {
    const Entry& e = m.entries[i];
    if (e.Failed() || !e.metrics.ok) continue;
    if (drawn++ == kMaxMetricBars) break;
    labels.push_back(e.name + " (" + e.budget + ")");
    data.push_back(Value(e.metrics.*field.value));
  }
  // Tableau 10's colours, one per error metric (core/metrics.h kErrorMetrics).
  static constexpr const char* kMetricColors[] = {"#4e79a7", "#f28e2b", "#59a14f",
                                                  "#e15759", "#76b7b2", "#edc948"};
  json datasets = json::array();
  datasets.push_back({{"label", field.name},
                      {"data", std::move(data)},
                      {"backgroundColor", kMetricColors[metric % std::size(kMetricColors)]}});
  json options = BaseOptions(title);
  const std::string unit = *field.unit ? std::string(" (") + field.unit + ")" : "";
  options["scales"] = {
      {"y", Axis("logarithmic", std::string(field.name) + unit + ", log scale; lower is better")}};
  options["plugins"]["legend"]["display"] = false;
  return {{"type", "bar"},
          {"data", {{"labels", labels}, {"datasets", datasets}}},
          {"options", options}};
}

json RegionPsnrChart(const std::string& title, const Material& m) {
  json labels = json::array();
  std::array<json, kLightRegions> data;
  data.fill(json::array());
  std::array<bool, kLightRegions> judged{};
  std::size_t drawn = 0;
  for (const std::size_t i : RankEntries(m.entries)) {
    const Entry& e = m.entries[i];
    if (e.Failed() || !e.metrics.ok || !e.metrics.rendered.ok) continue;
    if (drawn++ == kMaxMetricBars) break;
    labels.push_back(e.name + " (" + e.budget + ")");
    const auto regions = RenderedRegions(e.metrics.rendered);
    for (int r = 0; r < kLightRegions; ++r) {
      judged[r] = judged[r] || regions[r].lights > 0;
      data[r].push_back(regions[r].lights > 0 ? Value(regions[r].psnr_db) : json(nullptr));
    }
  }
  if (drawn == 0) return nullptr;
  // The regions' colours: warm to cool from the light near the camera to the one behind.
  static constexpr const char* kRegionColors[kLightRegions] = {"#f28e2b", "#59a14f", "#4e79a7",
                                                               "#b07aa1"};
  json datasets = json::array();
  for (int r = 0; r < kLightRegions; ++r) {
    if (!judged[r]) continue;
    datasets.push_back({{"label", RegionName(static_cast<LightRegion>(r))},
                        {"data", std::move(data[r])},
                        {"backgroundColor", kRegionColors[r]}});
  }
  json options = BaseOptions(title);
  options["scales"] = {{"y", Axis("linear", "rendered PSNR (dB; higher is better)")}};
  return {{"type", "bar"},
          {"data", {{"labels", labels}, {"datasets", datasets}}},
          {"options", options}};
}

namespace {

// One bar per (material, model): value(entries of that model in that material), NaN for none.
// Entries are grouped in one pass per material (Entry::Model()), not once per model.
json PerModelBars(const std::string& title, const Report& report, const Palette& palette,
                  const std::function<double(const std::vector<Entry>&)>& value,
                  const json& y_axis) {
  std::vector<std::string> models;
  std::map<std::string, std::size_t> model_index;
  std::vector<std::vector<double>> values;  // [model][material]
  for (std::size_t mi = 0; mi < report.materials.size(); ++mi) {
    std::map<std::string, std::vector<Entry>> of;
    for (const Entry& e : report.materials[mi].entries) {
      of[e.Model()].push_back(e);
      if (model_index.emplace(e.Model(), models.size()).second) {
        models.push_back(e.Model());
        values.emplace_back(report.materials.size(), NAN);
      }
    }
    for (const auto& [model, entries] : of) values[model_index.at(model)][mi] = value(entries);
  }
  json labels = json::array();
  for (const Material& m : report.materials) labels.push_back(m.name);
  json datasets = json::array();
  for (std::size_t k = 0; k < models.size(); ++k) {
    const std::string& model = models[k];
    json data = json::array();
    for (const double v : values[k]) data.push_back(Value(v));
    datasets.push_back(
        {{"label", model}, {"data", data}, {"backgroundColor", palette.Color(model)}});
  }
  json options = BaseOptions(title);
  options["scales"] = {{"y", y_axis}};
  return {{"type", "bar"}, {"data", {{"labels", labels}, {"datasets", datasets}}},
          {"options", options}};
}

}  // namespace

json SummaryChart(const std::string& title, const Report& report, const Palette& palette) {
  return PerModelBars(
      title, report, palette,
      [](const std::vector<Entry>& of) {
        double best = NAN;
        for (const Entry& e : of) {
          if (e.Failed() || !e.metrics.ok) continue;
          if (!(best <= e.metrics.log_rmse)) best = e.metrics.log_rmse;
        }
        return best;
      },
      Axis("logarithmic", "best log_rmse (log scale; lower is better)"));
}

json PsnrSummaryChart(const std::string& title, const Report& report, const Palette& palette) {
  return PerModelBars(
      title, report, palette,
      [](const std::vector<Entry>& of) {
        const BestPick p = PickBest(of);
        // The chosen fit is picked by the rendered score too (core/model_choice.h).
        const bool has = p.index >= 0 &&
                         (p.by == BestBy::kRendered || p.by == BestBy::kChosen) &&
                         of[static_cast<std::size_t>(p.index)].metrics.rendered.ok;
        return has ? of[static_cast<std::size_t>(p.index)].metrics.rendered.psnr_db : NAN;
      },
      Axis("linear", "rendered PSNR of the best fit (dB; higher is better)"));
}

}  // namespace brdfit::report
