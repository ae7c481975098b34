// Scoring a factorization with the metrics of the analytic fits (fit/metrics.h), on the same
// samples (fit/samples.h), so factored and analytic results sit side by side in one report.
#pragma once

#include "core/table.h"
#include "factor/factor_eval.h"
#include "fit/metrics.h"
#include "fit/samples.h"

namespace brdfit {

// Evaluates the factored BRDF (through its float32 textures) at every sample of
// PrepareSamples(table, options) and scores it with ComputeMetrics.
FitMetrics ScoreFactorization(const Table& table, const FactoredBrdf& brdf,
                              const SampleOptions& options = {});

// The ln-ratio RMS of a factored BRDF against a table, the factorization's own objective seen as
// a relative error: sqrt(mean over usable cells with every channel > 0, channels pooled, of
// (ln f_factored - ln f_table)^2), unweighted, at cell centres (phi_h = 0) through the textures;
// cells with theta_i or theta_o above max_theta are skipped. A factor of 2 everywhere is ln 2 =
// 0.69. Written as `ln_ratio_rmse` in sidecars and printed by `brdfit factor` beside the shared
// metrics of ScoreFactorization.
double FactorLnRatioRmse(const Table& table, const FactoredBrdf& brdf, double max_theta = kPi / 2);

}  // namespace brdfit
