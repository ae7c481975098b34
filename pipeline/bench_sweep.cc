#include "pipeline/bench_sweep.h"

#include <algorithm>
#include <chrono>

#include "fit/fitter.h"

namespace brdfit::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

report::BenchPoint ToPoint(const BenchTable& t, LossKind loss, const Budget& budget,
                           const FitResult& r, double prepare_ms) {
  report::BenchPoint b;
  b.material = t.material;
  b.table = t.source;
  b.model = r.model;
  b.loss = ToString(loss);
  b.budget = budget.ToString();
  b.status = ToString(r.status);
  b.message = r.message;
  b.prepare_ms = prepare_ms;
  b.init_ms = r.times.init;
  b.solve_ms = r.times.solve;
  b.time_ms = prepare_ms + r.times.init + r.times.solve;
  b.fit_cells = r.fit_cells;
  b.iterations = r.iterations;
  b.metrics = r.metrics;
  return b;
}

}  // namespace

std::vector<report::BenchPoint> RunBenchSweep(const BenchTable& t, const BenchConfig& config,
                                              const BenchCallbacks& callbacks) {
  const int repeats = std::max(config.repeats, 1);
  std::vector<report::BenchPoint> points;
  FitOptions fo = config.fit;
  for (const LossKind loss : config.losses) {
    fo.loss = loss;
    for (const Budget& budget : config.budgets) {
      SampleOptions so = config.samples;
      so.budget = budget;
      std::vector<double> prepare;
      PreparedTable prepared;
      for (int k = 0; k < repeats; ++k) {
        const auto t0 = Clock::now();
        prepared = PrepareTable(t.table, so, fo);
        prepare.push_back(MsSince(t0));
      }
      for (const std::string& model : config.models) {
        if (callbacks.on_start) {
          callbacks.on_start(t.material + " " + model + " " + budget.ToString());
        }
        FitResult first;
        std::vector<double> init, solve;
        for (int k = 0; k < repeats; ++k) {
          FitResult r = FitPrepared(model, prepared, fo);
          init.push_back(r.times.init);
          solve.push_back(r.times.solve);
          if (k == 0) first = std::move(r);
        }
        first.times.init = Median(init);
        first.times.solve = Median(solve);
        points.push_back(ToPoint(t, loss, budget, first, Median(prepare)));
        if (callbacks.on_point) callbacks.on_point(points.back());
      }
    }
  }
  return points;
}

}  // namespace brdfit::pipeline
