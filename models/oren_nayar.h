// Oren-Nayar rough diffuse reflection: the qualitative model ("oren-nayar") and Fujii's
// improved form ("oren-nayar-fujii", Blender Cycles' Diffuse BSDF).
#pragma once

#include <algorithm>
#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/param.h"

namespace brdfit {

// Oren & Nayar 1994, "Generalization of Lambert's Reflectance Model" (SIGGRAPH), eq. 30 (the
// qualitative model):
//   f_r = kd / pi (A + B max(0, cos(ph_i - ph_o)) sin(a) tan(b)),  a = max(th_i, th_o),
//   b = min(th_i, th_o),  A = 1 - 0.5 s^2 / (s^2 + 0.33),  B = 0.45 s^2 / (s^2 + 0.09),
// s = sigma, the standard deviation of the facet slope angle (radians).     [1/sr, no cosine]
// Vector form without angles or singular points (after the vector form of Tokoi's lecture
// notes, whose L_proj = L - N(N.V) is a typo for N(N.L)):
// cos(dph) sin(th_i) sin(th_o) = wi.x wo.x + wi.y wo.y and
// sin(a) tan(b) = sin(th_i) sin(th_o) / cos(b) = sin(th_i) sin(th_o) / max(cos_i, cos_o), so
//   f_r = kd / pi (A + B max(0, wi.x wo.x + wi.y wo.y) / max(cos_i, cos_o)).
// sigma = 0 is Lambert. NOT energy conserving: the qualitative model is a fit to the full
// Oren-Nayar model, and with kd = 1 its directional albedo reaches 1.015 at 89.9 deg incidence
// (sigma ~ 0.2; tests/models/test_physics.cc); below ~85 deg it stays <= 1.
//
// Parameters: kd_r, kd_g, kd_b [0, 1] linear weights; sigma [0, pi/2] rad.
struct OrenNayar {
  static constexpr std::string_view kName = "oren-nayar";
  static constexpr std::string_view kDoc =
      "Oren-Nayar rough diffuse (1994, qualitative model eq. 30), sigma = facet slope std. dev.";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"kd_r", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, red", ParamRole::kWeightR},
      {"kd_g", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, green", ParamRole::kWeightG},
      {"kd_b", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, blue", ParamRole::kWeightB},
      {"sigma", "rad", 0.0, kPi / 2, 0.3, false, "std. dev. of the facet slope angle"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T s2 = p[3] * p[3];
    const T a = 1.0 - 0.5 * s2 / (s2 + 0.33);
    const T b = 0.45 * s2 / (s2 + 0.09);
    const double sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
    const double geo = std::max(0.0, sxy) / std::max(g.cos_i, g.cos_o);
    const T shape = (a + b * geo) * kInvPi;
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * shape;
  }
};

// Fujii 2012, "A tiny improvement of Oren-Nayar reflectance model"
// (mimosa-pudica.net/improved-oren-nayar.html), the "improved ON" form:
//   f_r = kd (A + B s / t),  s = wi.wo - cos_i cos_o,  t = max(cos_i, cos_o) if s > 0 else 1,
//   A = 1 / (pi + (pi/2 - 2/3) sigma),  B = sigma A.                       [1/sr, no cosine]
// s = sin(th_i) sin(th_o) cos(ph_i - ph_o) = wi.x wo.x + wi.y wo.y; unlike eq. 30 above, s < 0
// (lights and views on opposite sides) darkens instead of being clamped to 0. sigma is Fujii's
// roughness in [0, 1], not eq. 30's slope deviation. This is Blender Cycles' Diffuse BSDF
// (intern/cycles/kernel/closure/bsdf_oren_nayar.h: div = 1 / (pi + ((3 pi - 4) / 6) sigma),
// a = div, b = sigma div, sigma = saturate(Roughness)), checked against Cycles renders by
// scripts/cycles_diffuse_roughness_check.py. sigma = 0 is Lambert. Energy conserving: with
// kd = 1 the directional albedo is 1 at sigma = 0 and below 1 otherwise (0.78 at normal
// incidence and sigma = 1; tests/models/test_physics.cc).
//
// Parameters: kd_r, kd_g, kd_b [0, 1] linear weights; sigma [0, 1] (Cycles' Roughness).
struct OrenNayarFujii {
  static constexpr std::string_view kName = "oren-nayar-fujii";
  static constexpr std::string_view kDoc =
      "Oren-Nayar rough diffuse, Fujii's improved form (Blender Cycles' Diffuse BSDF), "
      "sigma = Cycles' Roughness in [0, 1]";
  static constexpr bool kEnergyConserving = true;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"kd_r", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, red", ParamRole::kWeightR},
      {"kd_g", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, green", ParamRole::kWeightG},
      {"kd_b", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, blue", ParamRole::kWeightB},
      {"sigma", "1", 0.0, 1.0, 0.3, false, "roughness (Cycles' Diffuse BSDF Roughness)"},
  }};

  // A(sigma) = 1 / (pi + (pi/2 - 2/3) sigma): f_r / kd where s = 0 (normal incidence or view).
  template <class T>
  static T A(const T& sigma) {
    return 1.0 / (kPi + (kPi / 2 - 2.0 / 3.0) * sigma);
  }

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& sigma = p[3];
    const T a = A(sigma);
    const double s = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
    // max(cos_i, cos_o) > 0 for every geometry a table or image evaluates (both above the
    // surface); s / t is bounded by 1 in magnitude.
    const double st = s > 0 ? s / std::max(g.cos_i, g.cos_o) : s;
    const T shape = a * (1.0 + sigma * st);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * shape;
  }
};

}  // namespace brdfit
