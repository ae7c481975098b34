// Speed of the compressed blocks' Gram accumulation (fit/block_compress.h), per row of
// [grad r, r]: GramRows (column-major chunks, AccumulateGramColumns: AVX where the CPU has it),
// the portable loop alone, and Eigen's rank update of a row-major 64-row chunk (what GramRows
// used until 2026-12-04), at 5, 9, 14 and 19 columns (lambert+ggx has 8, three Lafortune lobes
// 19). 64 Ki random rows per iteration; items_per_second is rows per second. One thread.
//   build/bench/bench_gram --benchmark_filter=/9/   (one width)
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "fit/block_compress.h"

namespace {

using namespace brdfit::internal;

constexpr int kRows = 1 << 16;

std::vector<double> Rows(int cols) {
  std::mt19937_64 rng(cols);
  std::normal_distribution<double> normal;
  std::vector<double> rows(static_cast<std::size_t>(kRows) * cols);
  for (double& v : rows) v = normal(rng);
  return rows;
}

void SetPerRow(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * kRows);
}

template <int kCols>
void BM_GramRows(benchmark::State& state) {
  const std::vector<double> rows = Rows(kCols);
  for (auto _ : state) {
    GramRows<kCols> gram;
    for (int r = 0; r < kRows; ++r) {
      double* row = gram.Next();
      for (int c = 0; c < kCols; ++c) row[c] = rows[r * kCols + c];
      gram.Commit();
    }
    benchmark::DoNotOptimize(gram.Finish());
  }
  SetPerRow(state);
}

// The portable loop on chunks already stored column by column (no transposition).
template <int kCols>
void BM_PortableColumns(benchmark::State& state) {
  const std::vector<double> rows = Rows(kCols);
  std::vector<double> columns(rows.size());
  for (int chunk = 0; chunk < kRows / kGramChunk; ++chunk) {
    for (int r = 0; r < kGramChunk; ++r) {
      for (int c = 0; c < kCols; ++c) {
        columns[chunk * kGramChunk * kCols + c * kGramChunk + r] =
            rows[(chunk * kGramChunk + r) * kCols + c];
      }
    }
  }
  for (auto _ : state) {
    std::array<double, kCols * kCols> gram{};
    for (int chunk = 0; chunk < kRows / kGramChunk; ++chunk) {
      AccumulateGramColumnsPortable(&columns[chunk * kGramChunk * kCols], kCols, gram.data());
    }
    benchmark::DoNotOptimize(gram.data());
  }
  SetPerRow(state);
}

// The previous method: Eigen's self-adjoint rank update of each row-major 64-row chunk.
template <int kCols>
void BM_EigenRankUpdate(benchmark::State& state) {
  const std::vector<double> rows = Rows(kCols);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  for (auto _ : state) {
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(kCols, kCols);
    for (int chunk = 0; chunk < kRows / kGramChunk; ++chunk) {
      const Eigen::Map<const RowMajor> r(&rows[chunk * kGramChunk * kCols], kGramChunk, kCols);
      gram.selfadjointView<Eigen::Lower>().rankUpdate(r.transpose());
    }
    benchmark::DoNotOptimize(gram.data());
  }
  SetPerRow(state);
}

#define BRDFIT_GRAM_BENCH(C)                                                                   \
  BENCHMARK(BM_GramRows<C>)->Name("GramRows/" #C)->Repetitions(5)->ReportAggregatesOnly(true); \
  BENCHMARK(BM_PortableColumns<C>)                                                             \
      ->Name("PortableColumns/" #C)                                                            \
      ->Repetitions(5)                                                                         \
      ->ReportAggregatesOnly(true);                                                            \
  BENCHMARK(BM_EigenRankUpdate<C>)                                                             \
      ->Name("EigenRankUpdate/" #C)                                                            \
      ->Repetitions(5)                                                                         \
      ->ReportAggregatesOnly(true)

BRDFIT_GRAM_BENCH(5);
BRDFIT_GRAM_BENCH(9);
BRDFIT_GRAM_BENCH(14);
BRDFIT_GRAM_BENCH(19);

}  // namespace

BENCHMARK_MAIN();
