// Löw et al.'s smooth-surface ("ABC") lobe ("abc").
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/microfacet/fresnel.h"
#include "models/param.h"

namespace brdfit {

// Löw, Kronander, Ynnerman, Unger 2012, "BRDF Models for Accurate and Efficient Rendering of
// Glossy Surfaces" (ACM TOG 31(1)), the smooth surface model (§4): a Rayleigh-Rice style lobe
// whose power spectral density is the ABC (K-correlation) function of Church et al.,
// evaluated at the length of the projected deviation vector D_p, the difference between the
// projections on the surface plane of wo and of the mirror direction of wi:
//   D_p = (wi.x + wo.x, wi.y + wo.y),   S(f) = 1 / (1 + B f^2)^C,
//   f_r = A S(|D_p|) F(wi.h)                                      [1/sr, without the cosine]
// The form implemented is stated here because the paper was not at hand: this is the form the
// ALTA library's "abc" plugin fits, A / (1 + B x)^C, with x = |D_p|^2 (ALTA's plugin uses
// x = 1 - cos th_h, the model's microfacet variant); Church's printed PSD
// A / (1 + B^2 f^2)^((C + 1) / 2) is the same family (B^2 -> B, (C + 1)/2 -> C). The paper's
// Fresnel factor (with an index of refraction) is Schlick's approximation here (Schlick 1994
// eq. 15, f0 = ((eta - 1)/(eta + 1))^2); the Rayleigh-Rice obliquity factors are folded into A,
// as in the paper's simplified model. A is the per-channel peak value (linear weights).
// NOT energy conserving: S is not normalized (A = 1 with a broad S reflects pi F).
//
// Parameters: a_r, a_g, a_b [0, 1e5] linear weights; b [1e-2, 1e8] (log); c [1e-2, 10] (log);
// f0 [0, 1].
struct Abc {
  static constexpr std::string_view kName = "abc";
  static constexpr std::string_view kDoc =
      "Low et al. 2012 smooth-surface lobe: A / (1 + B |D_p|^2)^C times Schlick F";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 6> kParams = {{
      {"a_r", "1/sr", 0.0, 1e5, 1.0, false, "peak value A, red", ParamRole::kWeightR},
      {"a_g", "1/sr", 0.0, 1e5, 1.0, false, "peak value A, green", ParamRole::kWeightG},
      {"a_b", "1/sr", 0.0, 1e5, 1.0, false, "peak value A, blue", ParamRole::kWeightB},
      {"b", "1", 1e-2, 1e8, 1e3, true, "ABC B: inverse squared width in projected space"},
      {"c", "1", 1e-2, 10.0, 1.0, true, "ABC C: fall-off exponent of the lobe's tail"},
      {"f0", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence (Schlick)"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    using std::exp;
    using std::log1p;
    const double dx = g.wi.x + g.wo.x, dy = g.wi.y + g.wo.y;
    const T s = exp(-p[4] * log1p(p[3] * (dx * dx + dy * dy)));
    const T lobe = s * FSchlickOneMinusCos(p[5], OneMinusCosD(g));
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * lobe;
  }
};

}  // namespace brdfit
