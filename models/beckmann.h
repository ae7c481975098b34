// Beckmann microfacet specular lobe ("beckmann").
#pragma once

#include <string_view>

#include "models/microfacet/microfacet.h"

namespace brdfit {

// Beckmann lobe in Walter et al. 2007's form (eq. 20), D eq. 25 normalized with pi, separable
// Smith G with the exact Beckmann Lambda (erf form, Walter §5.1 / Heitz 2014 §5.3); Fresnel
// folded into ks:
//   f_r = ks exp(-tan^2 th_h / alpha^2) / (pi alpha^2 cos^4 th_h) G1(wi) G1(wo) / (4 cos_i cos_o)
// [1/sr, without the cosine]. Some course notes print the NDF without pi (1/(4 m^2 cos^4),
// 1/(alpha^2 cos^4)); the constant factor is absorbed by ks (docs/models.md).
// Energy conserving for ks <= 1.
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; alpha = RMS slope m [1e-4, 1] (log).
struct Beckmann : Microfacet<BeckmannNdf, SmithSeparable, NoFresnel> {
  static constexpr std::string_view kName = "beckmann";
  static constexpr std::string_view kDoc =
      "Beckmann microfacet lobe (Walter 2007), exact separable Smith G, Fresnel folded into ks";
  static constexpr bool kEnergyConserving = true;
};

}  // namespace brdfit
