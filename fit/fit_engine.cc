// The fit of one model: initializer, Levenberg-Marquardt stages, result and metrics
// (pipeline described in fit/fitter.h).
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "fit/bounded_lm.h"
#include "fit/grid_init.h"
#include "fit/metrics.h"
#include "fit/model_ops.h"
#include "fit/rendered_polish.h"
#include "fit/threads.h"

namespace brdfit::internal {

namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Blocks per problem: enough for Ceres' threads and short accumulations, few enough that the
// per-block eigen-decompositions stay negligible.
std::size_t NumBlocks(std::size_t samples) {
  return std::clamp<std::size_t>(samples / 256, 1, 64);
}

void AddBlocks(const ModelOps& ops, const Samples& s, const LossData& l,
               const ceres::LossFunction* robust, double* x, ceres::Problem* problem) {
  const std::size_t ns = s.NumSamples(), nb = NumBlocks(ns);
  for (std::size_t b = 0; b < nb; ++b) {
    const std::size_t begin = ns * b / nb, end = ns * (b + 1) / nb;
    if (begin == end) continue;
    problem->AddResidualBlock(ops.make_block(s, l, ops.layout, robust, begin, end), nullptr, x);
  }
}

// LM on the fit set's blocks within the bounds (fit/bounded_lm.h).
BoundedLmRun RunLm(const ModelOps& ops, const Samples& s, const LossData& l,
                   const ceres::LossFunction* robust, const FitOptions& opt, double* x) {
  ceres::Solver::Options so = LmSolverOptions(opt.threads);
  so.function_tolerance = opt.function_tolerance;
  so.parameter_tolerance = opt.parameter_tolerance;
  so.gradient_tolerance = opt.gradient_tolerance;
  return RunBoundedLm(
      ops.layout,
      [&](double* xb, ceres::Problem* problem) { AddBlocks(ops, s, l, robust, xb, problem); }, so,
      opt.max_iterations, x);
}

}  // namespace

ceres::Solver::Options LmSolverOptions(int threads) {
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.num_threads = std::max(threads, 1);
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  return so;
}

