#include "fit/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "fit/fast_cbrt.h"
#include "fit/loss.h"
#include "fit/threads.h"
#include "fit/vector_log1p.h"

namespace brdfit {

namespace {

// GuardedLog1p(a) - GuardedLog1p(b). Both above the guard (every non-negative a, b):
// ln(1 + a) - ln(1 + b) = ln(1 + (a - b) / (1 + b)), one logarithm instead of two and no
// cancellation when a and b are close.
double LogDifference(double a, double b) {
  if (a >= kLogGuard && b >= kLogGuard) return std::log1p((a - b) / (1.0 + b));
  return GuardedLog1p(a) - GuardedLog1p(b);
}

// True when lo <= x[k] < hi for every k < n (NaN is not). Two at a time with SSE2 compares
// (GCC does not vectorize the scalar loop: it short-circuits).
bool AllInRange(const double* x, std::size_t n, double lo, double hi) {
  std::size_t k = 0;
#if defined(__SSE2__)
  const __m128d vlo = _mm_set1_pd(lo), vhi = _mm_set1_pd(hi);
  __m128d ok = _mm_castsi128_pd(_mm_set1_epi32(-1));
  for (; k + 2 <= n; k += 2) {
    const __m128d v = _mm_loadu_pd(x + k);
    ok = _mm_and_pd(ok, _mm_and_pd(_mm_cmpge_pd(v, vlo), _mm_cmplt_pd(v, vhi)));
  }
  if (_mm_movemask_pd(ok) != 3) return false;
#endif
  for (; k < n; ++k) {
    if (!(x[k] >= lo && x[k] < hi)) return false;
  }
  return true;
}

// out[j] = (a[j] - b[j]) / (1 + b[j]), the argument of LogDifference's single logarithm, where
// both are at or above kLogGuard; NaN (the long way) elsewhere. The same IEEE operations as
// LogDifference, two at a time.
void LogRatioArguments(const double* a, const double* b, std::size_t n, double* out) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::size_t j = 0;
#if defined(__SSE2__)
  const __m128d guard = _mm_set1_pd(kLogGuard), one = _mm_set1_pd(1.0), nan = _mm_set1_pd(kNaN);
  for (; j + 2 <= n; j += 2) {
    const __m128d va = _mm_loadu_pd(a + j), vb = _mm_loadu_pd(b + j);
    const __m128d plain = _mm_and_pd(_mm_cmpge_pd(va, guard), _mm_cmpge_pd(vb, guard));
    const __m128d x = _mm_div_pd(_mm_sub_pd(va, vb), _mm_add_pd(one, vb));
    _mm_storeu_pd(out + j, _mm_or_pd(_mm_and_pd(plain, x), _mm_andnot_pd(plain, nan)));
  }
#endif
  for (; j < n; ++j) {
    out[j] = a[j] >= kLogGuard && b[j] >= kLogGuard ? (a[j] - b[j]) / (1.0 + b[j]) : kNaN;
  }
}

// The sums of one range of samples.
struct Partial {
  double log_sum = 0, cbrt_sum = 0, num = 0, den = 0;
  double worst = -1;  // largest |ln-error| of a cell, and where
  std::size_t worst_obs = 0;
  std::array<double, 3> worst_pred{};  // a copy: the predictions may live in a chunk's buffer
  bool nonfinite = false;
};

// Samples per chunk. The chunks (not the threads) fix the order of the floating-point sums, so
// the metrics are the same bits whatever the number of threads.
constexpr std::size_t kChunkSamples = 8192;

// Observations per block of the pass below.
constexpr std::size_t kBlockObs = 256;

// predicted(o, s) returns the 3 predictions of observation o of sample s.
// A block of observations at a time: first their arguments f c and m c, then every cube root of
// the block (vectorized, below), every log difference (its arguments, then the logarithms four
// at a time where the CPU allows: fit/vector_log1p.h), then the sums in observation order. Each
// term depends on its observation alone and is added in observation order: the same bits for
// any chunking of the samples among threads.
template <class Predicted>
Partial ScoreRange(const Samples& samples, std::size_t s_begin, std::size_t s_end,
                   const Predicted& predicted) {
  Partial p;
  struct Obs {
    std::uint32_t o;
    const double* f;
  };
  constexpr std::size_t kM = 3 * kBlockObs;  // offset of the measured half below
  std::array<Obs, kBlockObs> obs;
  // Per observation and channel j = 3 k + ch: arg[j] = f c, arg[kM + j] = m c.
  std::array<double, 2 * kM> arg;
  // The metric's cube root of arg: GuardedCbrt (fit/loss.h) with FastCbrt above the guard.
  std::array<double, 2 * kM> root;
  std::array<double, kM> log_diff;  // LogDifference(arg[j], arg[kM + j])
  std::size_t n = 0;
  // The cube roots of arg[begin, end): the guesses (integer arithmetic, two per instruction) and
  // the refinement (double arithmetic: two or four divisions per instruction), then the guard's
  // few values (f c or m c below 1e-5: dark or zero cells) on their own, when the block has any.
  auto cube_roots = [&](std::size_t begin, std::size_t end) {
    FastCbrtGuesses(&arg[begin], end - begin, &root[begin]);
    FastCbrtRefineAll(&arg[begin], end - begin, &root[begin]);
    if (AllInRange(&arg[begin], end - begin, kCbrtGuard, 1e300)) return;
    for (std::size_t k = begin; k < end; ++k) {
      if (!(arg[k] >= kCbrtGuard && arg[k] < 1e300)) root[k] = GuardedCbrt(arg[k]);
    }
  };
  auto flush = [&] {
    const std::size_t m = 3 * n;
    cube_roots(0, m);
    cube_roots(kM, kM + m);
    // LogDifference's arguments, then its logarithms; the guard's values (an argument below
    // kLogGuard: a negative prediction) marked by NaN and taken the long way.
    LogRatioArguments(arg.data(), arg.data() + kM, m, log_diff.data());
    Log1pAll(log_diff.data(), m, log_diff.data());
    for (std::size_t j = 0; j < m; ++j) {
      if (std::isnan(log_diff[j])) log_diff[j] = LogDifference(arg[j], arg[kM + j]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t o = obs[k].o;
      const double* f_rgb = obs[k].f;
      const double w = samples.weight[o];
      const double c = samples.cos_i[o];
      const double* measured = samples.Value(o);
      double cell_worst = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const std::size_t j = 3 * k + ch;
        const double f = f_rgb[ch];
        const double v = measured[ch];
        // The measured side is recomputed at each call rather than stored (48 bytes per
        // observation; docs/reliability.md, "Memory").
        const double dl = log_diff[j];
        const double dc = root[j] - root[kM + j];
        p.log_sum += w * dl * dl;
        p.cbrt_sum += w * dc * dc;
        p.num += w * c * c * (f - v) * (f - v);
        p.den += w * c * c * v * v;
        cell_worst = std::max(cell_worst, std::abs(dl));
      }
      if (cell_worst > p.worst) {
        p.worst = cell_worst;
        p.worst_obs = o;
        p.worst_pred = {f_rgb[0], f_rgb[1], f_rgb[2]};
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
        arg[3 * n + ch] = f_rgb[ch] * c;
        arg[kM + 3 * n + ch] = measured[ch] * c;
      }
      obs[n++] = {o, f_rgb};
      if (n == kBlockObs) flush();
    }
  }
  flush();
  return p;
}

// score_chunk(begin, end) returns the Partial of samples [begin, end); called once per chunk,
// from the thread that owns it.
template <class ScoreChunk>
FitMetrics Score(const Samples& samples, const ScoreChunk& score_chunk, int threads) {
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
      parts[k] = score_chunk(k * kChunkSamples, std::min(ns, (k + 1) * kChunkSamples));
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
  const auto predicted = [&](std::size_t o, std::size_t) { return &predicted_rgb[3 * o]; };
  return Score(
      samples, [&](std::size_t b, std::size_t e) { return ScoreRange(samples, b, e, predicted); },
      threads);
}

FitMetrics ComputeMetricsPerSample(const Samples& samples, std::span<const double> per_sample_rgb,
                                   int threads) {
  if (per_sample_rgb.size() != 3 * samples.NumSamples()) {
    throw std::invalid_argument("ComputeMetricsPerSample: expected 3 predictions per sample");
  }
  const auto predicted = [&](std::size_t, std::size_t s) { return &per_sample_rgb[3 * s]; };
  return Score(
      samples, [&](std::size_t b, std::size_t e) { return ScoreRange(samples, b, e, predicted); },
      threads);
}

FitMetrics ComputeMetricsStreamed(const Samples& samples, const SampleEvaluator& eval,
                                  int threads) {
  return Score(
      samples,
      [&](std::size_t b, std::size_t e) {
        // One chunk's predictions (3 x 8192 doubles, 192 KiB: stays in cache), then its sums.
        thread_local std::vector<double> buffer;
        buffer.resize(3 * kChunkSamples);
        eval(b, e, buffer.data());
        return ScoreRange(samples, b, e,
                          [&](std::size_t, std::size_t s) { return &buffer[3 * (s - b)]; });
      },
      threads);
}

}  // namespace brdfit
