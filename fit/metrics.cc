#include "fit/metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/loss.h"

namespace brdfit {

FitMetrics ComputeMetrics(const Samples& samples, std::span<const double> predicted_rgb) {
  const std::size_t n = samples.NumObservations();
  if (predicted_rgb.size() != 3 * n) {
    throw std::invalid_argument("ComputeMetrics: expected 3 predictions per observation");
  }
  FitMetrics m;
  m.weighting = ToString(samples.options.weighting);
  m.cutoff_deg = samples.options.cutoff_deg;
  m.cells = n;
  m.total_weight = samples.total_weight;
  if (n == 0 || !(samples.total_weight > 0)) {
    m.problem = "no samples to score";
    return m;
  }
  for (double v : predicted_rgb) {
    if (!std::isfinite(v)) {
      m.problem = "non-finite prediction";
      return m;
    }
  }
  const bool pre = samples.metric_log.size() == 3 * n && samples.metric_cbrt.size() == 3 * n;
  double log_sum = 0, cbrt_sum = 0, num = 0, den = 0;
  double worst = -1;
  for (std::size_t o = 0; o < n; ++o) {
    const double w = samples.weight[o];
    const double c = samples.cos_i[o];
    double cell_worst = 0;
    for (int ch = 0; ch < 3; ++ch) {
      const double f = predicted_rgb[3 * o + ch];
      const double v = samples.value[3 * o + ch];
      const double dl =
          GuardedLog1p(f * c) - (pre ? samples.metric_log[3 * o + ch] : GuardedLog1p(v * c));
      const double dc =
          GuardedCbrt(f * c) - (pre ? samples.metric_cbrt[3 * o + ch] : GuardedCbrt(v * c));
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
        m.worst.predicted[ch] = predicted_rgb[3 * o + ch];
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

}  // namespace brdfit
