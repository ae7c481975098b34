#include "fit/vector_log1p.h"

#include <cmath>

#if defined(BRDFIT_HAVE_LIBMVEC) && defined(__x86_64__)
#include <immintrin.h>
// glibc's AVX2 log1p of four doubles (the x86-64 vector function ABI name; declared AVX2 so
// that its __m256d argument passes in a ymm register for every compiler).
extern "C" __attribute__((target("avx2"))) __m256d _ZGVdN4v_log1p(__m256d);
#define BRDFIT_LOG1P_AVX2 1
#endif

namespace brdfit {

namespace {

#if defined(BRDFIT_LOG1P_AVX2)
__attribute__((target("avx2"))) void Log1pAvx2(const double* x, std::size_t n, double* y) {
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4) _mm256_storeu_pd(y + k, _ZGVdN4v_log1p(_mm256_loadu_pd(x + k)));
  if (k < n) {  // the tail through the same function, padded with zeros
    alignas(32) double in[4] = {0, 0, 0, 0}, out[4];
    for (std::size_t j = k; j < n; ++j) in[j - k] = x[j];
    _mm256_store_pd(out, _ZGVdN4v_log1p(_mm256_load_pd(in)));
    for (std::size_t j = k; j < n; ++j) y[j] = out[j - k];
  }
}
#endif

bool UseAvx2() {
#if defined(BRDFIT_LOG1P_AVX2)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

}  // namespace

bool Log1pAllIsVectorized() { return UseAvx2(); }

void Log1pAll(const double* x, std::size_t n, double* y) {
#if defined(BRDFIT_LOG1P_AVX2)
  if (UseAvx2()) {
    Log1pAvx2(x, n, y);
    return;
  }
#endif
  for (std::size_t k = 0; k < n; ++k) y[k] = std::log1p(x[k]);
}

}  // namespace brdfit
