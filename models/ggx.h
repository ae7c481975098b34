// GGX / Trowbridge-Reitz microfacet specular lobes ("ggx", "ggx-hc", "ggx-f0").
#pragma once

#include <array>
#include <string_view>

#include "models/microfacet/microfacet.h"

namespace brdfit {

// GGX lobe, Walter et al. 2007 ("Microfacet Models for Refraction through Rough Surfaces",
// EGSR) eq. 20 with D eq. 33 and separable Smith G (G1 eq. 34; Heitz 2014 eq. 98); Fresnel
// folded into the RGB weight ks:
//   f_r = ks D_GGX(h) G1(wi) G1(wo) / (4 cos_i cos_o)       [1/sr, without the cosine]
// Karis 2013 and the tutorials of docs/models.md print the same D (their G and F differ).
// Energy conserving for ks <= 1 (the single-scattering lobe loses energy).
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; alpha [1e-4, 1] (log scale).
struct Ggx : Microfacet<GgxNdf, SmithSeparable, NoFresnel> {
  static constexpr std::string_view kName = "ggx";
  static constexpr std::string_view kDoc =
      "GGX microfacet lobe (Walter 2007), separable Smith G, Fresnel folded into ks";
  static constexpr bool kEnergyConserving = true;
};

// GGX lobe with height-correlated Smith G (Heitz 2014 eq. 99), the G of Frostbite's
// V_SmithGGXCorrelated (Lagarde & de Rousiers 2014, Listing 2; that V already holds the
// 1/(4 cos_i cos_o)):
//   f_r = ks D_GGX(h) / ((1 + Lambda(wi) + Lambda(wo)) 4 cos_i cos_o)
// Same parameters as "ggx". Energy conserving for ks <= 1.
struct GgxHc : Microfacet<GgxNdf, SmithHeightCorrelated, NoFresnel> {
  static constexpr std::string_view kName = "ggx-hc";
  static constexpr std::string_view kDoc =
      "GGX microfacet lobe (Walter 2007), height-correlated Smith G (Heitz 2014), Fresnel in ks";
  static constexpr bool kEnergyConserving = true;
};

// GGX lobe with a free per-channel Schlick F0 and height-correlated Smith G, the specular term
// of the glTF 2.0 metallic-roughness BRDF (and of UE4-style fits, Karis 2013) with F90 = 1:
//   f_r = D_GGX(h) G2(wi, wo) F_c(wi.h) / (4 cos_i cos_o)       [1/sr, without the cosine]
//   D:  Walter et al. 2007 ("Microfacet Models for Refraction through Rough Surfaces") eq. 33
//   G2: Heitz 2014 ("Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
//       JCGT 3(2)) eq. 99, 1 / (1 + Lambda(wi) + Lambda(wo))
//   F:  Schlick 1994 eq. 15, F_c = f0_c + (1 - f0_c)(1 - wi.h)^5 per channel
// Parameterization: per-channel F0 and NO separate specular weight. A weight ks in front of
// F would trade off with F0 (ks F0 and ks (1 - F0) are the two identifiable combinations, and
// at F0 -> 1 only their sum is), so ks is fixed to 1: the lobe is physically plausible
// (F <= 1) and its colour at normal incidence is F0, its grazing colour white. The parameters
// are not linear weights (F has the constant term (1 - c)^5), so they are shape parameters.
// Energy conserving (F <= 1 and the single-scattering lobe loses energy); a sum with a diffuse
// lobe is not (nothing couples the diffuse weight to 1 - F: models/sum.h).
//
// Parameters: f0_r, f0_g, f0_b [0, 1]; alpha [1e-4, 1] (log scale).
struct GgxF0 {
  static constexpr std::string_view kName = "ggx-f0";
  static constexpr std::string_view kDoc =
      "GGX lobe (Walter 2007), height-correlated Smith G (Heitz 2014), Schlick F with RGB F0";
  static constexpr bool kEnergyConserving = true;
  // The lobe's albedo is not scaled by linear weights (models/sum.h).
  static constexpr bool kHasWeights = false;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"f0_r", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence, red"},
      {"f0_g", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence, green"},
      {"f0_b", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence, blue"},
      GgxNdf::kAlpha,
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& alpha = p[3];
    const T dg = GgxNdf::D(alpha, g) * SmithHeightCorrelated::G<GgxNdf>(alpha, g) /
                 (4.0 * g.cos_i * g.cos_o);
    const double omc = OneMinusCosD(g);
    for (int c = 0; c < 3; ++c) rgb[c] = dg * FSchlickOneMinusCos(p[c], omc);
  }
};

}  // namespace brdfit
