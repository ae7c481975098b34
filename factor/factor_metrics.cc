#include "factor/factor_metrics.h"

namespace brdfit {

FitMetrics ScoreFactorization(const Table& table, const FactoredBrdf& brdf,
                              const SampleOptions& options) {
  const Samples samples = PrepareSamples(table, options);
  std::vector<double> per_sample(3 * samples.NumSamples());
  for (std::size_t s = 0; s < samples.NumSamples(); ++s) {
    const Geometry& g = samples.geometry[s];
    const auto f = brdf.Eval(g.wi, g.wo);
    for (int c = 0; c < 3; ++c) per_sample[3 * s + c] = f[c];
  }
  return ComputeMetricsPerSample(samples, per_sample);
}

}  // namespace brdfit
