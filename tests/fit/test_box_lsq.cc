// Box-constrained least squares: the Karush-Kuhn-Tucker conditions of the convex QP are the
// oracle (Nocedal & Wright 2006, Numerical Optimization, Thm. 12.1 / §16.6).
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "fit/box_lsq.h"

namespace brdfit {
namespace {

void ExpectKkt(const Eigen::MatrixXd& N, const Eigen::VectorXd& b, const Eigen::VectorXd& lo,
               const Eigen::VectorXd& hi, const Eigen::VectorXd& x, double tol) {
  const Eigen::VectorXd g = N * x - b;  // half the gradient of x^T N x - 2 b^T x
  const double scale = 1.0 + b.cwiseAbs().maxCoeff();
  for (int i = 0; i < x.size(); ++i) {
    ASSERT_GE(x[i], lo[i] - 1e-12);
    ASSERT_LE(x[i], hi[i] + 1e-12);
    if (x[i] > lo[i] + 1e-9 && x[i] < hi[i] - 1e-9) {
      EXPECT_NEAR(g[i] / scale, 0.0, tol) << "free " << i;
    } else if (x[i] <= lo[i] + 1e-9) {
      EXPECT_GE(g[i] / scale, -tol) << "at lower " << i;
    } else {
      EXPECT_LE(g[i] / scale, tol) << "at upper " << i;
    }
  }
}

TEST(BoxLeastSquares, SatisfiesKktOnRandomProblems) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  const double inf = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= 7; ++k) {
    for (int trial = 0; trial < 40; ++trial) {
      Eigen::MatrixXd a(3 * k, k);
      for (int i = 0; i < a.size(); ++i) a.data()[i] = n01(rng);
      Eigen::VectorXd y(3 * k);
      for (int i = 0; i < y.size(); ++i) y[i] = n01(rng);
      const Eigen::MatrixXd N = a.transpose() * a;
      const Eigen::VectorXd b = a.transpose() * y;
      Eigen::VectorXd lo = Eigen::VectorXd::Zero(k), hi(k);
      for (int i = 0; i < k; ++i) hi[i] = (trial % 3 == 0) ? inf : 0.2 + std::abs(n01(rng));
      const Eigen::VectorXd x = BoxLeastSquares(N, b, lo, hi);
      // Enumeration (k <= 5) is exact; projected Gauss-Seidel converges to KKT.
      ExpectKkt(N, b, lo, hi, x, k <= 5 ? 1e-9 : 1e-6);
    }
  }
}

TEST(BoxLeastSquares, UnconstrainedOptimumWhenInside) {
  Eigen::MatrixXd N(2, 2);
  N << 2, 0.5, 0.5, 1;
  const Eigen::VectorXd x_true = Eigen::Vector2d(0.3, 0.4);
  const Eigen::VectorXd b = N * x_true;
  const Eigen::VectorXd x = BoxLeastSquares(N, b, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_NEAR(x[0], 0.3, 1e-14);
  EXPECT_NEAR(x[1], 0.4, 1e-14);
}

TEST(BoxLeastSquares, CollinearColumnsStayFeasible) {
  // Two identical basis functions (a diffuse and a very broad lobe at their limit).
  Eigen::MatrixXd N(2, 2);
  N << 1, 1, 1, 1;
  const Eigen::VectorXd x =
      BoxLeastSquares(N, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_NEAR(x[0] + x[1], 0.5, 1e-12);
  EXPECT_GE(x.minCoeff(), 0.0);
}

}  // namespace
}  // namespace brdfit
