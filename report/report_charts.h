// Chart.js 3 configurations (plain JSON, no callbacks) for the report's plots. The HTML writer
// (report/html_report.h) embeds each as a JSON script and Chart.js draws it; this file only decides
// what is plotted and how it is labelled.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report/report_model.h"

namespace brdfit::report {

// One colour per model (or factorization) name, stable across every chart of a report.
class Palette {
 public:
  explicit Palette(const Report& report);
  std::string Color(const std::string& name) const;  // "#rrggbb"

 private:
  std::map<std::string, std::string> colors_;
};

// Run time (ms, log x) against log_rmse (log y): one dataset per model x budget (colour from
// the model, point style from the budget), and the Pareto front as a line.
struct ParetoPoint {
  std::string model, budget, label;  // label: tooltip text
  double time_ms = 0, error = 0;
  bool usable = false;
};
nlohmann::json ParetoChart(const std::string& title, const std::vector<ParetoPoint>& points,
                           const Palette& palette, const std::string& error_name = "log_rmse");

// The points of a material's entries, and of bench points (optionally of one material only).
std::vector<ParetoPoint> EntryPoints(const Material& m);
std::vector<ParetoPoint> BenchPoints(const std::vector<BenchPoint>& bench,
                                     const std::string& material = "");

// θh (degrees, linear x) against f_r (log y): measured as points, fits as lines, factorizations
// as dashed lines.
nlohmann::json SliceChart(const std::string& title, const Slice& slice, const Palette& palette);

// One error metric (core/metrics.h kErrorMetrics[metric]) of the usable entries of a material,
// one bar each on that metric's own log axis: the first kMaxMetricBars by RankEntries. One chart
// per metric, since their ranges differ by orders of magnitude.
inline constexpr std::size_t kMaxMetricBars = 40;
nlohmann::json MetricsChart(const std::string& title, const Material& m, std::size_t metric);

// The rendered PSNR (dB, linear y) per region of the domain (core/rendered_regions.h) of the
// usable entries of a material that have a rendered error, grouped by entry: the first
// kMaxMetricBars by RankEntries. Regions no entry judged are left out; null when no entry has a
// rendered error.
nlohmann::json RegionPsnrChart(const std::string& title, const Material& m);

// Best log_rmse per material (x) and model (one dataset each), over the whole report.
nlohmann::json SummaryChart(const std::string& title, const Report& report, const Palette& palette);

// The rendered PSNR (dB, linear y) of each material's best entry per model, by report::PickBest
// among that model's entries; missing where no entry of the model has a rendered error.
nlohmann::json PsnrSummaryChart(const std::string& title, const Report& report,
                                const Palette& palette);

}  // namespace brdfit::report
