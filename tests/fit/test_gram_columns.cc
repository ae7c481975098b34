// The compressed blocks' Gram accumulation (fit/block_compress.h): AccumulateGramColumns and
// GramRows against an independent oracle (each entry summed in long double, row by row), the
// AVX loop bit for bit equal to the portable one, and the chunking (full chunks, a partial
// one, none) invisible in the result. Random rows with magnitudes over 12 decades, as a
// Jacobian's columns are (an albedo's against a roughness's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fit/block_compress.h"

namespace brdfit::internal {
namespace {

std::vector<double> RandomRows(int n, int cols, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> decade(-6, 6);
  std::vector<double> scale(cols);
  for (double& s : scale) s = std::pow(10.0, decade(rng));
  std::vector<double> rows(static_cast<std::size_t>(n) * cols);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < cols; ++c) rows[r * cols + c] = scale[c] * normal(rng);
  }
  return rows;
}

// Oracle: lower triangle of rows^T rows, each entry summed in long double in row order.
std::vector<long double> OracleGram(const std::vector<double>& rows, int n, int cols) {
  std::vector<long double> g(static_cast<std::size_t>(cols) * cols, 0.0L);
  for (int r = 0; r < n; ++r) {
    for (int j = 0; j < cols; ++j) {
      for (int i = j; i < cols; ++i) {
        g[i + j * cols] += static_cast<long double>(rows[r * cols + i]) * rows[r * cols + j];
      }
    }
  }
  return g;
}

// |computed - (start + oracle)| against the Cauchy-Schwarz scale sqrt(g_ii g_jj) of the rows'
// part (a dot product of n terms summed in double is within ~n eps of it) plus the rounding of
// the final addition to the start value.
void ExpectMatchesOracle(const double* gram, const std::vector<long double>& oracle, int cols,
                         const std::vector<double>& start = {}) {
  for (int j = 0; j < cols; ++j) {
    for (int i = j; i < cols; ++i) {
      const long double scale = std::sqrt(oracle[i + i * cols] * oracle[j + j * cols]);
      const long double s = start.empty() ? 0.0L : start[i + j * cols];
      const long double bound = 1e-13L * scale + 0x1p-52L * std::abs(s);
      EXPECT_LE(std::abs(gram[i + j * cols] - (s + oracle[i + j * cols])), bound)
          << "entry (" << i << ", " << j << ") of " << cols << " columns";
    }
  }
}

TEST(GramColumns, OneChunkMatchesTheOracleAndAvxMatchesPortableBitForBit) {
  for (int cols : {1, 2, 5, 9, 14, 19}) {
    for (int n : {1, 3, 37, kGramChunk}) {
      const std::vector<double> rows = RandomRows(n, cols, 100 * cols + n);
      std::vector<double> columns(static_cast<std::size_t>(kGramChunk) * cols, 0.0);
      for (int r = 0; r < n; ++r) {
        for (int c = 0; c < cols; ++c) columns[c * kGramChunk + r] = rows[r * cols + c];
      }
      // Start from a non-zero Gram: the kernel adds to it.
      std::vector<double> start(static_cast<std::size_t>(cols) * cols);
      for (std::size_t k = 0; k < start.size(); ++k) start[k] = 0.25 * static_cast<double>(k);
      std::vector<double> fast = start, portable = start;
      AccumulateGramColumns(columns.data(), cols, fast.data());
      AccumulateGramColumnsPortable(columns.data(), cols, portable.data());
      EXPECT_EQ(std::memcmp(fast.data(), portable.data(), fast.size() * sizeof(double)), 0)
          << cols << " columns, " << n << " rows";
      // The upper triangle is not touched.
      for (int j = 1; j < cols; ++j) {
        for (int i = 0; i < j; ++i) EXPECT_EQ(fast[i + j * cols], start[i + j * cols]);
      }
      ExpectMatchesOracle(fast.data(), OracleGram(rows, n, cols), cols, start);
    }
  }
}

template <int kCols>
void CheckGramRows(int n) {
  const std::vector<double> rows = RandomRows(n, kCols, 7 * n + kCols);
  GramRows<kCols> gram;
  for (int r = 0; r < n; ++r) {
    double* row = gram.Next();
    for (int c = 0; c < kCols; ++c) row[c] = rows[r * kCols + c];
    gram.Commit();
  }
  const double* g = gram.Finish();
  ExpectMatchesOracle(g, OracleGram(rows, n, kCols), kCols);
  for (int j = 1; j < kCols; ++j) {
    for (int i = 0; i < j; ++i)
      EXPECT_EQ(g[i + j * kCols], 0.0) << "upper (" << i << ", " << j << ")";
  }
}

TEST(GramColumns, GramRowsOverFullAndPartialChunksMatchesTheOracle) {
  for (int n : {0, 1, kGramChunk - 1, kGramChunk, kGramChunk + 1, 3 * kGramChunk + 17}) {
    SCOPED_TRACE(n);
    CheckGramRows<9>(n);
    CheckGramRows<19>(n);
  }
}

// An all-zero row (what pads a partial chunk) adds exactly nothing: ten rows, and the same ten
// followed by twenty zero rows, give the same bits.
TEST(GramColumns, ZeroPaddingAddsNothing) {
  constexpr int kCols = 5;
  const std::vector<double> rows = RandomRows(10, kCols, 3);
  GramRows<kCols> a, b;
  for (int r = 0; r < 10; ++r) {
    std::memcpy(a.Next(), &rows[r * kCols], kCols * sizeof(double));
    a.Commit();
    std::memcpy(b.Next(), &rows[r * kCols], kCols * sizeof(double));
    b.Commit();
  }
  for (int r = 0; r < 20; ++r) {
    double* z = b.Next();
    for (int c = 0; c < kCols; ++c) z[c] = 0.0;
    b.Commit();
  }
  const double* ga = a.Finish();
  const double* gb = b.Finish();
  EXPECT_EQ(std::memcmp(ga, gb, kCols * kCols * sizeof(double)), 0);
}

}  // namespace
}  // namespace brdfit::internal
