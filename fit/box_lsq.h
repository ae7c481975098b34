// Small box-constrained linear least squares, for the colour weights of the initializer.
#pragma once

#include <Eigen/Core>

namespace brdfit {

// Minimizes q(x) = x^T N x - 2 b^T x subject to lo <= x <= hi (N symmetric positive
// semi-definite, K = N.rows()). Bounds may be infinite. For K <= 5 every assignment of the
// variables to {free, at lower, at upper} is solved and the best feasible one kept (exact:
// the optimum is one of them); larger K use projected Gauss-Seidel (200 sweeps).
Eigen::VectorXd BoxLeastSquares(const Eigen::MatrixXd& N, const Eigen::VectorXd& b,
                                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi);

}  // namespace brdfit
