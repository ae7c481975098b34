#include "fit/block_compress.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace brdfit::internal {

void AccumulateGram(const double* rows, int n, int cols, double* gram) {
  if (n == 0) return;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> r(
      rows, n, cols);
  Eigen::Map<Eigen::MatrixXd> g(gram, cols, cols);
  g.selfadjointView<Eigen::Lower>().rankUpdate(r.transpose());
}

bool CompressGram(const double* gram, int P, double cost, double* residuals, double* jacobian) {
  const Eigen::Map<const Eigen::MatrixXd> g(gram, P + 1, P + 1);
  const Eigen::MatrixXd full = g.selfadjointView<Eigen::Lower>();
  if (!full.allFinite() || !std::isfinite(cost)) return false;
  const Eigen::MatrixXd jtj = full.topLeftCorner(P, P);
  const Eigen::VectorXd jtr = full.topRightCorner(P, 1);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jtj);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::MatrixXd& v = eig.eigenvectors();
  // Directions with eigenvalues below this carry no gradient (J^T r lies in range(J^T J)).
  const double cut = 1e-14 * std::max(lambda.maxCoeff(), 0.0);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> jac(jacobian,
                                                                                         P + 1, P);
  double z2 = 0;
  for (int k = 0; k < P; ++k) {
    if (lambda[k] > cut && lambda[k] > 0) {
      const double sl = std::sqrt(lambda[k]);
      jac.row(k) = sl * v.col(k).transpose();
      residuals[k] = v.col(k).dot(jtr) / sl;
    } else {
      jac.row(k).setZero();
      residuals[k] = 0.0;
    }
    z2 += residuals[k] * residuals[k];
  }
  jac.row(P).setZero();
  if (z2 > cost) {
    // Only through rounding (|z|^2 <= r^T r exactly): keep the cost exact.
    const double f = z2 > 0 ? std::sqrt(cost / z2) : 0.0;
    for (int k = 0; k < P; ++k) residuals[k] *= f;
    z2 = cost;
  }
  residuals[P] = std::sqrt(cost - z2);
  return jac.allFinite() && std::isfinite(residuals[P]);
}

}  // namespace brdfit::internal
