// core/sse2_finite.h against std::isfinite: every IEEE class (zeros, subnormals, normals, the
// largest finite, infinities, quiet and signalling NaNs of both signs) in both lanes, and a
// million random bit patterns, which are mostly finite and NaN-heavy in the top exponent.
#include "core/sse2_finite.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace brdfit {
namespace {

#if defined(__SSE2__)
// The lanes' masks as two bools, low lane first.
std::pair<bool, bool> Lanes(double lo, double hi) {
  const int m = _mm_movemask_pd(FiniteLanes(_mm_set_pd(hi, lo)));
  return {(m & 1) != 0, (m & 2) != 0};
}

TEST(Sse2Finite, AgreesWithIsfiniteOnEveryClass) {
  using L = std::numeric_limits<double>;
  const std::vector<double> values = {
      0.0, -0.0, L::denorm_min(), -L::denorm_min(), L::min(), 1.0, -3.5, L::max(), -L::max(),
      L::infinity(), -L::infinity(), L::quiet_NaN(), -L::quiet_NaN(), L::signaling_NaN(),
      std::bit_cast<double>(std::uint64_t{0x7ff0000000000001}),   // the smallest NaN payload
      std::bit_cast<double>(std::uint64_t{0xfff8000000000000})};  // a negative quiet NaN
  for (double a : values) {
    for (double b : values) {
      const auto [lo, hi] = Lanes(a, b);
      EXPECT_EQ(lo, std::isfinite(a)) << a;
      EXPECT_EQ(hi, std::isfinite(b)) << b;
    }
  }
}

TEST(Sse2Finite, AgreesWithIsfiniteOnRandomBits) {
  std::mt19937_64 rng(7);
  int non_finite = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    std::uint64_t bits = rng();
    if (i % 4 == 0) bits |= std::uint64_t{0x7ff} << 52;  // a quarter in the top exponent
    const double a = std::bit_cast<double>(bits), b = std::bit_cast<double>(rng());
    const auto [lo, hi] = Lanes(a, b);
    ASSERT_EQ(lo, std::isfinite(a)) << std::hex << bits;
    ASSERT_EQ(hi, std::isfinite(b));
    non_finite += !std::isfinite(a);
  }
  EXPECT_GT(non_finite, 200'000);  // the top-exponent quarter was exercised
}
#else
TEST(Sse2Finite, NotAnSse2Build) { GTEST_SKIP() << "no SSE2: the readers use std::isfinite"; }
#endif

}  // namespace
}  // namespace brdfit
