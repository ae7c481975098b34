// Unreal Engine 4 metallic/roughness BRDF ("ue4").
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/microfacet/fresnel.h"
#include "models/microfacet/masking.h"
#include "models/microfacet/ndf.h"
#include "models/param.h"

namespace brdfit {

// Karis 2013, "Real Shading in Unreal Engine 4" (SIGGRAPH course notes), as shading tutorials
// implement it (OpenGL course 2023 §1.1; the metallic workflow of mebiusbox 2018's sample code;
// docs/models.md):
//   f_r = (1 - m) base / pi  +  D_GGX(h) G(wi, wo) F(wi.h) / (4 cos_i cos_o)
//   D: GGX (Walter 2007 eq. 33; Karis eq. 3), alpha = r^2
//   G: Schlick-Smith with k = (r + 1)^2 / 8 (Karis eq. 4-5)
//   F: Schlick, F0 = mix(0.04, base, m) per channel (Schlick 1994's (1 - c)^5; Karis 2013
//      uses a spherical-Gaussian fit of the same curve)
// [1/sr, without the cosine]. With kDiffuseFresnel the diffuse term is also weighted
// by (1 - F), as the OpenGL course 2023's shader code does.
// NOT energy conserving: the diffuse and specular terms are added without a (1 - F) coupling,
// so base = 1, m = 0 reflects more than 1 (Karis 2013 accepts this).
//
// Parameters: base_r, base_g, base_b [0, 1] (not linear weights: base also sets F0);
// metallic [0, 1]; alpha [1e-4, 1] (log).
template <bool kDiffuseFresnel>
struct Ue4Brdf {
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 5> kParams = {{
      {"base_r", "1", 0.0, 1.0, 0.5, false, "base colour, red"},
      {"base_g", "1", 0.0, 1.0, 0.5, false, "base colour, green"},
      {"base_b", "1", 0.0, 1.0, 0.5, false, "base colour, blue"},
      {"metallic", "1", 0.0, 1.0, 0.0, false, "metalness (0 dielectric, F0 = 0.04; 1 metal)"},
      {"alpha", "1", 1e-4, 1.0, 0.25, true, "GGX roughness alpha = r^2"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& m = p[3];
    const T& alpha = p[4];
    const T dg = DGgx(alpha, g.cos_h, g.sin2_h) *
                 SchlickSmith<SchlickK::kUe4>::template G<GgxNdf>(alpha, g) /
                 (4.0 * g.cos_i * g.cos_o);
    const double omc = OneMinusCosD(g);
    for (int c = 0; c < 3; ++c) {
      const T f0 = 0.04 * (1.0 - m) + p[c] * m;
      const T f = FSchlickOneMinusCos(f0, omc);
      T diffuse = (1.0 - m) * p[c] * kInvPi;
      if constexpr (kDiffuseFresnel) diffuse = diffuse * (1.0 - f);
      rgb[c] = diffuse + dg * f;
    }
  }
};

struct Ue4 : Ue4Brdf<false> {
  static constexpr std::string_view kName = "ue4";
  static constexpr std::string_view kDoc =
      "UE4 metallic/roughness (Karis 2013): Lambert + GGX, Schlick-Smith k=(r+1)^2/8, Schlick F";
};

}  // namespace brdfit
