#include "fit/loss.h"

#include <ceres/loss_function.h>

#include <cmath>

#include "core/error.h"

namespace brdfit {

LossData PrepareLoss(const Samples& samples, const FitOptions& options) {
  LossData d;
  d.kind = options.loss;
  d.cosine = options.cosine;
  const std::size_t n = samples.NumObservations();
  d.mult.resize(n);
  d.sqrt_w.resize(n);
  d.target.resize(3 * n);
  if (options.loss == LossKind::kRel) d.inv.resize(3 * n);
  const double norm = samples.total_weight > 0 ? 1.0 / (3.0 * samples.total_weight) : 0.0;
  for (std::size_t o = 0; o < n; ++o) {
    // The relative and log-ratio losses compare ratios: the cosine would (nearly) cancel, so
    // it is not applied.
    const double c = (options.cosine && !IsRatioLoss(options.loss)) ? samples.cos_i[o] : 1.0;
    d.mult[o] = c;
    d.sqrt_w[o] = std::sqrt(samples.weight[o] * norm);
    for (int ch = 0; ch < 3; ++ch) {
      const double m = samples.Value(o)[ch];
      d.target[3 * o + ch] = LossTransform(options.loss, m * c);
      if (!d.inv.empty()) d.inv[3 * o + ch] = 1.0 / (std::abs(m) + kRelEpsilon);
    }
  }
  return d;
}

std::unique_ptr<ceres::LossFunction> MakeRobustLoss(const FitOptions& options) {
  if (!(options.robust_scale > 0) || !std::isfinite(options.robust_scale)) {
    throw InputError("robust scale must be positive and finite");
  }
  switch (options.robust) {
    case RobustKind::kNone:
      return nullptr;
    case RobustKind::kHuber:
      return std::make_unique<ceres::HuberLoss>(options.robust_scale);
    case RobustKind::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(options.robust_scale);
  }
  return nullptr;
}

}  // namespace brdfit
