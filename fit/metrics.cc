#include "fit/metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/loss.h"

namespace brdfit {

namespace {

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
    double cell_worst = 0;
    for (int ch = 0; ch < 3; ++ch) {
      const double f = f_rgb[ch];
      const double v = samples.value[3 * o + ch];
      // The measured side is recomputed at each call rather than stored (48 bytes per
      // observation; docs/reliability.md, "Memory").
      const double dl = GuardedLog1p(f * c) - GuardedLog1p(v * c);
      const double dc = GuardedCbrt(f * c) - GuardedCbrt(v * c);
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
        m.worst.measured[ch] = samples.value[3 * o + ch];
        m.worst.predicted[ch] = f_rgb[ch];
      }
      m.worst.theta_i_deg = std::acos(std::clamp(samples.cos_i[o], -1.0, 1.0)) * 180.0 / kPi;
      m.worst.theta_o_deg = std::acos(std::clamp(samples.cos_o[o], -1.0, 1.0)) * 180.0 / kPi;
    }
  }
  m.worst.angles = samples.grid.CellCentre(static_cast<std::size_t>(m.worst.cell));
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
