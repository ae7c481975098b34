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

// 1 - cos(theta) of a unit direction from its components: sin^2 / (1 + cos), no cancellation
// near the pole (Schlick's (1 - c)^5 with F0 = 0 would otherwise lose all digits there).
inline double OneMinusCos(const Vec3& v) {
  return Sin2Theta(v) / (1.0 + v.z);
}

// 1 - cos(theta_d) = 1 - wi.h = |wi - h|^2 / 2 (both unit): accurate at retro-reflection.
inline double OneMinusCosD(const Geometry& g) {
  const Vec3 d = g.wi - g.h;
  return 0.5 * Dot(d, d);
}

// cos(theta)^n for theta in [0, pi/2], n >= 1, from cos and sin^2 (both from components):
// exp(n log cos). log cos = log1p(-sin^2)/2 near theta = 0, where cos^n of a sharp lobe
// (n ~ 1e5) is most sensitive to rounding in cos; log(cos) directly when cos is small.
template <class T>
T PowCos(double cos, double sin2, const T& n) {
  using std::exp;
  if (cos <= 0.0) return T(0.0);  // the lobe vanishes (n >= 1); log would be -inf
  const double log_cos = sin2 < 0.5 ? 0.5 * std::log1p(-sin2) : std::log(cos);
  return exp(n * log_cos);
}

}  // namespace brdfit
