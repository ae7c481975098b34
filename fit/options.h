// Options of one fit: loss, robustness, initializer and solver settings. Sample selection
// (cut-off, weighting, budget) lives in SampleOptions (fit/samples.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/enum_names.h"

namespace brdfit {

// The data term of a residual, per cell and channel (f: model, m: measured, c = cos theta_i,
// or 1 with cosine = false). Definitions in fit/loss.h.
enum class LossKind {
  kLog,   // ln(1 + f c) - ln(1 + m c)          Löw et al. 2012, E2 (the default)
  kCbrt,  // cbrt(f c) - cbrt(m c), guarded       Fores, Ferwerda, Gu 2012
  kRel,   // (f - m) / (|m| + eps)                relative error
  kL2,    // f c - m c                            cosine-weighted L2 (Ngan et al. 2005)
  kLogRatio,  // ln(f + eps) - ln(m + eps), guarded    log-ratio (Sun et al. 2018)
};
inline constexpr auto kLossKindNames = MakeEnumNames<LossKind>("loss", {{LossKind::kLog, "log"},
                                                                        {LossKind::kCbrt, "cbrt"},
                                                                        {LossKind::kRel, "rel"},
                                                                        {LossKind::kL2, "l2"},
                                                                        {LossKind::kLogRatio, "logratio"}});
constexpr const auto& EnumNamesOf(LossKind) {
  return kLossKindNames;
}
// FromString<LossKind> under the name its callers use.
inline LossKind LossKindFromString(const std::string& s) {
  return FromString<LossKind>(s);
}

// Robust loss on each residual (ceres::HuberLoss / ceres::CauchyLoss with scale robust_scale,
// in the units of the loss's data term, e.g. log units for kLog).
enum class RobustKind { kNone, kHuber, kCauchy };
inline constexpr auto kRobustKindNames = MakeEnumNames<RobustKind>(
    "robust loss",
    {{RobustKind::kNone, "none"}, {RobustKind::kHuber, "huber"}, {RobustKind::kCauchy, "cauchy"}});
constexpr const auto& EnumNamesOf(RobustKind) {
  return kRobustKindNames;
}
// FromString<RobustKind> under the name its callers use.
inline RobustKind RobustKindFromString(const std::string& s) {
  return FromString<RobustKind>(s);
}

// A last stage after the fit on the table (fit/rendered_polish.h): kRendered polishes the
// parameters on the rendered-image metric's own pixels (docs/accuracy.md, "The rendered polish").
enum class PolishKind { kNone, kRendered };
inline constexpr auto kPolishKindNames = MakeEnumNames<PolishKind>(
    "polish", {{PolishKind::kNone, "none"}, {PolishKind::kRendered, "rendered"}});
constexpr const auto& EnumNamesOf(PolishKind) {
  return kPolishKindNames;
}

// The loss of a fit when none is given, in the library, `brdfit fit` and Python alike: the
// relative loss gives the lowest rendered error over the 100 MERL proxies of every loss tried
// (docs/accuracy.md).
inline constexpr LossKind kDefaultLoss = LossKind::kRel;

// A fit's options. The defaults are `brdfit fit`'s and Python's (pipeline/fit_settings.h takes
// them from here): the relative loss and the rendered polish.
struct FitOptions {
  LossKind loss = kDefaultLoss;
  bool cosine = true;  // multiply f and m by cos theta_i inside the loss
  RobustKind robust = RobustKind::kNone;
  double robust_scale = 0.1;
  int multistart = 1;               // LM runs from the best distinct initializer candidates
  int max_iterations = 100;         // per LM run
  int threads = 1;                  // Ceres threads per fit (parallelism is normally over fits)
  std::size_t init_samples = 1024;  // samples the initializer's grid is scored on
  // Coarse-to-fine: when the fit set has more than 4x this many samples, LM first runs on a
  // stratified subset of this size, then continues on the full set (0 disables).
  std::size_t coarse_samples = 8192;
  std::uint64_t seed = 1;  // subsets of the initializer and the coarse stage
  // LM stops when the relative cost change falls below function_tolerance. Model-mismatch fits
  // converge only linearly (about 0.4 per iteration on NBRDF tables), so each factor 100 costs
  // ~5 full-set iterations; 1e-6 leaves the metrics within ~1e-6 of the converged optimum
  // (bench_fit --csv: log_rmse equal to 7 digits against 1e-8) for 20-30 % less solve time.
  // Zero-residual fits converge quadratically whatever the tolerance.
  double function_tolerance = 1e-6;
  double parameter_tolerance = 1e-10;
  double gradient_tolerance = 1e-16;
  // On by default: it raises the rendered score of the chosen fit on every material of the
  // study (docs/accuracy.md, "The rendered polish").
  PolishKind polish = PolishKind::kRendered;

  bool operator==(const FitOptions&) const = default;
};

// The log loss (Löw et al. 2012, "BRDF Models for Accurate and Efficient Rendering of Glossy
// Surfaces", metric E2) without the rendered polish: the fit of the table alone, as `brdfit fit
// --loss log --polish none` makes it; what the fit engine's unit tests and benchmarks measure.
inline FitOptions LogLossUnpolished() {
  FitOptions o;
  o.loss = LossKind::kLog;
  o.polish = PolishKind::kNone;
  return o;
}

struct SampleOptions;
// Every option that can change a fit's result, as canonical JSON (sorted keys): reports store it
// so that `brdfit fit` can tell whether an existing entry was made with the same options.
// Ceres threads are left out (they change speed, not the problem).
std::string OptionsJson(const SampleOptions& samples, const FitOptions& fit);

// The fit engine's revision: raised whenever something OptionsJson does not record changes what
// a fit returns (an internal default such as the rendered polish's rounds). The on-disk cache of
// fits keys on it (pipeline/material_loader.cc), so a newer brdfit never reuses an older one's
// fit. 1: until 2026-12-03; 2: the polish's rounds go on while S rises (fit/rendered_polish.h).
// 3: the rendered judge lights the whole domain (front, side, rim; core/rendered_regions.h).
// 4: and an environment (fit/rendered_environment.h); the body's colour and narrow peaks in the
// choice (core/model_choice.h, fit/narrow_peak.h).
inline constexpr int kFitEngineRevision = 4;
// The rendered judge's name in OptionsJson: "front+side+rim" in revision 3,
// "front+side+rim+environment" since revision 4.
inline constexpr const char* kRenderedJudge = "front+side+rim+environment";

}  // namespace brdfit
