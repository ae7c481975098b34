// Levenberg-Marquardt within box bounds, with an active set: the solver of the table fit
// (fit/fit_engine.cc) and of the rendered polish (fit/rendered_polish.cc).
//
// Ceres projects steps that leave the box, but its Gauss-Newton step still assumes the clipped
// coordinates move, so a parameter pinned on a bound (no diffuse part in a metal) makes it crawl:
// 57 iterations on a full table, or a projected line search of up to 20 evaluations per
// iteration. Instead, parameters on a bound are held there (ceres::SubsetManifold) while LM runs
// on the others; then the gradient decides: a held parameter whose gradient points into the box
// is released, one that reached a bound with the gradient pushing out is held; repeat until the
// set is stable (Nocedal & Wright 2006, Numerical Optimization, §16.5, active-set methods).
#pragma once

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <functional>

#include "fit/param_layout.h"

namespace brdfit::internal {

struct BoundedLmRun {
  ceres::Solver::Summary summary;  // of the last round
  int iterations = 0;              // all rounds
  bool finite = false;             // final cost and parameters finite
};

// Adds the problem's residual blocks on parameter block x (P = layout.size() values).
using AddResidualBlocks = std::function<void(double* x, ceres::Problem* problem)>;

// Runs LM from x (optimization space, within the layout's bounds), updating x. At most
// max_iterations LM iterations over all rounds; so's other settings are used as given.
BoundedLmRun RunBoundedLm(const ParamLayout& layout, const AddResidualBlocks& add_blocks,
                          ceres::Solver::Options so, int max_iterations, double* x);

}  // namespace brdfit::internal
