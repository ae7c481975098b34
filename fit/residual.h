// One residual of the loss (fit/loss.h) and its robust weighting, written once for every place
// that evaluates the loss: the residual blocks (fit/block_cost.h) and the initializer
// (fit/grid_init.cc).
//
//   e = inv (T(x) - t),  x = f c,  de/df = inv T'(x) c
//
// f: the model's value in one channel, c = mult[o] (cos theta_i or 1), t = target[3 o + ch],
// inv = Inv(o, ch), T the loss transform.
#pragma once

#include <ceres/jet.h>
#include <ceres/loss_function.h>

#include <cstddef>

#include "fit/loss.h"

namespace brdfit::internal {

// e at the transform's argument x = f c. T: double, or a ceres::Jet in x (then e.v = inv T'(x)
// x.v).
template <class T>
T ResidualAt(const LossData& l, std::size_t o, int ch, const T& x) {
  return l.Inv(o, ch) * (LossTransform(l.kind, x) - l.target[3 * o + ch]);
}

// e at the model value f.
inline double LossResidual(const LossData& l, std::size_t o, int ch, double f) {
  return ResidualAt(l, o, ch, f * l.mult[o]);
}

// e and its slope in f, from a one-lane Jet in x (seeded with 1: T' comes out unscaled).
struct SlopedResidual {
  double e = 0;
  double de_dx = 0;  // inv T'(x)
  double c = 1;      // dx/df
  // k de/df, multiplied as (k inv T'(x)) c. Either inv = 1 (log, cbrt, l2) or T' = 1 (rel),
  // so this rounds exactly like k inv T'(x) c from left to right.
  double Slope(double k = 1.0) const { return k * de_dx * c; }
};
inline SlopedResidual LossResidualWithSlope(const LossData& l, std::size_t o, int ch, double f) {
  using Slope1 = ceres::Jet<double, 1>;
  const double c = l.mult[o];
  const Slope1 e = ResidualAt(l, o, ch, Slope1(f * c, 0));
  return {e.a, e.v[0], c};
}

// The robust weighting of one residual e (robust may be null: rho(s) = s). With s = e^2:
struct RobustTerm {
  double cost = 0;       // rho(s), the residual's term of the cost
  double weight = 1;     // max(rho'(s), 0): the IRLS weight (fit/grid_init.cc)
  double res_scale = 1;  // the residual's factor and
  double jac_scale = 1;  // its Jacobian row's, as ceres::Corrector (fit/block_cost.h)
};
RobustTerm Robustify(const ceres::LossFunction* robust, double e);

}  // namespace brdfit::internal
