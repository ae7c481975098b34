// What the (non-template) fit engine needs to know about a catalog model: its names, parameter
// layout, a double evaluator and a factory for its autodiff residual blocks. The only
// per-model template code is the residual block (fit/block_cost.h), instantiated in
// fit/problem_instances_*.cc.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/solver.h>

#include <string>
#include <vector>

#include "fit/fitter.h"
#include "fit/grid_init.h"
#include "fit/loss.h"
#include "fit/param_layout.h"
#include "fit/samples.h"

namespace brdfit::internal {

using MakeBlockFn = ceres::CostFunction* (*)(const Samples&, const LossData&, const ParamLayout&,
                                             const ceres::LossFunction*, std::size_t begin,
                                             std::size_t end);
struct PolishPixels;
using MakePixelBlockFn = ceres::CostFunction* (*)(const PolishPixels&, const ParamLayout&,
                                                  std::size_t begin, std::size_t end);

// The model at samples [begin, end) of a set: 3 values per sample into rgb[3 (s - begin)], the
// values of eval at SampleGeometry, bit for bit, without a call through a pointer per sample
// (the metric pass: every cell of the table).
using EvalSamplesFn = void (*)(const double* p, const Samples& samples, std::size_t begin,
                               std::size_t end, double* rgb);

struct ModelOps {
  std::size_t catalog_index = 0;
  std::string name;
  std::vector<std::string> param_names;
  ParamLayout layout;
  EvalFn eval = nullptr;
  std::vector<ComponentOps> components;  // its lobes (a sum) or itself (fit/grid_init.h)
  MakeBlockFn make_block = nullptr;
  MakePixelBlockFn make_pixel_block = nullptr;  // the rendered polish's (fit/pixel_cost.h)
  EvalSamplesFn eval_samples = nullptr;
};

// Each fit/problem_instances_K.cc registers the catalog models with index % kShards == K.
inline constexpr std::size_t kShards = 3;
void RegisterModels0(std::vector<ModelOps>& out);
void RegisterModels1(std::vector<ModelOps>& out);
void RegisterModels2(std::vector<ModelOps>& out);

// Levenberg-Marquardt (Ceres trust region, dense QR, silent) with `threads` threads: the
// settings every solve of the engine and the rendered polish shares (fit/fit_engine.cc).
ceres::Solver::Options LmSolverOptions(int threads);

// The engine (fit/fit_engine.cc).
// polish_on: the rendered reference of options.polish == kRendered (nullptr: no polish).
FitResult FitWithOps(const ModelOps& ops, const Samples& fit, const LossData& loss,
                     const Samples& metric, const FitOptions& options,
                     const RenderedReference* polish_on = nullptr);
NormalEquations NormalEquationsWithOps(const ModelOps& ops, const Samples& samples,
                                       const LossData& loss, const FitOptions& options,
                                       const std::vector<double>& params);

}  // namespace brdfit::internal
