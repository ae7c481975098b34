// GGX / Trowbridge-Reitz microfacet specular lobe.
#pragma once

#include <array>
#include <cmath>

#include "models/geometry.h"
#include "models/param.h"

namespace brdfit {

// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
// Surfaces" (EGSR), eq. 33:  D(h) = alpha^2 / (pi cos^4 th (alpha^2 + tan^2 th)^2)
//                                 = alpha^2 / (pi (alpha^2 cos^2 th + sin^2 th)^2).
// The second form is used: with sin^2 th from components it does not cancel at th -> 0,
// so D stays accurate for alpha down to 1e-4 (reference.md §5).
template <class T>
T DGgx(const T& alpha, double cos_h, double sin2_h) {
  const T a2 = alpha * alpha;
  const T denom = a2 * (cos_h * cos_h) + sin2_h;
  return a2 / (kPi * denom * denom);
}

// Walter et al. 2007, eq. 34: separable Smith masking for GGX,
//   G1(v) = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta_v)),  tan^2 = sin^2 / cos^2.
template <class T>
T G1SmithGgx(const T& alpha, const Vec3& v) {
  using std::sqrt;
  const double sin2 = v.x * v.x + v.y * v.y;
  const double tan2 = sin2 / (v.z * v.z);  // v.z > 0 is a precondition of Eval
  return T(2.0) / (T(1.0) + sqrt(T(1.0) + alpha * alpha * tan2));
}

// GGX specular lobe with RGB weight ks (Fresnel folded into ks):
//   f_r = ks * D(h) G1(wi) G1(wo) / (4 cos_i cos_o)   (Walter et al. 2007, eq. 20).
// f_r in 1/sr, without the cosine.
struct Ggx {
  static constexpr std::string_view kName = "ggx";
  static constexpr std::string_view kDoc =
      "GGX microfacet lobe (Walter 2007), separable Smith G, Fresnel folded into ks";
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"ks_r", "1", 0.0, 1e3, 0.1, false, "specular weight, red", ParamRole::kWeightR},
      {"ks_g", "1", 0.0, 1e3, 0.1, false, "specular weight, green", ParamRole::kWeightG},
      {"ks_b", "1", 0.0, 1e3, 0.1, false, "specular weight, blue", ParamRole::kWeightB},
      {"alpha", "1", 1e-4, 1.0, 0.1, true, "GGX slope-space roughness alpha"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& alpha = p[3];
    const T spec = DGgx(alpha, g.cos_h, g.sin2_h) * G1SmithGgx(alpha, g.wi) *
                   G1SmithGgx(alpha, g.wo) / (4.0 * g.cos_i * g.cos_o);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * spec;
  }
};

}  // namespace brdfit
