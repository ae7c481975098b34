// The active-set Levenberg-Marquardt (fit/bounded_lm.h) on straight-line fits whose bounded
// least-squares solutions are known in closed form: a bound that binds is held exactly, one
// that starts active but whose gradient points into the box is released, and a problem whose
// every parameter is held ends as a KKT point.
#include <gtest/gtest.h>

#include <ceres/autodiff_cost_function.h>

#include <array>
#include <cmath>
#include <vector>

#include "fit/bounded_lm.h"
#include "fit/model_ops.h"

namespace brdfit::internal {
namespace {

// y_i - (a + b x_i): one residual block per point.
struct LineResidual {
  double x, y;
  template <class T>
  bool operator()(const T* p, T* r) const {
    r[0] = T(y) - (p[0] + p[1] * x);
    return true;
  }
};

ParamLayout Layout(double a_lo, double a_hi, double b_lo, double b_hi) {
  const std::array<ParamSpec, 2> specs = {ParamSpec{"a", "1", a_lo, a_hi, 0.0, false, "intercept"},
                                          ParamSpec{"b", "1", b_lo, b_hi, 0.0, false, "slope"}};
  return ParamLayout::Of(specs);  // copies the specs
}

struct Line {
  std::vector<double> x, y;
  AddResidualBlocks Blocks() const {
    return [this](double* p, ceres::Problem* problem) {
      for (std::size_t i = 0; i < x.size(); ++i) {
        problem->AddResidualBlock(new ceres::AutoDiffCostFunction<LineResidual, 1, 2>(
                                      new LineResidual{x[i], y[i]}),
                                  nullptr, p);
      }
    };
  }
  double MeanY() const {
    double s = 0;
    for (double v : y) s += v;
    return s / static_cast<double>(y.size());
  }
};

// Falling data: the unconstrained slope is negative, so under b >= 0 the solution is b = 0 and
// a = mean(y) (the least squares of a constant).
const Line kFalling{{0, 1, 2, 3, 4}, {5.0, 4.1, 2.9, 2.2, 0.8}};

TEST(BoundedLm, HoldsABindingBoundExactly) {
  const ParamLayout layout = Layout(-10, 10, 0, 10);
  double p[2] = {0.0, 1.0};  // interior start
  const BoundedLmRun run = RunBoundedLm(layout, kFalling.Blocks(), LmSolverOptions(1), 100, p);
  ASSERT_TRUE(run.finite);
  EXPECT_EQ(run.summary.termination_type, ceres::CONVERGENCE) << run.summary.message;
  EXPECT_EQ(p[1], 0.0);  // on the bound, not near it
  // To LM's function tolerance (1e-6 relative to a cost that the misfit dominates).
  EXPECT_NEAR(p[0], kFalling.MeanY(), 1e-4);
  EXPECT_LT(run.iterations, 100);
}

TEST(BoundedLm, ReleasesABoundWhoseGradientPointsIn) {
  // Rising data, slope 1.5 exactly; the start sits on the slope's lower bound 0.
  const Line rising{{0, 1, 2, 3}, {1.0, 2.5, 4.0, 5.5}};
  const ParamLayout layout = Layout(-10, 10, 0, 10);
  double p[2] = {0.0, 0.0};
  const BoundedLmRun run = RunBoundedLm(layout, rising.Blocks(), LmSolverOptions(1), 100, p);
  ASSERT_TRUE(run.finite);
  EXPECT_NEAR(p[0], 1.0, 1e-8);
  EXPECT_NEAR(p[1], 1.5, 1e-8);
}

TEST(BoundedLm, EveryParameterHeldIsAKktPoint) {
  // With a = 0 the slope wants to be negative (sum x y < 0) and with b = 0 the intercept wants to
  // be positive (sum y > 0): a <= 0 and b >= 0 both bind, and the start is the solution.
  const Line line{{-2, -1, 0, 1, 2}, {3.0, 2.0, 1.0, 0.0, -1.0}};
  const ParamLayout layout = Layout(-10, 0, 0, 10);
  double p[2] = {0.0, 0.0};
  const BoundedLmRun run = RunBoundedLm(layout, line.Blocks(), LmSolverOptions(1), 100, p);
  ASSERT_TRUE(run.finite);
  EXPECT_EQ(run.summary.termination_type, ceres::CONVERGENCE);
  EXPECT_NE(run.summary.message.find("KKT"), std::string::npos) << run.summary.message;
  EXPECT_EQ(p[0], 0.0);
  EXPECT_EQ(p[1], 0.0);
  EXPECT_EQ(run.iterations, 0);
}

TEST(BoundedLm, IterationBudgetSpansTheRounds) {
  const ParamLayout layout = Layout(-10, 10, 0, 10);
  double p[2] = {0.0, 1.0};
  const BoundedLmRun run = RunBoundedLm(layout, kFalling.Blocks(), LmSolverOptions(1), 1, p);
  EXPECT_LE(run.iterations, 1);
}

}  // namespace
}  // namespace brdfit::internal
