// Comparing two reports (report/report_model.h) entry by entry: for each material and each
// approximation (name | loss | budget), the metric deltas, and whether the change is a
// regression beyond a threshold. `brdfit compare` prints it and gates CI with its exit code.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "report/report_model.h"

namespace brdfit::report {

// The deciding metric: an index into core/metrics.h kErrorMetrics.
// The index of the error metric called `name`; InputError listing the names when none is.
std::size_t ErrorMetricIndex(const std::string& name);

struct CompareOptions {
  std::size_t metric = kPrimaryErrorMetric;  // the metric that decides (kErrorMetrics)
  // A change is a regression when new > old * (1 + threshold) and new - old > abs_floor
  // (the floor keeps round-off on near-perfect fits from failing CI).
  double threshold = 0.05;
  double abs_floor = 1e-6;
  // > 0: time_ms growing by more than this fraction (and by more than time_floor_ms) is also a
  // regression. Off by default: timings are noisy across machines.
  double time_threshold = 0;
  double time_floor_ms = 5;
  bool missing_is_regression = true;  // an entry of the old report absent from the new one
  // The rendered-image metric (docs/accuracy.md), judged whenever both entries have it: a PSNR
  // drop of more than psnr_drop_db, or a median relative luminance error growing by more than
  // lum_rise_points percentage points (0.02 as a fraction), is a regression too. 0.5 dB is a
  // few times the run-to-run spread of the metric's scene choices (resolution, lights: ±0.1 dB
  // at 128², docs/accuracy.md); 2 points a tenth of a typical good fit's 10-20 %.
  bool judge_rendered = true;
  double psnr_drop_db = 0.5;
  double lum_rise_points = 2.0;
};

enum class Change {
  kSame,        // within the threshold
  kBetter,      // metric dropped by more than the threshold
  kWorse,       // metric grew beyond the threshold: a regression
  kWorseRendered,  // metric within its threshold or better, rendered error worse: a regression
  kSlower,      // time grew beyond time_threshold: a regression
  kNowFails,    // usable before, failed (or unscored) now: a regression
  kFixed,       // failed before, usable now
  kStillFails,  // failed in both
  kMissing,     // only in the old report (a regression if missing_is_regression)
  kAdded,       // only in the new report
};
inline constexpr auto kChangeNames =
    MakeEnumNames<Change>("change", {{Change::kSame, "same"},
                                     {Change::kBetter, "better"},
                                     {Change::kWorse, "worse"},
                                     {Change::kWorseRendered, "worse-rendered"},
                                     {Change::kSlower, "slower"},
                                     {Change::kNowFails, "now-fails"},
                                     {Change::kFixed, "fixed"},
                                     {Change::kStillFails, "still-fails"},
                                     {Change::kMissing, "missing"},
                                     {Change::kAdded, "added"}});
constexpr const auto& EnumNamesOf(Change) {
  return kChangeNames;
}

struct EntryDelta {
  std::string material, name, loss, budget;
  Change change = Change::kSame;
  bool regression = false;
  std::string status_old, status_new;
  double old_value = 0, new_value = 0;  // the deciding metric (NaN when absent or unusable)
  double rel_change = 0;                // (new - old) / old; NaN when undefined
  FitMetrics old_metrics, new_metrics;
  double old_time_ms = 0, new_time_ms = 0;
  // Rendered-image metric of each side (NaN where the entry has none or is unusable), and the
  // changes when both have it (NaN otherwise): dB, and percentage points of the median
  // relative luminance error.
  double old_psnr_db = 0, new_psnr_db = 0, old_lum = 0, new_lum = 0;
  double psnr_change_db = 0, lum_change_points = 0;
  // The region of the domain whose PSNR fell most (core/rendered_regions.h; empty when no
  // region is judged on both sides) and by how much, dB (positive: worse).
  std::string worst_region;
  double region_drop_db = 0;
  // Beyond psnr_drop_db (pooled, or in any region) or lum_rise_points.
  bool rendered_regression = false;
  // Factorizations: what each side costs to draw (Entry::cost; has_cost false where unknown or
  // absent). Never a regression: a cost is a choice, shown beside the metrics.
  bool factor = false;
  bool old_has_cost = false, new_has_cost = false;
  FactorCost old_cost, new_cost;
};

struct Comparison {
  CompareOptions options;
  std::vector<EntryDelta> deltas;  // in the old report's order, then additions
  std::vector<std::string> regressed_materials;  // materials with at least one regression
  std::vector<std::string> missing_materials;    // in the old report only
  std::vector<std::string> added_materials;      // in the new report only

  int Count(Change c) const;
  int Regressions() const;
  bool Regressed() const { return Regressions() > 0; }
};

Comparison Compare(const Report& old_report, const Report& new_report,
                   const CompareOptions& options = {});

nlohmann::ordered_json ComparisonToJson(const Comparison& c);
// Human-readable: one line per material and changed entry, then a summary. With all = true,
// unchanged entries are listed too.
std::string FormatComparison(const Comparison& c, bool all = false);

}  // namespace brdfit::report
