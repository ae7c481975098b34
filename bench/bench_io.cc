// I/O benchmarks: reading/writing one MERL file (34,992,012 bytes, warm page cache), HDF5
// tables on the MERL grid, tabulating one NBRDF network on the MERL grid, synthesis and the
// statistics of `brdfit info`. Medians over repetitions:
//   build/bench/bench_io --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "io/hdf5_table.h"
#include "io/merl.h"
#include "io/nbrdf.h"
#include "core/synth.h"
#include "io/table_io.h"
#include "core/table_stats.h"
#include "models/registry.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

const fs::path kZip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";

Table SyntheticMerlTable() {
  const ModelInfo* m = FindModel("lambert+ggx");
  const std::vector<double> p = m->DefaultParams();
  return SynthesizeTable(Grid::Merl(),
                         [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); },
                         {0.02, 0.1, 1});
}

// One synthetic table and its MERL and HDF5 files, made once, removed at exit.
struct Fixture {
  fs::path dir = fs::temp_directory_path() / ("brdfit-bench-io-" + std::to_string(::getpid()));
  Table table = SyntheticMerlTable();
  fs::path merl = dir / "t.binary", h5 = dir / "t.h5";
  Fixture() {
    fs::create_directories(dir);
    WriteMerl(table, merl);
    WriteHdf5Table(table, h5);
  }
  ~Fixture() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

Fixture& Files() {
  static Fixture f;
  return f;
}

void BM_ReadMerl(benchmark::State& state) {
  const fs::path p = Files().merl;
  for (auto _ : state) benchmark::DoNotOptimize(ReadMerl(p));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(kMerlFileBytes));
}
BENCHMARK(BM_ReadMerl)->Unit(benchmark::kMillisecond);

void BM_LoadTableMerl(benchmark::State& state) {  // format detection + read
  const fs::path p = Files().merl;
  for (auto _ : state) benchmark::DoNotOptimize(LoadTable(p));
}
BENCHMARK(BM_LoadTableMerl)->Unit(benchmark::kMillisecond);

void BM_WriteMerl(benchmark::State& state) {
  const Fixture& f = Files();
  for (auto _ : state) WriteMerl(f.table, f.dir / "w.binary");
}
BENCHMARK(BM_WriteMerl)->Unit(benchmark::kMillisecond);

void BM_ReadHdf5Table(benchmark::State& state) {
  const fs::path p = Files().h5;
  for (auto _ : state) benchmark::DoNotOptimize(ReadHdf5Table(p));
}
BENCHMARK(BM_ReadHdf5Table)->Unit(benchmark::kMillisecond);

void BM_WriteHdf5Table(benchmark::State& state) {
  const Fixture& f = Files();
  for (auto _ : state) WriteHdf5Table(f.table, f.dir / "w.h5");
}
BENCHMARK(BM_WriteHdf5Table)->Unit(benchmark::kMillisecond);

// One network on the 90 x 90 x 180 grid (1,458,000 cells); argument = threads.
void BM_TabulateNbrdfMerlGrid(benchmark::State& state) {
  if (!fs::exists(kZip)) {
    state.SkipWithError((kZip.string() + " not found, skipping").c_str());
    return;
  }
  const NbrdfNetwork net = ReadNbrdf(kZip, "gold-metallic-paint");
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(TabulateNbrdf(net, Grid::Merl(), threads));
}
BENCHMARK(BM_TabulateNbrdfMerlGrid)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_ReadNbrdfFromZip(benchmark::State& state) {
  if (!fs::exists(kZip)) {
    state.SkipWithError((kZip.string() + " not found, skipping").c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(ReadNbrdf(kZip, "gold-metallic-paint"));
}
BENCHMARK(BM_ReadNbrdfFromZip)->Unit(benchmark::kMillisecond);

void BM_SynthesizeMerlGrid(benchmark::State& state) {  // lambert+ggx, noise and holes
  for (auto _ : state) benchmark::DoNotOptimize(SyntheticMerlTable());
}
BENCHMARK(BM_SynthesizeMerlGrid)->Unit(benchmark::kMillisecond);

void BM_InfoStatsMerlGrid(benchmark::State& state) {  // counts, medians, 4 albedo estimates
  const Table& t = Files().table;
  for (auto _ : state) benchmark::DoNotOptimize(ComputeTableStats(t));
}
BENCHMARK(BM_InfoStatsMerlGrid)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace brdfit

BENCHMARK_MAIN();
