// Speed of preparing a table for fitting (fit/fitter.h PrepareTable, docs/fitting.md) on the
// MERL grid (90 x 90 x 180), one thread, default sample options (stride:32, 80-degree cut-off,
// bin-measure weights), split into its stages: the rendered metric's reference
// (PrepareRenderedReference), the metric set (PrepareMetricSamples), the fit set (SelectBudget)
// and the loss constants (PrepareLoss), and the whole PrepareTable without and with a warm
// PrepareCache (fit/prepare_cache.h) (the second table of a batch). Table: the synthetic Lambert +
// GGX table of bench_fit (10 % holes), so that the mask is not the grid's.
#include <benchmark/benchmark.h>

#include "bench/bench_tables.h"
#include "fit/fitter.h"
#include "fit/prepare_cache.h"
#include "fit/loss.h"
#include "fit/rendered_error.h"
#include "fit/sample_plan.h"
#include "fit/samples.h"

namespace {

using namespace brdfit;

const Table& BenchTable() {
  static const Table t = bench::SyntheticLambertGgxTable();
  return t;
}

SampleOptions Defaults() {
  SampleOptions o;
  o.budget = DefaultFitBudget();
  return o;
}

void BM_RenderedReference(benchmark::State& state) {
  for (auto _ : state) {
    RenderedReference r = PrepareRenderedReference(BenchTable());
    benchmark::DoNotOptimize(r.pixels.data());
  }
}
BENCHMARK(BM_RenderedReference)->Unit(benchmark::kMillisecond);

void BM_MetricSamples(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    Table copy = BenchTable();
    state.ResumeTiming();
    Samples s = PrepareMetricSamples(std::move(copy), Defaults());
    benchmark::DoNotOptimize(s.cell.data());
  }
}
BENCHMARK(BM_MetricSamples)->Unit(benchmark::kMillisecond);

// The grid's part alone (once per batch), and the metric set from a ready plan (per table).
void BM_SamplePlan(benchmark::State& state) {
  for (auto _ : state) {
    SamplePlan p = MakeSamplePlan(Grid::Merl(), Defaults());
    benchmark::DoNotOptimize(p.cell.data());
  }
}
BENCHMARK(BM_SamplePlan)->Unit(benchmark::kMillisecond);

void BM_MetricSamplesFromPlan(benchmark::State& state) {
  const SamplePlan plan = MakeSamplePlan(Grid::Merl(), Defaults());
  for (auto _ : state) {
    state.PauseTiming();
    Table copy = BenchTable();
    state.ResumeTiming();
    Samples s = PrepareMetricSamples(std::move(copy), plan, Defaults());
    benchmark::DoNotOptimize(s.cell.data());
  }
}
BENCHMARK(BM_MetricSamplesFromPlan)->Unit(benchmark::kMillisecond);

void BM_RenderedPlan(benchmark::State& state) {
  for (auto _ : state) {
    RenderedPlan p = MakeRenderedPlan(Grid::Merl());
    benchmark::DoNotOptimize(p.lit.data());
  }
}
BENCHMARK(BM_RenderedPlan)->Unit(benchmark::kMillisecond);

void BM_RenderedReferenceFromPlan(benchmark::State& state) {
  const RenderedPlan plan = MakeRenderedPlan(Grid::Merl());
  for (auto _ : state) {
    RenderedReference r = PrepareRenderedReference(BenchTable(), plan);
    benchmark::DoNotOptimize(r.pixels.data());
  }
}
BENCHMARK(BM_RenderedReferenceFromPlan)->Unit(benchmark::kMillisecond);

void BM_SelectBudget(benchmark::State& state) {
  Table copy = BenchTable();
  const Samples metric = PrepareMetricSamples(std::move(copy), Defaults());
  for (auto _ : state) {
    Samples s = SelectBudget(metric, DefaultFitBudget(), 1);
    benchmark::DoNotOptimize(s.cell.data());
  }
}
BENCHMARK(BM_SelectBudget)->Unit(benchmark::kMillisecond);

void BM_PrepareLoss(benchmark::State& state) {
  const Samples fit = PrepareSamples(BenchTable(), Defaults());
  for (auto _ : state) {
    LossData l = PrepareLoss(fit, LogLossUnpolished());
    benchmark::DoNotOptimize(l.mult.data());
  }
}
BENCHMARK(BM_PrepareLoss)->Unit(benchmark::kMillisecond);

// The whole preparation as brdfit fit runs it (consuming the table); arg 0: no cache (one
// table), arg 1: a warm cache (every later table of a batch on the same grid and options).
void BM_PrepareTable(benchmark::State& state) {
  PrepareCache cache;
  PrepareCache* use = state.range(0) ? &cache : nullptr;
  if (use) {
    Table warm = BenchTable();
    benchmark::DoNotOptimize(PrepareTable(std::move(warm), Defaults(), LogLossUnpolished(), use));
  }
  for (auto _ : state) {
    state.PauseTiming();
    Table copy = BenchTable();
    state.ResumeTiming();
    PreparedTable p = PrepareTable(std::move(copy), Defaults(), LogLossUnpolished(), use);
    benchmark::DoNotOptimize(p.fit.cell.data());
  }
}
BENCHMARK(BM_PrepareTable)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
