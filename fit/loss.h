// Loss terms of a fit, per observation (cell) and channel:
//
//   e = inv * (T(f * c) - T(m * c)),   cost = sum over cells and channels of  omega * rho(e^2)
//
// f: model value, m: measured value (1/sr), c = cos theta_i (or 1), T the loss transform,
// inv a per-cell scale (relative loss only), omega = weight / (3 * total weight) so that the
// cost is a weighted mean over cells and channels, rho the robust function (identity if none).
// With the log loss, cosine on, no robust loss and the full sample set, the cost is exactly
// log_rmse^2 of fit/metrics.h.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "fit/options.h"
#include "fit/samples.h"

namespace ceres {
class LossFunction;
}

namespace brdfit {

// Below this |x| the cube root is replaced by an odd C1 cubic (Ceres #594:
// cbrt has an infinite derivative at 0 and pow(x, 1/3) is NaN for x < 0 on Jets).
inline constexpr double kCbrtGuard = 1e-5;
// Offset of the relative loss (1/sr): (f - m) / (|m| + eps), after Sun et al. 2018 (eps 1e-3).
inline constexpr double kRelEpsilon = 1e-3;
// Below this argument ln(1 + x) continues as its tangent, so f c <= -1 stays finite.
inline constexpr double kLogGuard = -0.5;
// Offset of the log-ratio loss (1/sr): ln((f + eps) / (m + eps)), after Sun, Jensen,
// Ramamoorthi 2018, "Connecting Measured BRDFs to Analytic BRDFs by Data-Driven
// Diffuse-Specular Separation" (TOG 37(6)), whose fitting error is a log ratio offset by a
// small constant. The same eps as the relative loss: the two differ to first order only in
// how they weigh errors larger than the value (log: symmetric in ratio; rel: in difference).
inline constexpr double kLogRatioEpsilon = kRelEpsilon;

// cbrt(x) for |x| >= g; for |x| < g, a x + b x^3 with a = 4/3 g^(-2/3), b = -1/3 g^(-8/3):
// the same value and slope at |x| = g, odd, slope 4/3 g^(-2/3) at 0.
template <class T>
T GuardedCbrt(const T& x) {
  using std::cbrt;
  if (x >= kCbrtGuard) return cbrt(x);
  if (x <= -kCbrtGuard) return -cbrt(-x);
  const double g23 = std::cbrt(kCbrtGuard * kCbrtGuard);
  const double a = 4.0 / (3.0 * g23);
  const double b = -1.0 / (3.0 * g23 * kCbrtGuard * kCbrtGuard);
  return x * (a + b * (x * x));
}

// ln(1 + x), continued linearly below kLogGuard.
template <class T>
T GuardedLog1p(const T& x) {
  using std::log1p;
  if (x >= kLogGuard) return log1p(x);
  return std::log1p(kLogGuard) + (x - kLogGuard) / (1.0 + kLogGuard);
}

// ln(x + eps) for x >= -eps / 2, continued as its tangent below, so a model value that dips
// below -eps (no registered model does; a robustness guard) stays finite.
template <class T>
T GuardedLogOffset(const T& x) {
  using std::log;
  constexpr double kEps = kLogRatioEpsilon;
  if (x >= -0.5 * kEps) return log(x + kEps);
  return std::log(0.5 * kEps) + (x + 0.5 * kEps) / (0.5 * kEps);
}

template <class T>
T LossTransform(LossKind kind, const T& x) {
  switch (kind) {
    case LossKind::kLog:
      return GuardedLog1p(x);
    case LossKind::kCbrt:
      return GuardedCbrt(x);
    case LossKind::kLogRatio:
      return GuardedLogOffset(x);
    case LossKind::kRel:
    case LossKind::kL2:
      break;
  }
  return x;
}

// The losses that compare f / m rather than f c against m c (no cosine factor).
inline bool IsRatioLoss(LossKind kind) {
  return kind == LossKind::kRel || kind == LossKind::kLogRatio;
}

// Per-observation constants of the loss, prepared once per (samples, options).
struct LossData {
  LossKind kind = LossKind::kLog;
  bool cosine = true;          // FitOptions::cosine it was prepared with
  std::vector<double> mult;    // per observation: c (cos theta_i, or 1)
  std::vector<double> sqrt_w;  // per observation: sqrt(omega)
  std::vector<double> target;  // 3 per observation: T(m c)
  std::vector<double> inv;     // kRel only, 3 per observation: 1 / (|m| + eps); else empty

  // The residual's scale of observation o, channel ch (1 except for kRel). Other losses keep no
  // per-observation array: 26 MB less on a full MERL table (docs/reliability.md, "Memory").
  double Inv(std::size_t o, int ch) const { return inv.empty() ? 1.0 : inv[3 * o + ch]; }
};

LossData PrepareLoss(const Samples& samples, const FitOptions& options);

// The robust function for the options, nullptr for RobustKind::kNone.
std::unique_ptr<ceres::LossFunction> MakeRobustLoss(const FitOptions& options);

}  // namespace brdfit
