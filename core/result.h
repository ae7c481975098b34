// The outcome of one fit. Plain data: no NaN or Inf is ever stored here (a failed fit has
// status kFailed, a message, and zeros), so every writer can output it as is.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "core/metrics.h"
#include "core/sample_counts.h"

namespace brdfit {

enum class FitStatus {
  kConverged,      // Ceres reported convergence and everything is finite
  kNoConvergence,  // iteration limit reached; parameters are the best found, still usable
  kFailed,         // no usable result (see message); parameters are the initial guess or 0
};
inline constexpr auto kFitStatusNames =
    MakeEnumNames<FitStatus>("fit status", {{FitStatus::kConverged, "converged"},
                                            {FitStatus::kNoConvergence, "no_convergence"},
                                            {FitStatus::kFailed, "failed"}});
constexpr const auto& EnumNamesOf(FitStatus) {
  return kFitStatusNames;
}

// Milliseconds. Wall clock, and the fitting thread's CPU time (CLOCK_THREAD_CPUTIME_ID): on a
// busy machine the wall time includes waiting for a core, the CPU time does not.
struct FitTimes {
  double load = 0;      // reading the table (set by the caller)
  double prepare = 0;   // samples and loss constants (set by the caller, shared per table)
  double init = 0;      // grid initializer
  double solve = 0;     // Levenberg-Marquardt, all stages and starts
  double metrics = 0;   // predictions on the metric set and ComputeMetrics
  double init_cpu = 0;  // CPU time of init, solve, metrics
  double solve_cpu = 0;
  double metrics_cpu = 0;
};

struct FitResult {
  std::string model;                     // registry name, e.g. "lambert+ggx"
  std::vector<std::string> param_names;  // qualified for sums: "ggx.alpha"
  std::vector<double> params;
  std::vector<bool> at_bound;  // parameter ended on one of its bounds
  FitStatus status = FitStatus::kFailed;
  std::string message;          // why it failed, or notes (empty if none)
  std::string termination;      // Ceres termination of the final stage
  int iterations = 0;           // LM iterations, all stages and starts
  int starts = 0;               // LM runs (multi-start)
  double init_cost = 0;         // loss at the initializer's best point (its subset)
  double final_cost = 0;        // loss at the result on the fit samples
  std::size_t fit_samples = 0;  // model evaluation points of the final stage
  std::size_t fit_cells = 0;    // observations of the final stage
  SampleCounts sample_counts;   // what preparation kept, dropped and flagged (fit set)
  FitMetrics metrics;
  FitTimes times;

  bool Failed() const { return status == FitStatus::kFailed; }
};

// ---- The fit entry's numbers -----------------------------------------------------------------
// The fit report (io/fit_report.h: HDF5 attributes of the entry, its samples and timing groups)
// and the Python dict (python/py_fit.cc) iterate these instead of naming the members; the error
// metrics have their own tables (core/metrics.h). Adding a number is its member and one row.

// The solver's numbers of a FitResult, attributes of the entry in this order: integers >= 0
// (an int member: at most INT_MAX) or finite doubles >= 0. One member pointer of each row is set.
struct FitNumberField {
  const char* name;
  const char* doc;
  int FitResult::*small = nullptr;
  std::size_t FitResult::*count = nullptr;
  double FitResult::*value = nullptr;
};
inline constexpr FitNumberField kFitNumbers[] = {
    {"iterations", "Levenberg-Marquardt iterations, all stages and starts", &FitResult::iterations},
    {"starts", "Levenberg-Marquardt runs (multi-start)", &FitResult::starts},
    {"init_cost", "loss at the initializer's best point (its subset)", nullptr, nullptr,
     &FitResult::init_cost},
    {"final_cost", "loss at the result on the fit samples", nullptr, nullptr,
     &FitResult::final_cost},
    {"fit_samples", "model evaluation points of the final stage", nullptr, &FitResult::fit_samples},
    {"fit_cells", "observations of the final stage", nullptr, &FitResult::fit_cells},
};

// SampleCounts, the entry's samples group: integers >= 0.
struct SampleCountField {
  const char* name;
  std::size_t SampleCounts::*value;
};
inline constexpr SampleCountField kSampleCountFields[] = {
    {"cells", &SampleCounts::cells},
    {"valid", &SampleCounts::valid},
    {"nonfinite", &SampleCounts::nonfinite},
    {"negative", &SampleCounts::negative},
    {"beyond_cutoff", &SampleCounts::beyond_cutoff},
    {"eligible", &SampleCounts::eligible},
    {"selected", &SampleCounts::selected},
};

// FitTimes, the entry's timing group and the Python dict's "timings": milliseconds >= 0.
struct FitTimeField {
  const char* name;
  double FitTimes::*value;
};
inline constexpr FitTimeField kFitTimeFields[] = {
    {"load_ms", &FitTimes::load},           {"prepare_ms", &FitTimes::prepare},
    {"init_ms", &FitTimes::init},           {"solve_ms", &FitTimes::solve},
    {"metrics_ms", &FitTimes::metrics},     {"init_cpu_ms", &FitTimes::init_cpu},
    {"solve_cpu_ms", &FitTimes::solve_cpu}, {"metrics_cpu_ms", &FitTimes::metrics_cpu},
};

}  // namespace brdfit
