#include "fit/metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/fast_cbrt.h"
#include "fit/loss.h"

namespace brdfit {

namespace {

// GuardedCbrt (fit/loss.h) with FastCbrt above the guard.
double MetricCbrt(double x) {
  return x >= kCbrtGuard && x < 1e300 ? FastCbrt(x) : GuardedCbrt(x);
}

// GuardedLog1p(a) - GuardedLog1p(b). Both above the guard (every non-negative a, b):
// ln(1 + a) - ln(1 + b) = ln(1 + (a - b) / (1 + b)), one logarithm instead of two and no
// cancellation when a and b are close.
double LogDifference(double a, double b) {
  if (a >= kLogGuard && b >= kLogGuard) return std::log1p((a - b) / (1.0 + b));
  return GuardedLog1p(a) - GuardedLog1p(b);
}

// predicted(o) returns the 3 predictions of observation o; observations are visited in order.
template <class Predicted>
FitMetrics Score(const Samples& samples, Predicted predicted) {
  const std::size_t n = samples.NumObservations();
  FitMetrics m;
  m.weighting = ToString(samples.options.weighting);
  m.cutoff_deg = samples.options.cutoff_deg;
  m.cells = n;
  m.total_weight = samples.total_weight;
  if (n == 0 || !(samples.total_weight > 0)) {
    m.problem = "no samples to score";
    return m;
  }
  double log_sum = 0, cbrt_sum = 0, num = 0, den = 0;
  double worst = -1;
  for (std::size_t o = 0; o < n; ++o) {
    const double* f_rgb = predicted(o);
    if (!(std::isfinite(f_rgb[0]) && std::isfinite(f_rgb[1]) && std::isfinite(f_rgb[2]))) {
      m.worst = WorstCell{};  // nothing of the partial sums is reported
      m.problem = "non-finite prediction";
      return m;
    }
    const double w = samples.weight[o];
    const double c = samples.cos_i[o];
    const double* measured = samples.Value(o);
    double cell_worst = 0;
    for (int ch = 0; ch < 3; ++ch) {
      const double f = f_rgb[ch];
      const double v = measured[ch];
      // The measured side is recomputed at each call rather than stored (48 bytes per
      // observation; docs/reliability.md, "Memory").
      const double dl = LogDifference(f * c, v * c);
      const double dc = MetricCbrt(f * c) - MetricCbrt(v * c);
      log_sum += w * dl * dl;
      cbrt_sum += w * dc * dc;
      num += w * c * c * (f - v) * (f - v);
      den += w * c * c * v * v;
      cell_worst = std::max(cell_worst, std::abs(dl));
    }
    if (cell_worst > worst) {
      worst = cell_worst;
      m.worst.cell = samples.cell[o];
      m.worst.log_error = cell_worst;
      for (int ch = 0; ch < 3; ++ch) {
        m.worst.measured[ch] = measured[ch];
        m.worst.predicted[ch] = f_rgb[ch];
      }
    }
  }
  // The worst cell's directions, from its centre (the observation's own configuration: for a
  // phi_d mirror, theta_i and theta_o of its sample swapped).
  m.worst.angles = samples.grid.CellCentre(static_cast<std::size_t>(m.worst.cell));
  Vec3 wi, wo;
  FromHalfDiff(m.worst.angles, 0.0, &wi, &wo);
  m.worst.theta_i_deg = std::acos(std::clamp(wi.z, -1.0, 1.0)) * 180.0 / kPi;
  m.worst.theta_o_deg = std::acos(std::clamp(wo.z, -1.0, 1.0)) * 180.0 / kPi;
  const double wsum = 3.0 * samples.total_weight;
  m.log_rmse = std::sqrt(log_sum / wsum);
  m.cbrt_rmse = std::sqrt(cbrt_sum / wsum);
  if (den > 0) {
    m.rel_l2 = std::sqrt(num / den);
  } else {
    m.rel_l2 = num > 0 ? 1.0 : 0.0;
    m.problem = "measured values are all zero: rel_l2 is 1 for any non-zero prediction";
  }
  m.ok = std::isfinite(m.log_rmse) && std::isfinite(m.cbrt_rmse) && std::isfinite(m.rel_l2);
  if (!m.ok) {
    m.problem = "non-finite metric (overflow)";
    m.log_rmse = m.cbrt_rmse = m.rel_l2 = 0;
  }
  return m;
}

}  // namespace

FitMetrics ComputeMetrics(const Samples& samples, std::span<const double> predicted_rgb) {
  if (predicted_rgb.size() != 3 * samples.NumObservations()) {
    throw std::invalid_argument("ComputeMetrics: expected 3 predictions per observation");
  }
  return Score(samples, [&](std::size_t o) { return &predicted_rgb[3 * o]; });
}

FitMetrics ComputeMetricsPerSample(const Samples& samples, std::span<const double> per_sample_rgb) {
  if (per_sample_rgb.size() != 3 * samples.NumSamples()) {
    throw std::invalid_argument("ComputeMetricsPerSample: expected 3 predictions per sample");
  }
  // Observations are stored sample by sample: advance s as o leaves its range.
  std::size_t s = 0;
  return Score(samples, [&](std::size_t o) {
    while (o >= samples.obs_begin[s + 1]) ++s;
    return &per_sample_rgb[3 * s];
  });
}

}  // namespace brdfit
