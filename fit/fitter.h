// Fitting any catalog model (models/catalog.h) by name: prepare a table once, then fit as many
// models to it as wanted.
//
// Pipeline of one fit (fit/fit_engine.cc):
//  1. initializer: grid over the shape parameters with the colour weights solved linearly, on
//     a stratified subset (FitOptions::init_samples) of the fit samples (fit/grid_init.h);
//  2. Levenberg-Marquardt (Ceres) from the best `multistart` grid points, each first on a
//     stratified subset (coarse_samples) when the fit set is much larger, then on the fit set;
//     log_scale parameters are optimized as log p, every parameter within its bounds;
//  3. the best finite result; its metrics on the metric set (all cells inside the cut-off).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fit/loss.h"
#include "fit/options.h"
#include "core/result.h"
#include "fit/rendered_error.h"
#include "fit/samples.h"
#include "core/table.h"

namespace brdfit {

// A table made ready for fitting: fit samples (per the budget), their loss constants, and the
// metric samples (the full set; the same object as `fit` when the budget is full).
struct PreparedTable {
  Samples fit;
  LossData loss;
  Samples metric_own;
  bool has_own_metric = false;
  // The measured side of the rendered-image metric (fit/rendered_error.h); every fit of the
  // table is scored against it. Empty: no rendered metric (metrics.rendered.ok = false).
  RenderedReference rendered;
  // The same at the second pixel lattice (fit/narrow_peak.h), against which fits with a peak
  // narrower than a pixel are scored too. Empty exactly when `rendered` is.
  RenderedReference rendered_check;
  const Samples& metric() const { return has_own_metric ? metric_own : fit; }
};

// Throws InputError on bad options. `cache` (optional, fit/prepare_cache.h) holds the per-grid
// work for the next tables of a batch; the result is the same bits with or without it.
class PrepareCache;
PreparedTable PrepareTable(const Table& table, const SampleOptions& sample_options,
                           const FitOptions& fit_options, PrepareCache* cache = nullptr);
// The same, consuming the table: it is released as soon as the samples are built, which lowers
// the peak memory of a fit (brdfit fit; docs/reliability.md, "Memory").
PreparedTable PrepareTable(Table&& table, const SampleOptions& sample_options,
                           const FitOptions& fit_options, PrepareCache* cache = nullptr);

// Fits one model. Throws InputError if the name is not a catalog model; every other problem
// (no samples, non-finite values, solver failure) is a result with status kFailed.
// times.load and times.prepare are left for the caller.
FitResult FitPrepared(std::string_view model, const PreparedTable& table,
                      const FitOptions& options);

// Convenience: prepare + fit.
FitResult FitTable(std::string_view model, const Table& table, const SampleOptions& sample_options,
                   const FitOptions& options);

// Every catalog model name the fitter can fit, in catalog order.
std::vector<std::string> FittableModels();
bool IsFittable(std::string_view model);

// Gauss-Newton terms of the fit problem at parameters p (parameter space), as the solver sees
// them (optimization space: log p for log_scale parameters): cost = sum omega rho(e^2),
// gradient = J^T r and jtj = J^T J (row-major P x P). For tests and diagnostics.
struct NormalEquations {
  double cost = 0;
  std::vector<double> gradient;
  std::vector<double> jtj;
};
NormalEquations EvaluateNormalEquations(std::string_view model, const Samples& samples,
                                        const LossData& loss, const FitOptions& options,
                                        const std::vector<double>& params);

}  // namespace brdfit
