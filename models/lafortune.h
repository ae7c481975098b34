// Lafortune generalized cosine lobe, isotropic ("lafortune"; sums give N lobes).
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// Lafortune, Foo, Torrance, Greenberg 1997, "Non-Linear Approximation of Reflectance
// Functions" (SIGGRAPH), eq. 5-6: one lobe of
//   f_r(u, v) = sum_i [C_x,i u_x v_x + C_y,i u_y v_y + C_z,i u_z v_z]^n_i
// with u = wi, v = wo both pointing away from the surface; isotropic: C_x = C_y.
// (No Lafortune formula appears in the seeds; seeds 000 and 001 name it as the model for
// fitting measured data.)
//
// Parameterization used here (one lobe):
//   f_r = rho (n + 2) / (2 pi) max(0, cxy (u_x v_x + u_y v_y) + u_z v_z)^n     [1/sr, no cosine]
// The paper's lobe is redundant: scaling C by s and the weight by s^-n gives the same lobe, so
// C_z is fixed to 1 (C_x = C_y = cxy C_z) and the colour weight is separate (rho, linear). This
// covers every lobe with C_z > 0 — forward (cxy < 0; cxy = -1 is the Phong lobe about the
// mirror direction, -cxy > 1 the off-specular lobe that grows towards grazing), retro (cxy > 0)
// and diffuse-like (cxy = 0). (n + 2)/(2 pi) makes rho the lobe's albedo at normal incidence for
// every cxy (there u_x = u_y = 0 and the lobe is cos^n th_o). Equivalent original coefficients:
// C_z = (rho (n + 2) / (2 pi))^(1/n), C_x = C_y = cxy C_z (tested against that form).
//
// Bounds: cxy in [-1.1, 1.1], n in [1, 5000]. The lobe's largest value relative to normal
// incidence is max(1, |cxy|)^n (at grazing), so these bounds keep f_r finite (n ln 1.1 < 477);
// n >= 1 keeps d/d cxy of max(0, x)^n finite at x -> 0. Lobes narrower than n = 5000 (~1 deg)
// are better fitted with GGX. NOT energy conserving for |cxy| > 1 (grazing gain).
//
// Parameters: rho_r, rho_g, rho_b [0, 1e3] linear weights; cxy [-1.1, 1.1]; n [1, 5000] (log).
struct Lafortune {
  static constexpr std::string_view kName = "lafortune";
  static constexpr std::string_view kDoc =
      "isotropic Lafortune cosine lobe (Lafortune 1997), C_z = 1, rho = normal-incidence albedo";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 5> kParams = {{
      {"rho_r", "1", 0.0, 1e3, 0.1, false, "lobe albedo at normal incidence, red",
       ParamRole::kWeightR},
      {"rho_g", "1", 0.0, 1e3, 0.1, false, "lobe albedo at normal incidence, green",
       ParamRole::kWeightG},
      {"rho_b", "1", 0.0, 1e3, 0.1, false, "lobe albedo at normal incidence, blue",
       ParamRole::kWeightB},
      {"cxy", "1", -1.1, 1.1, -1.0, false, "C_x = C_y relative to C_z = 1 (-1: mirror lobe)"},
      {"n", "1", 1.0, 5000.0, 20.0, true, "lobe exponent"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& cxy = p[3];
    const T& n = p[4];
    const double sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
    const T base = cxy * sxy + g.wi.z * g.wo.z;
    const T lobe = (n + 2.0) / (2.0 * kPi) * PowClipped(base, n);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * lobe;
  }
};

}  // namespace brdfit
