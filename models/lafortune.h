// Lafortune generalized cosine lobe, isotropic ("lafortune"; sums give N lobes).
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// Lafortune, Foo, Torrance, Greenberg 1997, "Non-Linear Approximation of Reflectance
// Functions" (SIGGRAPH), the generalized cosine lobe model:
//   f_r(u, v) = sum_i [C_x,i u_x v_x + C_y,i u_y v_y + C_z,i u_z v_z]^n_i
// with u = wi, v = wo both pointing away from the surface; isotropic: C_x = C_y. Tutorials
// name it as the model for fitting measured data but print no formula: this follows the paper.
//
// Parameterization (one lobe; sums give N lobes):
//   f_r = rho (n + 2) / (2 pi) max(0, cxy s + c)^n / sqrt(1 + cxy^(2n))        [1/sr, no cosine]
//   s = u_x v_x + u_y v_y,  c = u_z v_z.
// The paper's lobe is redundant: scaling C by k and the weight by k^-n gives the same lobe. So
// C_z is fixed to 1 (C_x = C_y = cxy), which keeps every lobe with C_z > 0 — forward (cxy < 0;
// cxy = -1 is the Phong lobe about the mirror direction; -cxy > 1 grows towards grazing, the
// paper's off-specular/increasing reflectance), retro (cxy > 0) and near-horizontal lobes
// (|cxy| >> 1; Cornell's fitted blue paint has C_x/C_z = -19.5). The colour weight rho is
// separate and linear.
// Normalization: (n + 2) / (2 pi) makes rho the lobe's albedo at normal incidence (there s = 0
// and the lobe is cos^n th_o) while |cxy| < 1. Since |cxy s + c| <= max(1, |cxy|), the lobe can
// reach max(1, |cxy|)^n at grazing: 1 / sqrt(1 + cxy^(2n)) — a smooth version of Ngan et al.
// 2005's max(C_z^2, C_xy^2)^(-n/2) (which has a kink at |cxy| = 1) — bounds the shape factor
// by 1 for every cxy and n, so f_r <= rho (n + 2) / (2 pi) everywhere in bounds. It is computed
// as exp(n log(base) - softplus(2 n log|cxy|) / 2) without overflow.
// Equivalent paper coefficients (tested): C_z = (rho (n + 2) / (2 pi) / sqrt(1 + cxy^(2n)))^(1/n),
// C_x = C_y = cxy C_z. Energy: at normal incidence the albedo is rho / sqrt(1 + cxy^(2n)) <= rho;
// elsewhere it stayed <= rho in a dense numerical scan (cxy in [-4, 4] incl. +-(1 + k/n), n in
// [1, 300], theta_i up to 89.9 deg) — not proven; the white-furnace test keeps checking it.
// (The paper's raw form and the C_z = 1 normal-incidence normalization alone are not bounded:
// their grazing gain max(1, |cxy|)^n overflows for -cxy > 1 and large n.)
//
// Parameters: rho_r, rho_g, rho_b [0, 1e3] linear weights; cxy [-25, 25]; n [1, 1e5] (log).
// n >= 1 keeps d/d cxy of max(0, x)^n finite at x -> 0.
struct Lafortune {
  static constexpr std::string_view kName = "lafortune";
  static constexpr std::string_view kDoc =
      "isotropic Lafortune cosine lobe (Lafortune 1997), C_z = 1, smooth Ngan-style bound";
  static constexpr bool kEnergyConserving = true;
  static constexpr std::array<ParamSpec, 5> kParams = {{
      {"rho_r", "1", 0.0, 1e3, 0.1, false, "lobe weight (albedo at normal incidence), red",
       ParamRole::kWeightR},
      {"rho_g", "1", 0.0, 1e3, 0.1, false, "lobe weight (albedo at normal incidence), green",
       ParamRole::kWeightG},
      {"rho_b", "1", 0.0, 1e3, 0.1, false, "lobe weight (albedo at normal incidence), blue",
       ParamRole::kWeightB},
      {"cxy", "1", -25.0, 25.0, -1.0, false, "C_x = C_y relative to C_z = 1 (-1: mirror lobe)"},
      {"n", "1", 1.0, 1e5, 20.0, true, "lobe exponent"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    using std::exp;
    using std::log;
    using std::log1p;
    const T& cxy = p[3];
    const T& n = p[4];
    const double sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
    const T base = cxy * sxy + g.wi.z * g.wo.z;
    T lobe = T(0.0);
    // base <= 1e-300: the lobe is clipped to max(0, base)^n = 0 (and 1/base would overflow in
    // the Jet derivative).
    if (base > 1e-300) {
      T log_shape = n * log(base);
      // |cxy| < 1e-100: cxy^(2n) < 1e-200, the factor is 1 (and log(cxy^2) would be -inf).
      if (cxy * cxy > 1e-200) {
        const T t = n * log(cxy * cxy);  // 2 n log|cxy|
        // softplus(t) = log(1 + e^t), stable for both signs of t.
        const T softplus = t > 0.0 ? t + log1p(exp(-t)) : log1p(exp(t));
        log_shape = log_shape - 0.5 * softplus;
      }
      lobe = (n + 2.0) / (2.0 * kPi) * exp(log_shape);
    }
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * lobe;
  }
};

}  // namespace brdfit
