// Model variants that reproduce formulas as tutorials and course notes print or code them. They
// are concrete types built from the same term families as the catalog models (and from
// tests/models/variant_terms.h), but NOT in the catalog and used by no layer: they exist to
// show, in tests/models/test_oracles.cc, that each printed formula maps onto those terms.
// docs/models.md ("Formula variants in tutorials and course notes") names the sources and maps
// every printed formula to the type or option here.
#pragma once

#include "models/burley.h"
#include "models/microfacet/microfacet.h"
#include "models/ue4.h"
#include "models/ward.h"
#include "tests/models/variant_terms.h"

namespace brdfit {

// mebiusbox 2018 §4.9 / §6.5.3 (a Three.js sample): GGX D, Schlick-Smith G, Schlick F (F0
// fitted or from metallic). The text gives k = alpha/2 (eq. 74, SchlickK::kAlphaHalf); the
// sample's shader code computes k = alpha^2/2 (+1e-6, dropped here). Parameters: ks RGB,
// alpha, f0.
using MebiusboxGgxCode = Microfacet<GgxNdf, SchlickSmith<SchlickK::kAlphaSqHalf>, SchlickFresnel>;

// Tokoi's lecture notes: Beckmann NDF with the Schlick-Smith k = sqrt(2 m^2 / pi) (Schlick 1994)
// and Schlick F. Their 1/(4 m^2 cos^4) under the Cook-Torrance pi-form equals Walter's
// normalized D under the 4-form.
using TokoiBeckmann = Microfacet<BeckmannNdf, SchlickSmith<SchlickK::kBeckmannFit>, SchlickFresnel>;

// Karis 2013 (UE4) as the shader of the OpenGL course 2023 (§1.1-1.4) computes it: the diffuse
// is also weighted by (1 - F). Parameters: base RGB, metallic, alpha.
using OpenGlCourseUe4 = Ue4Brdf<true>;

// URP workshop 2025 step 12: Beckmann + V-groove + Schlick under the Walter 4-form. Its D lacks
// pi and has 1/4 (exp(..)/(4 alpha^2 cos^4)): ks here = (pi/4) x the workshop's base colour.
using UrpCookTorrance = Microfacet<BeckmannNdf, VGroove, SchlickFresnel>;

// URP workshop 2025 step 15 specular: GGX D, Frostbite height-correlated G, Schlick F(F0),
// WITHOUT the workshop code's second division by 4 cos_i cos_o and its saturate() (a bug there:
// V_SmithGGXCorrelated already holds the 1/(4 cos_i cos_o)).
using UrpPbrSpecular = Microfacet<GgxNdf, SmithHeightCorrelated, SchlickFresnel>;

// URP workshop 2025 step 9, Fresnel alternatives on a GGX lobe: Far Cry 3 and the exact
// dielectric.
using GgxFarCry3 = Microfacet<GgxNdf, SmithHeightCorrelated, FarCry3Fresnel>;
using GgxDielectric = Microfacet<GgxNdf, SmithHeightCorrelated, DielectricFresnel>;

// URP workshop 2025 step 14: Frostbite diffuse fed alpha as "linearRoughness" (Frostbite's
// linearRoughness is the perceptual r = sqrt(alpha)). Burley 2012's original is in the catalog
// (burley-2012).
using UrpFrostbiteDiffuse = BurleyDiffuse<BurleyVariant::kUrpLinearRoughness>;

// Anisotropic Ward lobe, Ward 1992 eq. 5:
//   f_r = rho_s exp(-tan^2 th_h (cos^2 ph_h / ax^2 + sin^2 ph_h / ay^2))
//         / (4 pi ax ay sqrt(cos_i cos_o))
//       = rho_s exp(-((h.x/ax)^2 + (h.y/ay)^2) / h.z^2) / (4 pi ax ay sqrt(cos_i cos_o)),
// x = the tangent direction of the local frame. NOT in the catalog (fitted tables are
// isotropic). Parameters: rho_s RGB weights,
// alpha_x, alpha_y [1e-4, 1] (log).
template <WardNormalization N = WardNormalization::kWard1992>
struct WardAniso {
  static constexpr std::string_view kName = "ward-aniso";
  static constexpr std::string_view kDoc = "anisotropic Ward lobe (Ward 1992 eq. 5)";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 5> kParams = {{
      detail::kWardWeights[0],
      detail::kWardWeights[1],
      detail::kWardWeights[2],
      {"alpha_x", "1", 1e-4, 1.0, 0.1, true, "Ward roughness along the tangent x"},
      {"alpha_y", "1", 1e-4, 1.0, 0.1, true, "Ward roughness along the bitangent y"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    using std::exp;
    const T& ax = p[3];
    const T& ay = p[4];
    const double hz2 = g.h.z * g.h.z;
    const T e = (g.h.x * g.h.x / hz2) / (ax * ax) + (g.h.y * g.h.y / hz2) / (ay * ay);
    const T spec = exp(-e) * detail::WardNormalizationFactor(N, ax, ay, g);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * spec;
  }
};

// URP workshop 2025 step 8 (which calls it the "Walter model"): anisotropic Ward (Ward 1992),
// alpha_x = RoughnessX^2.
using UrpWard = WardAniso<WardNormalization::kWard1992>;

}  // namespace brdfit
