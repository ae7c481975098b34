#include "core/nbrdf_forward.h"

#include <algorithm>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#define BRDFIT_NBRDF_AVX2 1
#endif

namespace brdfit {

bool NbrdfForwardVectorized() {
#if defined(BRDFIT_NBRDF_AVX2)
  static const bool ok = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return ok;
#else
  return false;
#endif
}

#if defined(BRDFIT_NBRDF_AVX2)
namespace {

// Cells per call: kVectors vectors of four. Each hidden unit's sum is kVectors independent chains
// of fused multiply-adds (one chain alone waits on the FMA latency at every term).
constexpr int kVectors = 4;
constexpr std::size_t kCells = 4 * kVectors;

// One unit of a dense layer for the 16 cells: acc[v] = bias + sum_j w[j] in[j] (lanes of vector
// v), summed in input order by fused multiply-adds; in holds kCells values per input unit.
__attribute__((target("avx2,fma"))) inline void DenseUnit(const double* w, double bias,
                                                          const double* in, int n_in,
                                                          __m256d* acc) {
  for (int v = 0; v < kVectors; ++v) acc[v] = _mm256_set1_pd(bias);
  for (int j = 0; j < n_in; ++j) {
    const __m256d wj = _mm256_set1_pd(w[j]);
    for (int v = 0; v < kVectors; ++v) {
      acc[v] = _mm256_fmadd_pd(wj, _mm256_loadu_pd(in + kCells * j + 4 * v), acc[v]);
    }
  }
}

// The 16 cells r[0..15]; h1, h2: scratch of kCells * a.h1 and kCells * a.h2 doubles (cell
// 4 v + l of unit j at kCells j + 4 v + l); y16[kCells c + i]: output c of cell i.
__attribute__((target("avx2,fma"))) void SixteenCells(const NbrdfForwardArgs& a, const long* r,
                                                      double* h1, double* h2, double* y16) {
  const __m256d zero = _mm256_setzero_pd();
  for (int j = 0; j < a.h1; ++j) {
    const double* col = a.p + static_cast<std::size_t>(j) * a.p_rows;
    const __m256d hp = _mm256_set1_pd(a.hpart[j]);
    for (int v = 0; v < kVectors; ++v) {
      const long* q = r + 4 * v;
      // Four consecutive rows (most of a slice) in one load; any other four (the padded last
      // block repeats its last row) one by one.
      const bool consecutive = q[1] == q[0] + 1 && q[2] == q[0] + 2 && q[3] == q[0] + 3;
      const __m256d x = consecutive ? _mm256_loadu_pd(col + q[0])
                                    : _mm256_set_pd(col[q[3]], col[q[2]], col[q[1]], col[q[0]]);
      _mm256_storeu_pd(h1 + kCells * j + 4 * v, _mm256_max_pd(_mm256_add_pd(x, hp), zero));
    }
  }
  for (int k = 0; k < a.h2; ++k) {
    __m256d acc[kVectors];
    DenseUnit(a.k2 + static_cast<std::size_t>(k) * a.h1, a.b2[k], h1, a.h1, acc);
    for (int v = 0; v < kVectors; ++v) {
      _mm256_storeu_pd(h2 + kCells * k + 4 * v, _mm256_max_pd(acc[v], zero));
    }
  }
  for (int c = 0; c < 3; ++c) {
    __m256d acc[kVectors];
    DenseUnit(a.k3 + static_cast<std::size_t>(c) * a.h2, a.b3[c], h2, a.h2, acc);
    for (int v = 0; v < kVectors; ++v) _mm256_storeu_pd(y16 + kCells * c + 4 * v, acc[v]);
  }
}

}  // namespace

void NbrdfForwardAvx2(const NbrdfForwardArgs& a, double* y) {
  std::vector<double> h1(kCells * static_cast<std::size_t>(std::max(a.h1, 1)));
  std::vector<double> h2(kCells * static_cast<std::size_t>(std::max(a.h2, 1)));
  alignas(32) double y16[3 * kCells];
  for (std::size_t i = 0; i < a.n; i += kCells) {
    // The last block repeats its last cell to fill the lanes (each lane is its own cell).
    const std::size_t m = std::min(kCells, a.n - i);
    long r[kCells];
    for (std::size_t l = 0; l < kCells; ++l) r[l] = a.rows[i + std::min(l, m - 1)];
    SixteenCells(a, r, h1.data(), h2.data(), y16);
    for (std::size_t l = 0; l < m; ++l) {
      for (int c = 0; c < 3; ++c) y[3 * (i + l) + c] = y16[kCells * c + l];
    }
  }
}
#else
void NbrdfForwardAvx2(const NbrdfForwardArgs&, double*) {}
#endif

}  // namespace brdfit
