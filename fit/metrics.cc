#include "fit/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "fit/fast_cbrt.h"
#include "fit/loss.h"
#include "fit/threads.h"

namespace brdfit {

namespace {

// GuardedLog1p(a) - GuardedLog1p(b). Both above the guard (every non-negative a, b):
// ln(1 + a) - ln(1 + b) = ln(1 + (a - b) / (1 + b)), one logarithm instead of two and no
// cancellation when a and b are close.
double LogDifference(double a, double b) {
  if (a >= kLogGuard && b >= kLogGuard) return std::log1p((a - b) / (1.0 + b));
  return GuardedLog1p(a) - GuardedLog1p(b);
}

// The sums of one range of samples.
struct Partial {
  double log_sum = 0, cbrt_sum = 0, num = 0, den = 0;
  double worst = -1;  // largest |ln-error| of a cell, and where
  std::size_t worst_obs = 0;
  const double* worst_pred = nullptr;
  bool nonfinite = false;
};

// Samples per chunk. The chunks (not the threads) fix the order of the floating-point sums, so
// the metrics are the same bits whatever the number of threads.
constexpr std::size_t kChunkSamples = 8192;

// Observations per block of the pass below.
constexpr std::size_t kBlockObs = 256;

// predicted(o, s) returns the 3 predictions of observation o of sample s.
// A block of observations at a time: first their arguments f c and m c, then every cube root of
// the block (vectorized, below), then the sums in observation order. Each term is computed by
// the same operations as one observation at a time, and added in the same order: the same
// bits as a pass one observation at a time.
template <class Predicted>
Partial ScoreRange(const Samples& samples, std::size_t s_begin, std::size_t s_end,
                   const Predicted& predicted) {
  Partial p;
  struct Obs {
    std::uint32_t o;
    const double* f;
  };
  std::array<Obs, kBlockObs> obs;
  std::array<double, 6 * kBlockObs> arg;   // per observation: f c (3), m c (3)
  // The metric's cube root of arg: GuardedCbrt (fit/loss.h) with FastCbrt above the guard.
  std::array<double, 6 * kBlockObs> root;
  std::size_t n = 0;
  auto flush = [&] {
    // The cube root of every argument: the guess (integer arithmetic) and the refinement (double
    // arithmetic, vectorized: two divisions per instruction) in separate loops, then the
    // guard's few values (f c or m c below 1e-5: dark or zero cells) on their own.
    const std::size_t m = 6 * n;
    for (std::size_t k = 0; k < m; ++k) root[k] = FastCbrtGuess(arg[k]);
    for (std::size_t k = 0; k < m; ++k) root[k] = FastCbrtRefine(arg[k], root[k]);
    for (std::size_t k = 0; k < m; ++k) {
      if (!(arg[k] >= kCbrtGuard && arg[k] < 1e300)) root[k] = GuardedCbrt(arg[k]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t o = obs[k].o;
      const double* f_rgb = obs[k].f;
      const double w = samples.weight[o];
      const double c = samples.cos_i[o];
      const double* measured = samples.Value(o);
      double cell_worst = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const double f = f_rgb[ch];
        const double v = measured[ch];
        // The measured side is recomputed at each call rather than stored (48 bytes per
        // observation; docs/reliability.md, "Memory").
        const double dl = LogDifference(arg[6 * k + ch], arg[6 * k + 3 + ch]);
        const double dc = root[6 * k + ch] - root[6 * k + 3 + ch];
        p.log_sum += w * dl * dl;
        p.cbrt_sum += w * dc * dc;
        p.num += w * c * c * (f - v) * (f - v);
        p.den += w * c * c * v * v;
        cell_worst = std::max(cell_worst, std::abs(dl));
      }
      if (cell_worst > p.worst) {
        p.worst = cell_worst;
        p.worst_obs = o;
        p.worst_pred = f_rgb;
      }
    }
    n = 0;
  };
  for (std::size_t s = s_begin; s < s_end; ++s) {
    for (std::uint32_t o = samples.obs_begin[s]; o < samples.obs_begin[s + 1]; ++o) {
      const double* f_rgb = predicted(o, s);
      if (!(std::isfinite(f_rgb[0]) && std::isfinite(f_rgb[1]) && std::isfinite(f_rgb[2]))) {
        p.nonfinite = true;
        return p;
      }
      const double c = samples.cos_i[o];
      const double* measured = samples.Value(o);
      for (int ch = 0; ch < 3; ++ch) {
        arg[6 * n + ch] = f_rgb[ch] * c;
        arg[6 * n + 3 + ch] = measured[ch] * c;
      }
      obs[n++] = {o, f_rgb};
      if (n == kBlockObs) flush();
    }
  }
  flush();
  return p;
}

template <class Predicted>
FitMetrics Score(const Samples& samples, const Predicted& predicted, int threads) {
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
  const std::size_t ns = samples.NumSamples();
  const std::size_t n_chunks = (ns + kChunkSamples - 1) / kChunkSamples;
  std::vector<Partial> parts(n_chunks);
  const std::size_t n_threads =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), 1, n_chunks);
  internal::RunOnThreads(static_cast<int>(n_threads), [&](int t) {
    for (std::size_t k = static_cast<std::size_t>(t); k < n_chunks; k += n_threads) {
      parts[k] = ScoreRange(samples, k * kChunkSamples, std::min(ns, (k + 1) * kChunkSamples),
                            predicted);
    }
  });

  if (std::any_of(parts.begin(), parts.end(), [](const Partial& p) { return p.nonfinite; })) {
    m.problem = "non-finite prediction";  // nothing of the partial sums is reported
    return m;
  }
  // Combined in chunk order; the first largest error wins, as in one pass.
  double log_sum = 0, cbrt_sum = 0, num = 0, den = 0, worst = -1;
  for (const Partial& p : parts) {
    log_sum += p.log_sum;
    cbrt_sum += p.cbrt_sum;
    num += p.num;
    den += p.den;
    if (p.worst > worst) {
      worst = p.worst;
      m.worst.cell = samples.cell[p.worst_obs];
      m.worst.log_error = p.worst;
      const double* measured = samples.Value(p.worst_obs);
      for (int ch = 0; ch < 3; ++ch) {
        m.worst.measured[ch] = measured[ch];
        m.worst.predicted[ch] = p.worst_pred[ch];
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

FitMetrics ComputeMetrics(const Samples& samples, std::span<const double> predicted_rgb,
                          int threads) {
  if (predicted_rgb.size() != 3 * samples.NumObservations()) {
    throw std::invalid_argument("ComputeMetrics: expected 3 predictions per observation");
  }
  return Score(
      samples, [&](std::size_t o, std::size_t) { return &predicted_rgb[3 * o]; }, threads);
}

FitMetrics ComputeMetricsPerSample(const Samples& samples, std::span<const double> per_sample_rgb,
                                   int threads) {
  if (per_sample_rgb.size() != 3 * samples.NumSamples()) {
    throw std::invalid_argument("ComputeMetricsPerSample: expected 3 predictions per sample");
  }
  return Score(
      samples, [&](std::size_t, std::size_t s) { return &per_sample_rgb[3 * s]; }, threads);
}

}  // namespace brdfit
