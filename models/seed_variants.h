// Model variants that reproduce formulas as tutorials and course notes print or code them. They
// are concrete types built from the same term families as the catalog models, but NOT in the
// catalog: they exist for the preview, for reproducing those sources' images and for tests, and
// are not fitted (each catalog entry costs a Ceres instantiation). docs/models.md ("Formula
// variants in tutorials and course notes") names the sources and maps every printed formula to
// the type or option here.
#pragma once

#include "models/burley.h"
#include "models/microfacet/microfacet.h"
#include "models/ue4.h"
#include "models/ward.h"

namespace brdfit {

// mebiusbox 2018 §4.9 / §6.5.3 (a Three.js sample): GGX D, Schlick-Smith G, Schlick F (F0
// fitted or from metallic). The text gives k = alpha/2 (eq. 74); the sample's shader code
// computes k = alpha^2/2 (+1e-6, dropped here). Parameters: ks RGB, alpha, f0.
using Seed000GgxText = Microfacet<GgxNdf, SchlickSmith<SchlickK::kAlphaHalf>, SchlickFresnel>;
using Seed000GgxCode = Microfacet<GgxNdf, SchlickSmith<SchlickK::kAlphaSqHalf>, SchlickFresnel>;

// Tokoi's lecture notes: Beckmann NDF with the Schlick-Smith k = sqrt(2 m^2 / pi) (Schlick 1994)
// and Schlick F. Their 1/(4 m^2 cos^4) under the Cook-Torrance pi-form equals Walter's
// normalized D under the 4-form.
using Seed001Beckmann =
    Microfacet<BeckmannNdf, SchlickSmith<SchlickK::kBeckmannFit>, SchlickFresnel>;

// Karis 2013 (UE4) as the shader of the OpenGL course 2023 (§1.1-1.4) computes it: the diffuse
// is also weighted by (1 - F). Parameters: base RGB, metallic, alpha.
using Seed002Ue4 = Ue4Brdf<true>;

// URP workshop 2025 step 12: Beckmann + V-groove + Schlick under the Walter 4-form. Its D lacks
// pi and has 1/4 (exp(..)/(4 alpha^2 cos^4)): ks here = (pi/4) x the workshop's base colour.
using Seed004CookTorrance = Microfacet<BeckmannNdf, VGroove, SchlickFresnel>;

// URP workshop 2025 step 15 specular: GGX D, Frostbite height-correlated G, Schlick F(F0),
// WITHOUT the workshop code's second division by 4 cos_i cos_o and its saturate() (a bug there:
// V_SmithGGXCorrelated already holds the 1/(4 cos_i cos_o)).
using Seed004PbrSpecular = Microfacet<GgxNdf, SmithHeightCorrelated, SchlickFresnel>;

// URP workshop 2025 step 9, Fresnel alternatives on a GGX lobe: Far Cry 3 and the exact
// dielectric.
using GgxFarCry3 = Microfacet<GgxNdf, SmithHeightCorrelated, FarCry3Fresnel>;
using GgxDielectric = Microfacet<GgxNdf, SmithHeightCorrelated, DielectricFresnel>;

// URP workshop 2025 step 14: Frostbite diffuse fed alpha as "linearRoughness" (Frostbite's
// linearRoughness is the perceptual r = sqrt(alpha)); and Burley 2012's original Disney diffuse
// (no renormalization).
using Seed004FrostbiteDiffuse = BurleyDiffuse<BurleyVariant::kSeed004>;
using DisneyDiffuse = BurleyDiffuse<BurleyVariant::kDisney>;

// URP workshop 2025 step 8 (which calls it the "Walter model"): anisotropic Ward (Ward 1992),
// alpha_x = RoughnessX^2.
using Seed004Ward = WardAniso<WardNormalization::kWard1992>;

}  // namespace brdfit
