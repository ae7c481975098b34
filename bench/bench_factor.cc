// Factorization benchmarks on the MERL grid (90 x 90 x 180, ~1.1 M usable cells): one material
// factored with a cold cache (build + factor the system, then solve) and with the system reused
// from the cache (logs, A^T W y, triangular solves, bake), at 32^2 and 64^2 texels, for both
// parameterizations. The material is an NBRDF network (../shared/data/merl_nbrdf.zip) tabulated
// once, or a synthetic Lambert + GGX table when the archive is absent. Counters: cells, f<=0,
// PCG iterations, and the rendered-image metric of the result (psnr_dB, med_lum_%; docs/
// accuracy.md). BM_FactorReusedForm: a reused system plus the refinement of each refined form
// (factor/factor_refine.h; `brdfit factor`'s candidates first). The same metric over all 100
// materials: bench_factor_accuracy. Medians:
//   build/bench/bench_factor --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "core/synth.h"
#include "factor/factor.h"
#include "factor/factor_choice.h"
#include "factor/factor_form.h"
#include "factor/factor_metrics.h"
#include "io/nbrdf.h"
#include "models/registry.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

const fs::path kZip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
constexpr const char* kMaterial = "gold-metallic-paint";

struct Material {
  std::string name;
  Table table;
};

const Material& TheMaterial() {
  static const Material m = [] {
    if (fs::exists(kZip)) {
      return Material{std::string("nbrdf:") + kMaterial,
                      TabulateNbrdf(ReadNbrdf(kZip, kMaterial), Grid::Merl(), 2).table};
    }
    const ModelInfo* info = FindModel("lambert+ggx");
    const std::vector<double> p = info->DefaultParams();
    return Material{"synthetic lambert+ggx", SynthesizeTable(Grid::Merl(),
                                                             [&](const Geometry& g, double rgb[3]) {
                                                               info->eval(p.data(), g, rgb);
                                                             },
                                                             {0.0, 0.0, 1})};
  }();
  return m;
}

FactorOptions Options(const benchmark::State& state) {
  FactorOptions o;
  o.param = state.range(0) == 0 ? FactorParam::kMcCool : FactorParam::kHalfDiff;
  o.resolution = static_cast<int>(state.range(1));
  return o;
}

void Label(benchmark::State& state, const Factorization& r) {
  state.SetLabel(TheMaterial().name + " " + FactorFormLabel(FormOf(r.brdf)));
  state.counters["cells"] = static_cast<double>(r.stats.used_cells);
  state.counters["f<=0"] = static_cast<double>(r.stats.nonpositive_cells);
  state.counters["pcg_it"] = r.stats.pcg_iterations;
  // The rendered-image metric of the result (docs/accuracy.md, default scene; not timed).
  const RenderedError e = ScoreFactorizationRendered(TheMaterial().table, r.brdf);
  if (!e.ok) {
    state.SkipWithError(("rendered metric: " + e.problem).c_str());
    return;
  }
  state.counters["psnr_dB"] = e.psnr_db;
  state.counters["med_lum_%"] = 100 * e.median_rel_error;
}

// Cold: every iteration builds and factors the system, then solves.
void BM_FactorFirst(benchmark::State& state) {
  const Table& t = TheMaterial().table;
  const FactorOptions o = Options(state);
  Factorization r;
  for (auto _ : state) {
    FactorSystemCache cache;
    r = Factor(t, o, &cache);
    benchmark::DoNotOptimize(r);
  }
  Label(state, r);
}

// Times Factor with the system from the cache (built once before the loop).
Factorization TimeReused(benchmark::State& state, const FactorOptions& o) {
  const Table& t = TheMaterial().table;
  FactorSystemCache cache;
  Factorization r = Factor(t, o, &cache);
  for (auto _ : state) {
    r = Factor(t, o, &cache);
    benchmark::DoNotOptimize(r);
  }
  if (!r.stats.system_reused) state.SkipWithError("cache miss");
  Label(state, r);
  return r;
}

// Reused: the system comes from the cache; per material only logs, A^T W y and solves.
void BM_FactorReused(benchmark::State& state) {
  TimeReused(state, Options(state));
}

// The refined forms (factor/factor_refine.h) at 64^2: `brdfit factor`'s candidates
// (factor/factor_choice.h), then a few more of docs/nbrdf-results.md's table.
const std::vector<FactorCandidate>& RefinedForms() {
  static const std::vector<FactorCandidate> forms = [] {
    std::vector<FactorCandidate> f(kAutoFactorCandidates.begin(), kAutoFactorCandidates.end());
    f.push_back({"mccool+ref+lr", FactorParam::kMcCool, false, true, 1, RefineLoss::kLogRatio});
    f.push_back({"mccool+d+lr", FactorParam::kMcCool, true, true, 1, RefineLoss::kLogRatio});
    f.push_back({"halfdiff+d+lr", FactorParam::kHalfDiff, true, true, 1, RefineLoss::kLogRatio});
    f.push_back({"mccool+d+r4+lr", FactorParam::kMcCool, true, true, 4, RefineLoss::kLogRatio});
    return f;
  }();
  return forms;
}

// Reused system + the form's refinement (none for the log-linear candidate).
void BM_FactorReusedForm(benchmark::State& state) {
  const FactorCandidate& c = RefinedForms()[static_cast<std::size_t>(state.range(0))];
  FactorOptions base;
  base.resolution = 64;
  const Factorization r = TimeReused(state, CandidateOptions(base, c));
  state.SetLabel(TheMaterial().name + " " + c.name);
  state.counters["refine_ms"] = 1e3 * r.stats.refine_seconds;
  state.counters["lm_it"] = r.stats.refine_iterations;
}

// Args: {parameterization (0 mccool, 1 halfdiff), resolution}.
BENCHMARK(BM_FactorFirst)
    ->ArgsProduct({{0, 1}, {32, 64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FactorReused)
    ->ArgsProduct({{0, 1}, {32, 64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FactorReusedForm)
    ->DenseRange(0, static_cast<int>(RefinedForms().size()) - 1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace brdfit

BENCHMARK_MAIN();
