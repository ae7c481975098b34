// GGX / Trowbridge-Reitz microfacet specular lobes ("ggx", "ggx-hc").
#pragma once

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

}  // namespace brdfit
