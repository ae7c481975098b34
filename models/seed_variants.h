// Model variants that reproduce the seeds' formulas (seeds-digest §2, §2.14). They are
// concrete types built from the same term families as the catalog models, but NOT in the
// catalog: they exist for the preview, for seed-image reproduction and for tests, and are not
// fitted (each catalog entry costs a Ceres instantiation). docs/models.md maps every seed
// formula to the type or option here.
#pragma once

#include "models/burley.h"
#include "models/microfacet/microfacet.h"
#include "models/ue4.h"
#include "models/ward.h"

namespace brdfit {

// Seed 000 §4.9 / §6.5.3: GGX D, Schlick-Smith G, Schlick F (F0 fitted or from metallic).
// The text gives k = alpha/2 (eq. 74); the seed's shader code computes k = alpha^2/2 (+1e-6,
// dropped here) (D1). Parameters: ks RGB, alpha, f0.
using Seed000GgxText = Microfacet<GgxNdf, SchlickSmith<SchlickK::kAlphaHalf>, SchlickFresnel>;
using Seed000GgxCode = Microfacet<GgxNdf, SchlickSmith<SchlickK::kAlphaSqHalf>, SchlickFresnel>;

// Seed 001: Beckmann NDF with the Schlick-Smith k = sqrt(2 m^2 / pi) and Schlick F. Seed 001's
// 1/(4 m^2 cos^4) under the Cook-Torrance pi-form equals Walter's normalized D under the 4-form.
using Seed001Beckmann =
    Microfacet<BeckmannNdf, SchlickSmith<SchlickK::kBeckmannFit>, SchlickFresnel>;

// Seed 002 §1.1-1.4 (UE4 as the seed's shader computes it): the diffuse is also weighted by
// (1 - F) (D9). Parameters: base RGB, metallic, alpha.
using Seed002Ue4 = Ue4Brdf<true>;

// Seed 003 / 004 Sphere(12): Beckmann + V-groove + Schlick under the Walter 4-form. Seed 004's
// D lacks pi and has 1/4 (exp(..)/(4 alpha^2 cos^4)): ks here = (pi/4) x the seed's base colour.
using Seed004CookTorrance = Microfacet<BeckmannNdf, VGroove, SchlickFresnel>;

// Seed 004 Sphere(15) specular: GGX D, Frostbite height-correlated G, Schlick F(F0), WITHOUT the
// seed's second division by 4 cos_i cos_o and the saturate() (a known seed bug, §5.6.6).
using Seed004PbrSpecular = Microfacet<GgxNdf, SmithHeightCorrelated, SchlickFresnel>;

// Seed 004 Sphere(9) Fresnel alternatives on a GGX lobe: Far Cry 3 and the exact dielectric.
using GgxFarCry3 = Microfacet<GgxNdf, SmithHeightCorrelated, FarCry3Fresnel>;
using GgxDielectric = Microfacet<GgxNdf, SmithHeightCorrelated, DielectricFresnel>;

// Seed 004 Sphere(14): Frostbite diffuse fed alpha as "linearRoughness" (D20); and Burley 2012's
// original Disney diffuse (no renormalization).
using Seed004FrostbiteDiffuse = BurleyDiffuse<BurleyVariant::kSeed004>;
using DisneyDiffuse = BurleyDiffuse<BurleyVariant::kDisney>;

// Seed 004 Sphere(8) ("Walter model"): anisotropic Ward, alpha_x = RoughnessX^2.
using Seed004Ward = WardAniso<WardNormalization::kWard1992>;

}  // namespace brdfit
