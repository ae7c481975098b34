// The in-memory form of a fit report as `brdfit report` and `brdfit compare` see it: per
// material, every approximation (model fit or factorization) with its metrics, parameters and
// times; θh slices of measured against approximated values; bench points (run time against
// error); preview renders. Plain data, filled by readers (report/report_inputs.h) and consumed by
// the HTML writer (report/html_report.h) and the comparison (report/compare.h).
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/factor_form.h"
#include "core/metrics.h"

namespace brdfit::report {

// A factorization's files, for its slices and renders (pipeline/factor_export.h writes them).
struct FactorRef {
  std::string material;
  std::string label;  // the entry's name, e.g. "factor:mccool"
  std::filesystem::path sidecar;
};

// One approximation of one material.
struct Entry {
  enum class Kind { kFit, kFactor };
  Kind kind = Kind::kFit;
  // Model ("lambert+ggx") or factorization: "factor:" and the label of its form
  // (core/factor_form.h): "factor:mccool", "factor:mccool+d r2".
  std::string name;
  // The name before a suffix told two entries with one key apart ("lambert+ggx" of
  // "lambert+ggx #2"); empty when it is the name.
  std::string base_name;
  std::string loss;    // fits: loss name ("log"); factorizations: "log (linear)", with
                       // " + rel (refined)" / " + logratio (refined)" when the refinement ran
  std::string budget;  // fits: "full", "stride:8", "random:N"; factorizations: "res 64"
  std::string status;  // "converged", "no_convergence", "failed" (core/result.h)
  std::string message;
  std::vector<std::string> param_names;
  std::vector<double> params;
  std::vector<bool> at_bound;
  int iterations = 0;
  FitMetrics metrics;  // core/metrics.h; ok false: not computed or not finite (see message)
  // Factorizations: what drawing it costs (texture memory, fetches per light and fragment;
  // core/factor_form.h), when the sidecar gives every texture's size. Fits have their
  // parameter count instead (params.size()).
  bool has_cost = false;
  FactorCost cost;
  // The fit `brdfit fit` recommended for its table (core/model_choice.h; fit reports and JSON
  // parameters), and why.
  bool chosen = false;
  std::string choice;
  // Named stage times in milliseconds, in display order ("init", "solve", ...).
  std::vector<std::pair<std::string, double>> times_ms;
  // The time a user pays to get this approximation from a loaded table (fits: prepare + init +
  // solve; factorizations: the whole solve), in milliseconds. The x axis of the Pareto plots.
  double time_ms = 0;

  bool Failed() const { return status == "failed"; }
  // The model or factorization, without a duplicate's suffix: what summaries group by.
  const std::string& Model() const { return base_name.empty() ? name : base_name; }
  // Identifies the entry within its material across reports: "name | loss | budget".
  std::string Key() const;
};

// Values along θh at fixed θd, φd (cell centres of one θd and one φd bin): the mean of the
// three channels of f_r in 1/sr; NaN where the cell is invalid or the value is not positive.
struct SliceSeries {
  std::string label;  // "measured", a model name, "factor:mccool"
  std::string role;   // "measured", "fitted" or "factored"
  std::vector<double> value;
};
struct Slice {
  double theta_d_deg = 0;
  double phi_d_deg = 0;
  std::vector<double> theta_h_deg;
  std::vector<SliceSeries> series;
};

// One light of the rendered-image metric's scene (fit/rendered_error.h, docs/accuracy.md) as
// images of a material's best approximation: the measured sphere, the approximation's, and the
// relative luminance error map, each an 8-bit PNG file's bytes (report/rendered_colors.h for
// the colours; made by pipeline/rendered_views.h).
struct RenderedView {
  double light_deg = 0;
  std::string measured_png, approx_png, error_png;
  double psnr_db = 0, median_rel_error = 0;  // of this light's image (RenderedLightError)
};
struct MaterialViews {
  std::string entry_key;  // Entry::Key() of the approximation drawn
  int resolution = 0;     // the pictures are N x N (pipeline/rendered_views.h)
  int metric_resolution = 0;  // of the metric's images, whose numbers the captions give
  double exposure = 0;    // 1 / Y99 of the measured images, as the tone-mapped PSNR
  std::vector<RenderedView> lights;
  std::string missing;  // why there are no images (empty when there are)
};

struct Material {
  std::string name;    // table stem, e.g. "red-plastic"
  std::string source;  // table path as recorded by the producer
  std::vector<Entry> entries;
  std::vector<Slice> slices;
  MaterialViews views;
  std::vector<std::string> notes;  // e.g. why the slices are missing
};

// One point of a run time against error sweep (brdfit bench; report/bench_csv.h).
struct BenchPoint {
  std::string material, table, model, loss, budget;
  std::string status;  // as Entry::status
  std::string message;
  double time_ms = 0;  // prepare + init + solve, as Entry::time_ms
  double prepare_ms = 0, init_ms = 0, solve_ms = 0;
  std::size_t fit_cells = 0;  // observations the fit used (the budget's effect)
  int iterations = 0;
  FitMetrics metrics;
};

struct Render {
  std::string title;
  std::string png_path;  // embedded as a data: URI when the HTML is written
};

struct Report {
  std::string title = "brdfit fit report";
  std::string metric_definition;   // how the metrics were computed (fit/metrics.h)
  std::vector<std::string> inputs;  // files the report was made from
  std::vector<Material> materials;
  std::vector<BenchPoint> bench;
  std::vector<Render> renders;
  std::vector<std::string> notes;

