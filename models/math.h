// Scalar helpers shared by the models. Everything is templated on the scalar T (double or
// ceres::Jet); math calls are unqualified after `using std::...` so ADL finds the Jet overloads.
#pragma once

#include <cmath>

#include "models/geometry.h"

namespace brdfit {

template <class T>
inline T Sq(const T& x) {
  return x * x;
}

inline double Pow5(double x) {
  const double x2 = x * x;
  return x2 * x2 * x;
}

// sin^2 of a direction's polar angle from its components (no cancellation near the pole).
inline double Sin2Theta(const Vec3& v) {
  return v.x * v.x + v.y * v.y;
}

// tan^2 of a direction's polar angle; v.z > 0 is a precondition of every Eval.
inline double Tan2Theta(const Vec3& v) {
  return Sin2Theta(v) / (v.z * v.z);
}

// x^n for a data-side base x in [0, 1] and a parameter-side exponent n >= 1:
// exp(n log x). x == 0 returns 0 (log would be -inf and the Jet derivative NaN; the true
// value and its n-derivative are 0 there for n >= 1).
template <class T>
T PowData(double x, const T& n) {
  using std::exp;
  if (x <= 0.0) return T(0.0);
  return exp(n * std::log(x));
}

// cos(theta)^n from sin^2(theta): exp(n/2 * log1p(-sin2)). log1p keeps the exponent accurate
// near theta = 0, where cos^n of a sharp lobe (n ~ 1e5) is most sensitive.
template <class T>
T PowCosFromSin2(double sin2, const T& n) {
  using std::exp;
  if (sin2 >= 1.0) return T(0.0);  // cos = 0: the lobe vanishes (n >= 1)
  return exp(0.5 * n * std::log1p(-sin2));
}

// x^n for a parameter-dependent base x and exponent n >= 1. x <= 0 returns 0: the lobe is
// clipped there (max(0, x)^n), and log(x) would make Jet derivatives NaN.
template <class T>
T PowClipped(const T& x, const T& n) {
  using std::exp;
  using std::log;
  if (x <= 0.0) return T(0.0);
  return exp(n * log(x));
}

}  // namespace brdfit
