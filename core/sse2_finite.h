// Two doubles at a time: which are finite. x - x is 0 for a finite x and NaN for an infinite or
// NaN one, and an ordered compare with 0 is false only for NaN — two SSE2 instructions, no
// branches, the same answer as std::isfinite for every bit pattern (tests/core/test_sse2_finite.cc).
// Used by the MERL reader (io/merl.cc) and the table's usable-cell flags (fit/samples.cc).
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>

namespace brdfit {

// All bits set in the lanes whose value is finite, clear elsewhere.
inline __m128d FiniteLanes(__m128d v) {
  return _mm_cmpord_pd(_mm_sub_pd(v, v), _mm_setzero_pd());
}

}  // namespace brdfit
#endif
