// A fast cube root for the metrics' hot loop (fit/metrics.cc).
#pragma once

#include <cstdint>
#include <cstring>

namespace brdfit {

// cbrt(x) for x > 0 to within 4 ulp (tested against std::cbrt), 2-3x faster than glibc's (whose
// ldexp / scalbn calls were a fifth of a whole `brdfit fit`): an exponent-division first guess
// (Kahan 1991, "Computing a real cube root": the bits of x divided by 3 plus a bias, which
// divides the exponent by 3), two Halley steps
// y <- y (y^3 + 2x) / (2 y^3 + x) (cubic convergence) and one Newton step.
// The two halves, so that a loop over many values can run the second (double arithmetic only,
// no branch) vectorized: FastCbrt(x) == FastCbrtRefine(x, FastCbrtGuess(x)), bit for bit.
inline double FastCbrtGuess(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits = bits / 3 + 0x2a9f7893782da1ceULL;
  double y;
  std::memcpy(&y, &bits, sizeof y);
  return y;
}

inline double FastCbrtRefine(double x, double y) {
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y - (y * y * y - x) / (3.0 * y * y);
}

inline double FastCbrt(double x) {
  return FastCbrtRefine(x, FastCbrtGuess(x));
}

}  // namespace brdfit
