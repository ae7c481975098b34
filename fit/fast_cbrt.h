// A fast cube root for the metrics' hot loop (fit/metrics.cc).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace brdfit {

// cbrt(x) for x > 0 to within 4 ulp (tested against std::cbrt), 2-3x faster than glibc's (whose
// ldexp / scalbn calls were a fifth of a whole `brdfit fit`): an exponent-division first guess
// (Kahan 1991, "Computing a real cube root"; the high 32 bits of x divided by 3 plus a bias, which
// divides the exponent by 3, as fdlibm's cbrt: ~5 correct bits), two Halley steps
// y <- y (y^3 + 2x) / (2 y^3 + x) (cubic convergence) and one Newton step.
// The two halves, so that a loop over many values can run each vectorized (FastCbrtGuesses,
// FastCbrtRefine): FastCbrt(x) == FastCbrtRefine(x, FastCbrtGuess(x)), bit for bit.
inline constexpr std::uint32_t kCbrtGuessBias = 0x2a9f7893u;  // fdlibm's B1

inline double FastCbrtGuess(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // hi / 3 as (hi * ceil(2^33 / 3)) >> 33: exact for every 32-bit hi, and what SSE2 computes.
  const std::uint64_t hi = bits >> 32;
  bits = (((hi * 0xAAAAAAABull) >> 33) + kCbrtGuessBias) << 32;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  return y;
}

// y[k] = FastCbrtGuess(x[k]) for k < n, two at a time with SSE2 (the scalar loop's 64-bit
// multiply does not vectorize: it was half the metric pass's cube-root time).
inline void FastCbrtGuesses(const double* x, std::size_t n, double* y) {
  std::size_t k = 0;
#if defined(__SSE2__)
  const __m128i magic = _mm_set1_epi32(static_cast<int>(0xAAAAAAABu));
  const __m128i bias = _mm_set1_epi64x(kCbrtGuessBias);
  for (; k + 2 <= n; k += 2) {
    const __m128i hi = _mm_srli_epi64(_mm_castpd_si128(_mm_loadu_pd(x + k)), 32);
    const __m128i third = _mm_srli_epi64(_mm_mul_epu32(hi, magic), 33);
    _mm_storeu_pd(y + k, _mm_castsi128_pd(_mm_slli_epi64(_mm_add_epi64(third, bias), 32)));
  }
#endif
  for (; k < n; ++k) y[k] = FastCbrtGuess(x[k]);
}

inline double FastCbrtRefine(double x, double y) {
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y - (y * y * y - x) / (3.0 * y * y);
}

// y[k] = FastCbrtRefine(x[k], y[k]) for k < n: four at a time with AVX2 where the CPU has it
// (function clones chosen once at load time), else two with SSE2. The same IEEE operations
// either way (no FMA: AVX2 does not imply it), so the same bits on every x86-64 machine (tested).
// The divisions' throughput bounds this loop: AVX2 halves the metric pass's cube-root time.
void FastCbrtRefineAll(const double* x, std::size_t n, double* y);

inline double FastCbrt(double x) {
  return FastCbrtRefine(x, FastCbrtGuess(x));
}

}  // namespace brdfit
