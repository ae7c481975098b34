#include "fit/residual.h"

#include <algorithm>
#include <cmath>

namespace brdfit::internal {

// Triggs, McLauchlan, Hartley, Fitzgibbon 2000, "Bundle Adjustment — A Modern Synthesis", §4.3,
// as ceres::Corrector: rows scaled by sqrt(rho') (1 - a), residuals by sqrt(rho') / (1 - a),
// a = 1 - sqrt(1 + 2 s rho'' / rho') when rho'' > 0, else 0.
RobustTerm Robustify(const ceres::LossFunction* robust, double e) {
  const double s = e * e;
  RobustTerm t;
  if (robust == nullptr) {
    t.cost = s;
    return t;
  }
  double rho[3];
  robust->Evaluate(s, rho);
  t.cost = rho[0];
  t.weight = std::max(rho[1], 0.0);
  const double sqrt_rho1 = std::sqrt(t.weight);
  if (s == 0.0 || rho[2] <= 0.0 || !(rho[1] > 0.0)) {
    t.res_scale = t.jac_scale = sqrt_rho1;
    return t;
  }
  const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * s * rho[2] / rho[1]);
  t.res_scale = sqrt_rho1 / (1.0 - alpha);
  t.jac_scale = sqrt_rho1 * (1.0 - alpha);
  return t;
}

}  // namespace brdfit::internal
