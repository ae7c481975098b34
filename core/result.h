// The outcome of one fit. Plain data: no NaN or Inf is ever stored here (a failed fit has
// status kFailed, a message, and zeros), so every writer can output it as is.
#pragma once

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

}  // namespace brdfit
