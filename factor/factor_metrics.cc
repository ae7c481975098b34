#include "factor/factor_metrics.h"

#include <cmath>

namespace brdfit {

FitMetrics ScoreFactorization(const Table& table, const FactoredBrdf& brdf,
                              const SampleOptions& options) {
  // Only scored, never solved on: no stored geometry (55 MB on the MERL grid).
  const Samples samples = PrepareSamples(table, options, GeometryStorage::kOnDemand);
  // The predictions chunk by chunk as the metrics take them (fit/metrics.h), not stored whole.
  return ComputeMetricsStreamed(samples, [&](std::size_t begin, std::size_t end, double* out) {
    for (std::size_t s = begin; s < end; ++s) {
      const Geometry g = SampleGeometry(samples, s);
      const auto f = brdf.Eval(g.wi, g.wo);
      for (int c = 0; c < 3; ++c) out[3 * (s - begin) + c] = f[c];
    }
  });
}

double FactorLnRatioRmse(const Table& table, const FactoredBrdf& brdf, double max_theta) {
  const double cos_max = std::cos(max_theta);
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t idx = 0; idx < table.grid.NumCells(); ++idx) {
    if (!table.valid[idx]) continue;
    const double* v = table.Value(idx);
    if (!(v[0] > 0 && v[1] > 0 && v[2] > 0)) continue;
    Vec3 wi, wo;
    FromHalfDiff(table.grid.CellCentre(idx), 0.0, &wi, &wo);
    if (wi.z <= 0 || wo.z <= 0 || wi.z < cos_max || wo.z < cos_max) continue;
    const auto f = brdf.Eval(wi, wo);
    for (int c = 0; c < 3; ++c) {
      const double d = std::log(f[c]) - std::log(v[c]);
      sum += d * d;
    }
    count += 3;
  }
  return count ? std::sqrt(sum / count) : 0.0;
}

BrdfFunction FactoredBrdfFunction(const FactoredBrdf& brdf) {
  return [&brdf](const Vec3& wi, const Vec3& wo) { return brdf.Eval(wi, wo); };
}

RenderedError ScoreFactorizationRendered(const Table& table, const FactoredBrdf& brdf,
                                         const RenderedErrorOptions& options) {
  return ComputeRenderedError(table, FactoredBrdfFunction(brdf), options);
}

}  // namespace brdfit