FitResult FitWithOps(const ModelOps& ops, const Samples& fit, const LossData& loss,
                     const Samples& metric, const FitOptions& opt,
                     const RenderedReference* polish_on) {
  const ParamLayout& layout = ops.layout;
  const std::size_t P = layout.size();
  FitResult r;
  r.model = ops.name;
  r.param_names = ops.param_names;
  r.params.assign(P, 0.0);
  r.at_bound.assign(P, false);
  r.fit_samples = fit.NumSamples();
  r.fit_cells = fit.NumObservations();
  r.sample_counts = fit.counts;
  r.metrics.weighting = ToString(metric.options.weighting);
  r.metrics.cutoff_deg = metric.options.cutoff_deg;
  if (fit.NumSamples() == 0 || !(fit.total_weight > 0)) {
    r.status = FitStatus::kFailed;
    r.message = "no usable cells: every cell is invalid, non-finite or beyond the cut-off";
    return r;
  }
  const std::unique_ptr<ceres::LossFunction> robust = MakeRobustLoss(opt);

  // 1. Initializer on a stratified subset.
  auto t0 = Clock::now();
  double c0 = ThreadCpuMs();
  const Samples init_set = Subsample(fit, opt.init_samples, opt.seed);
  const LossData init_loss = PrepareLoss(init_set, opt);
  GridInitializer grid(init_set, init_loss, layout, ops.components, robust.get());
  const std::vector<InitCandidate> starts = grid.Run(std::max(opt.multistart, 1));
  r.times.init = MsSince(t0);
  r.times.init_cpu = ThreadCpuMs() - c0;
  if (!starts.empty() && std::isfinite(starts.front().cost)) r.init_cost = starts.front().cost;

  // 2. LM from each start; on a coarse subset first when the fit set is large.
  t0 = Clock::now();
  c0 = ThreadCpuMs();
  const bool coarse = opt.coarse_samples > 0 && fit.NumSamples() > 4 * opt.coarse_samples;
  Samples coarse_set;
  LossData coarse_loss;
  // The coarse stage is cheap: it runs to a 1000x tighter tolerance, so that the expensive
  // full-set stage starts as close as the subset allows and needs only a few iterations.
  FitOptions coarse_opt = opt;
  coarse_opt.function_tolerance = opt.function_tolerance * 1e-3;
  if (coarse) {
    coarse_set = Subsample(fit, opt.coarse_samples, opt.seed + 1);
    coarse_loss = PrepareLoss(coarse_set, opt);
  }
  bool have_best = false;
  double best_cost = 0;
  std::vector<double> best_x;
  ceres::Solver::Summary best_summary;
  std::string last_failure;
  for (const InitCandidate& start : starts) {
    std::vector<double> x(P);
    bool finite_start = true;
    for (std::size_t i = 0; i < P; ++i) {
      x[i] = std::clamp(layout.ToOpt(i, start.params[i]), layout.lower_opt[i], layout.upper_opt[i]);
      finite_start = finite_start && std::isfinite(x[i]);
    }
    if (!finite_start) {
      last_failure = "initializer produced non-finite parameters";
      continue;
    }
    ++r.starts;
    if (coarse) {
      std::vector<double> xc = x;
      const BoundedLmRun run =
          RunLm(ops, coarse_set, coarse_loss, robust.get(), coarse_opt, xc.data());
      r.iterations += run.iterations;
      if (run.finite) x = xc;  // else continue from the grid point
    }
    const BoundedLmRun run = RunLm(ops, fit, loss, robust.get(), opt, x.data());
    r.iterations += run.iterations;
    const bool usable = run.finite && run.summary.termination_type != ceres::FAILURE &&
                        run.summary.termination_type != ceres::USER_FAILURE;
    if (!usable) {
      last_failure = run.finite ? run.summary.message : "non-finite cost or parameters";
      continue;
    }
    if (!have_best || run.summary.final_cost < best_cost) {
      have_best = true;
      best_cost = run.summary.final_cost;
      best_x = x;
      best_summary = run.summary;
    }
  }
  // 2b. The rendered polish (fit/rendered_polish.h), counted in the solve's time. Not for a fit
  // that expresses its table (RMS loss residual below 1e-4, in the loss's units: a synthetic table
  // of the model itself): there the table's cells are the truth, and all the polish could fit is
  // the rendered images' interpolation of them (fit/rendered_error.h, RenderedLookup).
  constexpr double kExpressedCost = 1e-8;  // mean squared loss residual (final_cost)
  std::optional<RenderedError> polished_rendered;  // the polish scored what it returned
  if (have_best && polish_on != nullptr && 2.0 * best_cost > kExpressedCost) {
    RenderedPolishOptions po;
    po.threads = opt.threads;
    const RenderedPolishOutcome polish = PolishOnRendered(ops, *polish_on, po, best_x);
    r.iterations += polish.iterations;
    if (polish.ran) polished_rendered = polish.rendered;
    if (polish.improved) {
      // final_cost is the table loss at the result: re-evaluated at the polished parameters.
      ceres::Problem problem;
      AddBlocks(ops, fit, loss, robust.get(), best_x.data(), &problem);
      double cost = 0;
      if (problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr)) {
        best_cost = cost;
      }
    }
  }
  r.times.solve = MsSince(t0);
  r.times.solve_cpu = ThreadCpuMs() - c0;

  if (!have_best) {
    r.status = FitStatus::kFailed;
    r.message = "solver failed: " + last_failure;
    if (!starts.empty()) {
      for (std::size_t i = 0; i < P; ++i) {
        const double v = starts.front().params[i];
        r.params[i] = std::isfinite(v) ? v : 0.0;
      }
    }
    return r;
  }
  r.termination = ceres::TerminationTypeToString(best_summary.termination_type);
  r.final_cost = 2.0 * best_cost;  // Ceres reports 1/2 sum r^2
  for (std::size_t i = 0; i < P; ++i) {
    // exp(log(upper)) can land one ulp beyond the bound (abc.c = 10.000000000000002 for
    // nbrdf:black-fabric), which every reader refuses (core/model_params.h): the report could
    // not be resumed or merged. The bounds are the model's domain: clamp into them.
    r.params[i] =
        std::clamp(layout.FromOpt(i, best_x[i]), layout.specs[i].lower, layout.specs[i].upper);
    const double span = layout.upper_opt[i] - layout.lower_opt[i];
    r.at_bound[i] = best_x[i] <= layout.lower_opt[i] + 1e-9 * span ||
                    best_x[i] >= layout.upper_opt[i] - 1e-9 * span;
  }
  r.status = best_summary.termination_type == ceres::CONVERGENCE ? FitStatus::kConverged
                                                                 : FitStatus::kNoConvergence;
  if (r.status == FitStatus::kNoConvergence) r.message = best_summary.message;

  // 3. Metrics on the metric set.
  t0 = Clock::now();
  c0 = ThreadCpuMs();
  // The model on every sample of the metric set, chunk by chunk as the metrics take them, the
  // chunks shared by --threads (each sample's prediction is independent; the sums are chunked:
  // same bits for any number of threads).
  r.metrics = ComputeMetricsStreamed(
      metric,
      [&](std::size_t begin, std::size_t end, double* out) {
        ops.eval_samples(r.params.data(), metric, begin, end, out);
      },
      opt.threads);
  // The rendered metric of the result, when the polish already computed it at these parameters
  // (else the caller scores it: fit/fitter.cc).
  if (polished_rendered) r.metrics.rendered = *polished_rendered;
  r.times.metrics = MsSince(t0);
  r.times.metrics_cpu = ThreadCpuMs() - c0;
  if (!r.metrics.ok) {
    r.status = FitStatus::kFailed;
    r.message = "metrics: " + r.metrics.problem;
  }
  return r;
}

NormalEquations NormalEquationsWithOps(const ModelOps& ops, const Samples& s, const LossData& l,
                                       const FitOptions& opt, const std::vector<double>& params) {
  const std::size_t P = ops.layout.size();
  const std::unique_ptr<ceres::LossFunction> robust = MakeRobustLoss(opt);
  std::vector<double> x(P);
  for (std::size_t i = 0; i < P; ++i) x[i] = ops.layout.ToOpt(i, params[i]);
  ceres::Problem problem;
  AddBlocks(ops, s, l, robust.get(), x.data(), &problem);
  double cost = 0;
  std::vector<double> gradient;
  ceres::CRSMatrix jac;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, &gradient, &jac);
  NormalEquations ne;
  ne.cost = 2.0 * cost;
  ne.gradient = gradient;
  ne.jtj.assign(P * P, 0.0);
  for (int row = 0; row < jac.num_rows; ++row) {
    for (int a = jac.rows[row]; a < jac.rows[row + 1]; ++a) {
      for (int b = jac.rows[row]; b < jac.rows[row + 1]; ++b) {
        ne.jtj[jac.cols[a] * P + jac.cols[b]] += jac.values[a] * jac.values[b];
      }
    }
  }
  return ne;
}

}  // namespace brdfit::internal
