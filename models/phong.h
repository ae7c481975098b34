// Normalized (modified) Phong specular lobe ("phong").
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// Phong 1975, "Illumination for Computer Generated Pictures" (CACM 18(6)), as the
// energy-normalized "modified Phong" BRDF of Lewis 1994, "Making Shaders More Physically
// Plausible" (CGF 13(2)):
//   f_r = ks (n + 2) / (2 pi) max(0, cos alpha_r)^n,   cos alpha_r = wo . reflect(wi)
// [1/sr, without the cosine]. At normal incidence the albedo is exactly ks; elsewhere the
// horizon clips the lobe, so the albedo is <= ks: energy conserving for ks <= 1.
// Also printed: the raw Phong BRDF c_spec cos^m / (pi cos_i) (Tokoi's lecture notes) and the
// un-normalized (R.V)^n of shading tutorials (preview only; docs/models.md).
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; n = exponent [1, 1e5] (log).
struct Phong {
  static constexpr std::string_view kName = "phong";
  static constexpr std::string_view kDoc =
      "normalized Phong lobe ks (n+2)/(2 pi) cos^n alpha_r (Lewis 1994)";
  static constexpr bool kEnergyConserving = true;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"ks_r", "1", 0.0, 1e3, 0.1, false, "specular weight, red", ParamRole::kWeightR},
      {"ks_g", "1", 0.0, 1e3, 0.1, false, "specular weight, green", ParamRole::kWeightG},
      {"ks_b", "1", 0.0, 1e3, 0.1, false, "specular weight, blue", ParamRole::kWeightB},
      {"n", "1", 1.0, 1e5, 100.0, true, "Phong exponent (shininess)"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& n = p[3];
    // cos alpha_r = wo . r, r = reflect(wi) = (-wi.x, -wi.y, wi.z), from components; and
    // sin^2 alpha_r = |wo - r|^2 (1 - |wo - r|^2 / 4), free of cancellation near the mirror
    // direction, where n up to 1e5 amplifies rounding errors.
    const double cos_r = g.wi.z * g.wo.z - (g.wi.x * g.wo.x + g.wi.y * g.wo.y);
    const double d2 = Sq(g.wo.x + g.wi.x) + Sq(g.wo.y + g.wi.y) + Sq(g.wo.z - g.wi.z);
    const double sin2_r = d2 * (1.0 - 0.25 * d2);
    const T spec = (n + 2.0) / (2.0 * kPi) * PowCos(cos_r, sin2_r, n);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * spec;
  }
};

}  // namespace brdfit
