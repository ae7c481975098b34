#include "fit/bounded_lm.h"

#include <ceres/manifold.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace brdfit::internal {

namespace {

int Iterations(const ceres::Solver::Summary& s) {
  // summary.iterations[0] is the evaluation at the starting point.
  return std::max<int>(static_cast<int>(s.iterations.size()) - 1, 0);
}

// Indices of x on a bound (within a relative 1e-12 of the range), snapped onto it.
std::vector<int> OnBounds(const ParamLayout& layout, double* x) {
  std::vector<int> on;
  for (std::size_t i = 0; i < layout.size(); ++i) {
    const double lo = layout.lower_opt[i], hi = layout.upper_opt[i];
    const double tol = 1e-12 * (hi - lo);
    if (x[i] <= lo + tol) {
      x[i] = lo;
      on.push_back(static_cast<int>(i));
    } else if (x[i] >= hi - tol) {
      x[i] = hi;
      on.push_back(static_cast<int>(i));
    }
  }
  return on;
}

}  // namespace

BoundedLmRun RunBoundedLm(const ParamLayout& layout, const AddResidualBlocks& add_blocks,
                          ceres::Solver::Options so, int max_iterations, double* x) {
  const int P = static_cast<int>(layout.size());
  BoundedLmRun run;
  std::vector<int> held = OnBounds(layout, x);
  constexpr int kMaxRounds = 4;
  for (int round = 0; round < kMaxRounds; ++round) {
    ceres::Problem::Options po;
    po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(po);
    add_blocks(x, &problem);
    for (int i = 0; i < P; ++i) {
      problem.SetParameterLowerBound(x, i, layout.lower_opt[i]);
      problem.SetParameterUpperBound(x, i, layout.upper_opt[i]);
    }
    std::unique_ptr<ceres::SubsetManifold> subset;
    if (!held.empty() && static_cast<int>(held.size()) < P) {
      subset = std::make_unique<ceres::SubsetManifold>(P, held);
      problem.SetManifold(x, subset.get());
    }
    so.max_num_iterations = std::max(max_iterations - run.iterations, 0);
    if (static_cast<int>(held.size()) == P) so.max_num_iterations = 0;
    ceres::Solve(so, &problem, &run.summary);
    run.iterations += Iterations(run.summary);
    // Ceres #988: CONVERGENCE can come with an infinite cost. Check everything.
    run.finite = std::isfinite(run.summary.final_cost);
    for (int i = 0; i < P; ++i) run.finite = run.finite && std::isfinite(x[i]);
    if (!run.finite || run.summary.termination_type == ceres::FAILURE) return run;

    std::vector<int> on = OnBounds(layout, x);
    if (on.empty() && held.empty()) return run;  // interior: nothing to check
    if (subset) problem.SetManifold(x, nullptr);
    double cost = 0;
    std::vector<double> gradient;
    if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, &gradient, nullptr)) {
      return run;
    }
    std::vector<int> next;
    for (int i : on) {
      const bool at_lower = x[i] == layout.lower_opt[i];
      if (at_lower ? gradient[i] >= 0 : gradient[i] <= 0) next.push_back(i);
    }
    if (next == held) {
      if (static_cast<int>(held.size()) == P) {
        // Every parameter on a bound with the gradient pointing out of the box: a KKT point.
        // Ceres ran no iteration (max_num_iterations = 0) and calls that NO_CONVERGENCE.
        run.summary.termination_type = ceres::CONVERGENCE;
        run.summary.message =
            "every parameter on a bound, the gradient pointing out of the box (KKT point)";
      }
      return run;
    }
    held = next;
    if (run.iterations >= max_iterations) return run;
  }
  return run;
}

}  // namespace brdfit::internal
