// Charlie sheen: the grazing lobe of cloth and velvet ("sheen").
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/param.h"

namespace brdfit {

// Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF" (Sony Pictures Imageworks,
// SIGGRAPH 2017 course "Physically Based Shading in Theory and Practice"), the "Charlie"
// distribution of fibres standing on the surface (eq. 2, r their roughness):
//   D(h) = (2 + 1/alpha) sin(th_h)^(1/alpha) / (2 pi),
// with the visibility of Neubelt & Pettineo 2013 ("Crafting a Next-Gen Material Pipeline for
// The Order: 1886", SIGGRAPH course, after Ashikhmin et al. 2000's velvet), which already holds
// the 1/(4 cos_i cos_o):
//   V = 1 / (4 (cos_i + cos_o - cos_i cos_o)),
//   f_r = sheen D(h) V                                        [1/sr, without the cosine]
// This is the sheen of glTF's KHR_materials_sheen (its alpha = sheenRoughness^2, the
// project's convention for alpha: roughness = sqrt(alpha)) as three.js (BRDF_Sheen) and
// Filament evaluate it. As a lobe of a sum it is ADDED to the body below it; KHR_materials_sheen
// also scales the base layer by (1 - max(sheenColor) E_sheen), which a fit does not model
// (docs/exports.md). D is evaluated as exp(log(sin^2 th_h) / (2 alpha)), exactly 0 at
// th_h = 0 (no floor: three.js floors sin^2 at 2^-7, below 1e-9 of the peak for alpha <= 0.2).
// NOT energy conserving for sheen = 1 at grazing incidence: V grows as both cosines vanish;
// the directional albedo at sheen = 1 is 0.14 / 0.44 / 0.59 at 0 / 80 / 89 deg incidence for
// alpha = 1, 0.0 / 0.34 / 2.8 for alpha = 0.01 (tests/models/test_physics.cc: 3.8 at 89.9 deg).
//
// Parameters: sheen_r, sheen_g, sheen_b [0, 1] linear weights (glTF sheenColorFactor);
// alpha [0.01, 1] (log scale).
struct Sheen {
  static constexpr std::string_view kName = "sheen";
  static constexpr std::string_view kDoc =
      "Charlie sheen (Estevez & Kulla 2017), Neubelt-Pettineo visibility, RGB weight sheen";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"sheen_r", "1", 0.0, 1.0, 0.1, false, "sheen colour, red", ParamRole::kWeightR},
      {"sheen_g", "1", 0.0, 1.0, 0.1, false, "sheen colour, green", ParamRole::kWeightG},
      {"sheen_b", "1", 0.0, 1.0, 0.1, false, "sheen colour, blue", ParamRole::kWeightB},
      {"alpha", "1", 0.01, 1.0, 0.25, true, "sheen alpha (glTF sheenRoughness = sqrt(alpha))"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    using std::exp;
    const T& alpha = p[3];
    const T inv_alpha = 1.0 / alpha;
    const T d = g.sin2_h > 0 ? (2.0 + inv_alpha) * exp((0.5 * std::log(g.sin2_h)) * inv_alpha) *
                                   (0.5 * kInvPi)
                             : T(0.0);
    const double v = 1.0 / (4.0 * (g.cos_i + g.cos_o - g.cos_i * g.cos_o));
    const T lobe = d * v;
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * lobe;
  }
};

}  // namespace brdfit
