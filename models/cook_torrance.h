// Cook-Torrance specular lobe as Ngan et al. 2005 fit it ("cook-torrance").
#pragma once

#include <string_view>

#include "models/microfacet/microfacet.h"

namespace brdfit {

// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics" (ACM TOG 1(1)), in the form
// Ngan, Durand, Matusik 2005 ("Experimental Analysis of BRDF Models", EGSR) fit to MERL (as
// reproduced by bsdfbenchmark/bbm `ngancooktorrance`):
//   f_r = ks F_Schlick(F0, wi.h) D_Beckmann(h) G_Vgroove / (pi cos_i cos_o)
// with D normalized as in Walter 2007 eq. 25, G = min(1, 2 (n.h)(n.wo)/(wo.h), 2
// (n.h)(n.wi)/(wo.h)) and Schlick's F with F0 a fitted shape parameter. [1/sr, without the cosine.]
// Tutorials print the same terms (docs/models.md): the pi form (mebiusbox 2018 eq. 79), and the
// URP workshop 2025's step 12 (Beckmann + V-groove + Schlick, with the Walter 4 and an
// un-normalized D: same shape, ks rescaled by pi/4 and pi).
// NOT energy conserving with ks = 1: the pi form is 4/pi times the Walter form.
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; alpha = Beckmann m [1e-4, 1] (log);
// f0 [0, 1].
struct CookTorrance
    : Microfacet<BeckmannNdf, VGroove, SchlickFresnel, MicrofacetForm::kCookTorrance> {
  static constexpr std::string_view kName = "cook-torrance";
  static constexpr std::string_view kDoc =
      "Cook-Torrance as Ngan 2005: Beckmann D, V-groove G, Schlick F(F0), pi normalization";
  static constexpr bool kEnergyConserving = false;
};

}  // namespace brdfit
