// Speed of the rendered-image metric (fit/rendered_error.h): ComputeRenderedError on a full
// MERL-grid table (90 x 90 x 180) against a Lambert + GGX approximation, default scene (64 x 64,
// six lights), one thread. Medians over 5 repetitions. Tables: a noisy synthetic one with holes
// and, when ../shared/data/merl_nbrdf.zip is present, gold-metallic-paint against its default
// lambert+ggx fit (counters: the metric's numbers).
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_tables.h"
#include "core/model_params.h"
#include "fit/fitter.h"
#include "fit/rendered_error.h"
#include "io/nbrdf.h"
#include "models/registry.h"

namespace {

using namespace brdfit;
namespace fs = std::filesystem;

const fs::path kZip = bench::NbrdfZip();

struct Case {
  std::string name;
  Table table;
  std::vector<double> params;  // lambert+ggx
};

std::vector<Case> LoadCases() {
  const ModelInfo& m = *FindModel("lambert+ggx");
  std::vector<Case> cases;
  // The approximation: a wider lobe and a redder body than the table's lambert+ggx.
  cases.push_back({"synthetic-lambert-ggx-0.08", bench::SyntheticLambertGgxTable(),
                   ResolveModelParams(m, {"kd_r=0.3", "kd_g=0.1", "kd_b=0.05", "ks_r=0.4",
                                          "ks_g=0.4", "ks_b=0.3", "alpha=0.1"})});
  if (!fs::exists(kZip)) {
    fmt::print(stderr, "{} not found: NBRDF table skipped\n", kZip.string());
    return cases;
  }
  NbrdfTabulation tab = TabulateNbrdf(ReadNbrdf(kZip, "gold-metallic-paint"), Grid::Merl(), 1);
  const FitResult fit = FitTable("lambert+ggx", tab.table, SampleOptions{}, LogLossUnpolished());
  cases.push_back({"nbrdf-gold-metallic-paint", std::move(tab.table), fit.params});
  return cases;
}

void BM_RenderedError(benchmark::State& state, const Case* c) {
  const BrdfFunction approx = ModelBrdf(*FindModel("lambert+ggx"), c->params);
  RenderedError r;
  for (auto _ : state) {
    r = ComputeRenderedError(c->table, approx);
    // The whole struct: DoNotOptimize on a double lvalue returned garbage here (GCC 12,
    // benchmark 1.7.1; google/benchmark issue 903).
    benchmark::DoNotOptimize(r);
  }
  state.counters["psnr_db"] = r.psnr_db;
  state.counters["psnr_srgb_db"] = r.psnr_srgb_db;
  state.counters["median_rel"] = r.median_rel_error;
  state.counters["p95_rel"] = r.p95_rel_error;
  state.counters["lit_px"] = static_cast<double>(r.lit_pixels);
  state.SetLabel(r.ok ? "ok" : r.problem);
}

}  // namespace

int main(int argc, char** argv) {
  static const std::vector<Case> cases = LoadCases();
  for (const Case& c : cases) {
    benchmark::RegisterBenchmark(("rendered_error/" + c.name).c_str(), BM_RenderedError, &c)
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
