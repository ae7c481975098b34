// Scoring a factorization with the metrics of the analytic fits (fit/metrics.h), on the same
// samples (fit/samples.h), so factored and analytic results sit side by side in one report.
#pragma once

#include "factor/factor_eval.h"
#include "fit/metrics.h"
#include "fit/samples.h"
#include "core/table.h"

namespace brdfit {

// Evaluates the factored BRDF (through its float32 textures) at every sample of
// PrepareSamples(table, options) and scores it with ComputeMetrics.
FitMetrics ScoreFactorization(const Table& table, const FactoredBrdf& brdf,
                              const SampleOptions& options = {});

}  // namespace brdfit