  Material* FindMaterial(const std::string& name);
  const Material* FindMaterial(const std::string& name) const;
  Material& GetOrAddMaterial(const std::string& name);
};

// A point that may lie on a Pareto front: cost (time) and error, both to be minimized.
struct CostError {
  double cost = 0, error = 0;
  bool usable = false;  // failed or without metrics: never on the front
};

// Indices of the usable points that no other usable point dominates (<= in both and < in one),
// sorted by cost. Equal points are all kept.
std::vector<std::size_t> ParetoFront(const std::vector<CostError>& points);
// Front of (time_ms, log_rmse) over the entries that did not fail and have metrics.
std::vector<std::size_t> ParetoFront(const std::vector<Entry>& entries);

// How a material's best approximation is chosen. kChosen: the usable entry the fit report marks
// as chosen (core/model_choice.h; of several, the highest RenderedScore); else kRendered: the
// highest RenderedScore among the usable entries whose rendered-image error is ok; kLogRmse:
// only when no entry has one (e.g. a report written before the metric), the lowest log_rmse.
enum class BestBy { kNone, kChosen, kRendered, kLogRmse };
struct BestPick {
  int index = -1;  // into the entries; -1: no usable entry
  BestBy by = BestBy::kNone;
};
// psnr_db - 20 median_rel_error (dB; a 5 % median luminance error costs 1 dB): the score S of
// core/model_choice.h and of docs/accuracy.md's loss and model study.
double RenderedScore(const RenderedError& r);
BestPick PickBest(const std::vector<Entry>& entries);
// One sentence saying how the best was chosen, for pages and listings.
std::string BestRule(BestBy by);
// PickBest(entries).index.
int BestEntry(const std::vector<Entry>& entries);
// Indices of the entries, best first by the rule of PickBest's kRendered and kLogRmse: usable
// entries with a rendered error by descending RenderedScore, then the other usable ones by
// ascending log_rmse, then failed or unscored ones; ties keep the entries' order. (The pick
// itself may differ: a chosen entry.) The metrics table's row order, and what the report draws
// when it draws only a material's first few results.
std::vector<std::size_t> RankEntries(const std::vector<Entry>& entries);

// A report as its inputs give it (report/report_inputs.h ReadReportInputs): the report, and
// the files beside it that its slices and renders need.
struct ReportSources {
  Report report;
  std::map<std::string, std::filesystem::path> tables;  // material -> table, for slices
  std::vector<FactorRef> factors;                       // for slices (pipeline/factor_export.h)
  // Tables the results name but that are not there to load (missing, a device, a folder):
  // material -> the path named. The caller says so; a material in `tables` is not here.
  std::map<std::string, std::filesystem::path> unloadable_tables;
};

}  // namespace brdfit::report
