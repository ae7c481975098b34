// Burley (Disney) diffuse: with Frostbite's renormalization ("burley") and Burley 2012's
// original ("burley-2012", Blender Cycles' Principled BSDF diffuse).
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

enum class BurleyVariant {
  kFrostbite,  // Lagarde & de Rousiers 2014 renormalized, linearRoughness r = sqrt(alpha)
  kDisney,     // Burley 2012 original (albedo up to 1.55 at r = 1: not energy conserving)
  // URP workshop 2025 steps 14-15: Frostbite's code fed alpha as linearRoughness.
  kUrpLinearRoughness,
};

// Burley 2012, "Physically-Based Shading at Disney" (SIGGRAPH course), §5.3 diffuse:
//   f_d = kd / pi (1 + (F_D90 - 1)(1 - cos_i)^5)(1 + (F_D90 - 1)(1 - cos_o)^5),
//   F_D90 = 0.5 + 2 r cos_d^2,
// and Lagarde & de Rousiers 2014, "Moving Frostbite to Physically Based Rendering 3.0"
// (SIGGRAPH course), Listing 1 (Fr_DisneyDiffuse):
//   energyBias = lerp(0, 0.5, r), energyFactor = lerp(1, 1/1.51, r),
//   F_D90 = energyBias + 2 r cos_d^2,  f_d = kd / pi * F(cos_i) F(cos_o) * energyFactor,
//   F(c) = 1 + (F_D90 - 1)(1 - c)^5.                                         [1/sr, no cosine]
// r is Frostbite's "linearRoughness", the perceptual roughness: r = sqrt(alpha) (the project's
// parameter is alpha). The URP workshop 2025 (step 14, docs/models.md) passes alpha itself as
// linearRoughness; kUrpLinearRoughness reproduces it.
// NOT energy conserving: Frostbite's renormalization (energyFactor = 1/1.51 at r = 1) is a fit;
// with kd = 1 the directional albedo reaches 1.03 at 89.9 deg incidence and r = 1 (1.009 at
// 89 deg); Burley 2012's original reaches 1.55 at 89.9 deg (1.28 at 80)
// (tests/models/test_physics.cc).
//
// Parameters: kd_r, kd_g, kd_b [0, 1] linear weights; alpha [1e-4, 1].
template <BurleyVariant V>
struct BurleyDiffuse {
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"kd_r", "1", 0.0, 1.0, 0.5, false, "diffuse albedo (base colour), red", ParamRole::kWeightR},
      {"kd_g", "1", 0.0, 1.0, 0.5, false, "diffuse albedo (base colour), green",
       ParamRole::kWeightG},
      {"kd_b", "1", 0.0, 1.0, 0.5, false, "diffuse albedo (base colour), blue",
       ParamRole::kWeightB},
      {"alpha", "1", 1e-4, 1.0, 0.25, false, "roughness alpha (linearRoughness = sqrt(alpha))"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    using std::sqrt;
    const T& alpha = p[3];
    // alpha >= 1e-4 in bounds: sqrt's derivative is finite.
    const T r = V == BurleyVariant::kUrpLinearRoughness ? alpha : sqrt(alpha);
    const bool frostbite = V != BurleyVariant::kDisney;
    const T bias = frostbite ? 0.5 * r : T(0.5);
    const T factor = frostbite ? 1.0 + (1.0 / 1.51 - 1.0) * r : T(1.0);
    const T fd90 = bias + 2.0 * (g.cos_d * g.cos_d) * r;
    const T fl = 1.0 + (fd90 - 1.0) * Pow5(OneMinusCos(g.wi));
    const T fv = 1.0 + (fd90 - 1.0) * Pow5(OneMinusCos(g.wo));
    const T shape = fl * fv * factor * kInvPi;
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * shape;
  }
};

struct Burley : BurleyDiffuse<BurleyVariant::kFrostbite> {
  static constexpr std::string_view kName = "burley";
  static constexpr std::string_view kDoc =
      "Burley/Disney diffuse with Frostbite renormalization (Lagarde 2014), r = sqrt(alpha)";
};

// Burley 2012's original, unrenormalized. Blender Cycles 3.4's Principled BSDF evaluates the
// same diffuse in Burley 2015's split form (bsdf_principled_diffuse.h):
//   (1 - FL/2)(1 - FV/2) + RR (FL + FV + FL FV (RR - 1)),  RR = r (1 + wi.wo) = 2 r cos_d^2,
// which expands to (1 + (F_D90 - 1) FL)(1 + (F_D90 - 1) FV) with F_D90 = 0.5 + RR; its
// Roughness input is r = sqrt(alpha) (checked against Cycles renders by
// scripts/cycles_diffuse_roughness_check.py).
struct Burley2012 : BurleyDiffuse<BurleyVariant::kDisney> {
  static constexpr std::string_view kName = "burley-2012";
  static constexpr std::string_view kDoc =
      "Burley/Disney diffuse as published (Burley 2012, Blender Cycles' Principled diffuse), "
      "r = sqrt(alpha)";
};

}  // namespace brdfit
