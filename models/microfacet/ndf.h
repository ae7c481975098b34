// Microfacet normal distribution functions D(h) and their Smith Lambda functions.
//
// Every D here is normalized so that the projected facet area is one:
//   integral over the hemisphere of D(h) cos(theta_h) d omega_h = 1
// (Walter et al. 2007 eq. 4; tested in tests/models/test_physics.cc). Forms are chosen so that
// nothing cancels at theta_h -> 0 and alpha -> 1e-4: sin^2(theta_h) comes from the half-vector's
// components (Geometry::sin2_h), never from 1 - cos^2.
//
// Ndf policy types (GgxNdf, BeckmannNdf) bundle D, Lambda and the alpha parameter spec so that
// the microfacet lobe (models/microfacet/microfacet.h) and the Smith masking terms
// (models/microfacet/masking.h) are written once for every distribution.
#pragma once

#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// --- GGX / Trowbridge-Reitz -------------------------------------------------------------------

// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
// Surfaces" (EGSR), eq. 33 (= Trowbridge & Reitz 1975):
//   D(h) = alpha^2 / (pi cos^4 th (alpha^2 + tan^2 th)^2)
//        = alpha^2 / (pi (alpha^2 cos^2 th + sin^2 th)^2).
// The second form is used: with sin^2 th from components it does not cancel at th -> 0, so D
// stays accurate for alpha down to 1e-4 (the usual form cancels to 0 in float below roughness
// 0.01: godot #59123). Karis 2013 and most tutorials print the equivalent
// alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2); Tokoi's lecture notes drop the square (a typo).
template <class T>
T DGgx(const T& alpha, double cos_h, double sin2_h) {
  const T a2 = alpha * alpha;
  const T denom = a2 * (cos_h * cos_h) + sin2_h;
  return a2 / (kPi * denom * denom);
}

// Smith Lambda for GGX (Heitz 2014, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", JCGT 3(2), §5.3):  Lambda = (-1 + sqrt(1 + alpha^2 tan^2 th)) / 2,
// written as x / (2 (1 + sqrt(1 + x))), x = alpha^2 tan^2 th, which does not cancel for small x.
template <class T>
T LambdaGgx(const T& alpha, double tan2) {
  using std::sqrt;
  const T x = alpha * alpha * tan2;
  return x / (2.0 * (1.0 + sqrt(1.0 + x)));
}

// --- Beckmann --------------------------------------------------------------------------------

// Walter et al. 2007 eq. 25 (Beckmann & Spizzichino 1963), normalized with pi:
//   D(h) = exp(-tan^2 th / alpha^2) / (pi alpha^2 cos^4 th),   tan^2 th = sin^2 th / cos^2 th.
// Some course notes print 1/(4 m^2 cos^4) or 1/(alpha^2 cos^4) without pi: see docs/models.md.
template <class T>
T DBeckmann(const T& alpha, double cos_h, double sin2_h) {
  using std::exp;
  const double c2 = cos_h * cos_h;
  const T a2 = alpha * alpha;
  return exp(-sin2_h / (c2 * a2)) / (kPi * a2 * (c2 * c2));
}

// Smith Lambda for Beckmann (Walter et al. 2007 §5.1; Heitz 2014 §5.3), a = 1/(alpha tan th):
//   Lambda = (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)) = (exp(-a^2)/(a sqrt(pi)) - erfc(a)) / 2.
// For a > 8 Lambda < 1e-30 and is returned as 0 (guard: a = inf at th = 0 would make the Jet
// derivative NaN).
template <class T>
T LambdaBeckmann(const T& alpha, double tan2) {
  using std::erfc;
  using std::exp;
  const double tan_th = std::sqrt(tan2);
  const T inv_a = alpha * tan_th;  // 1/a
  if (inv_a < 1.0 / 8.0) return T(0.0);
  const T a = 1.0 / inv_a;
  return 0.5 * (exp(-a * a) * inv_a / std::sqrt(kPi) - erfc(a));
}

// --- Policy types ------------------------------------------------------------------------------

struct GgxNdf {
  static constexpr std::string_view kName = "GGX";
  static constexpr ParamSpec kAlpha = {
      "alpha", "1", 1e-4, 1.0, 0.1, true, "GGX roughness alpha (slope-space width)"};
  template <class T>
  static T D(const T& alpha, const Geometry& g) {
    return DGgx(alpha, g.cos_h, g.sin2_h);
  }
  template <class T>
  static T Lambda(const T& alpha, const Vec3& v) {
    return LambdaGgx(alpha, Tan2Theta(v));
  }
};

struct BeckmannNdf {
  static constexpr std::string_view kName = "Beckmann";
  static constexpr ParamSpec kAlpha = {
      "alpha", "1", 1e-4, 1.0, 0.1, true, "Beckmann roughness alpha (RMS slope m)"};
  template <class T>
  static T D(const T& alpha, const Geometry& g) {
    return DBeckmann(alpha, g.cos_h, g.sin2_h);
  }
  template <class T>
  static T Lambda(const T& alpha, const Vec3& v) {
    return LambdaBeckmann(alpha, Tan2Theta(v));
  }
};

}  // namespace brdfit
