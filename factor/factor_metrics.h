// Scoring a factorization with the metrics of the analytic fits (fit/metrics.h), on the same
// samples (fit/samples.h), and with the rendered-image metric (fit/rendered_error.h) on the same
// scene, so factored and analytic results sit side by side in one report.
#pragma once

#include "core/table.h"
#include "factor/factor_eval.h"
#include "fit/metrics.h"
#include "fit/rendered_error.h"
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

// A factorization as an approximation for the rendered-image metric (fit/rendered_error.h):
// FactoredBrdf::Eval, i.e. the float32 textures as written to the EXR files (lossless), looked
// up with GL_LINEAR's weights: what the preview's GLSL (preview/glsl/factored.glsl) and its CPU
// reference renderer draw. The brdf must outlive the function.
BrdfFunction FactoredBrdfFunction(const FactoredBrdf& brdf);

// The rendered-image metric of a factorization against its table (docs/accuracy.md, the default
// scene unless options say otherwise): ComputeRenderedError(table, FactoredBrdfFunction(brdf)).
// Written as metrics.rendered in the sidecar (docs/formats.md) and printed by `brdfit factor`.
RenderedError ScoreFactorizationRendered(const Table& table, const FactoredBrdf& brdf,
                                         const RenderedErrorOptions& options = {});

}  // namespace brdfit
