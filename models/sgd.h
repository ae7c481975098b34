// Bagher et al.'s shifted gamma microfacet distribution ("sgd").
#pragma once

#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/microfacet/fresnel.h"
#include "models/microfacet/masking.h"
#include "models/param.h"

namespace brdfit {

// The upper incomplete gamma function at x = 1, Gamma(s, 1) = integral_1^inf t^(s-1) e^-t dt,
// for s in [-1, 1]. It is entire in s, so its Taylor series
//   Gamma(s, 1) = sum_k c_k s^k,   c_k = (1/k!) integral_1^inf (ln t)^k e^-t / t dt
// (c_0 = E1(1)) converges fast: 20 terms are within 2e-15 relative on [-1, 1] (tested against
// quadrature in tests/models/test_physics.cc). A polynomial, so Jets differentiate it in s.
template <class T>
T UpperGammaAt1(const T& s) {
  static constexpr std::array<double, 20> kC = {
      2.19383934395520286e-01, 9.78431972166701747e-02, 3.56034919284750201e-02,
      1.10708954460087810e-02, 3.02761119587879012e-03, 7.42658300486897073e-04,
      1.65756256060385003e-04, 3.40313948680864571e-05, 6.48260981742866804e-06,
      1.15371352882970288e-06, 1.92937438757823334e-07, 3.04649136782046469e-08,
      4.56072536045882244e-09, 6.49619948634066585e-10, 8.83120605373338925e-11,
      1.14894282074868457e-11, 1.43398107829324202e-12, 1.72064755919261112e-13,
      1.98877664832351651e-14, 2.21812901704154145e-15,
  };
  T acc = T(kC[19]);
  for (int k = 18; k >= 0; --k) acc = acc * s + kC[k];
  return acc;
}

// Bagher, Soler, Holzschuch 2012, "Accurate fitting of measured reflectances using a Shifted
// Gamma micro-facet distribution" (CGF 31(4), EGSR), the SGD (§4):
//   D(h) = P22(tan^2 th_h) / (pi cos^4 th_h),
//   P22(x) = K exp(-(alpha + x) / alpha) / (alpha + x)^p,   K = alpha^(p-1) / Gamma(1 - p, 1),
// K normalizing the projected area (integral D cos th_h d omega_h = integral_0^inf P22 = 1;
// tested). Evaluated as exp(-1 - x/alpha - p log1p(x/alpha)) / (alpha Gamma(1 - p, 1) ...),
// which neither overflows nor cancels for alpha down to 1e-6. p = 0 is Beckmann with
// alpha = m^2; p > 0 gives the long tails measured materials have.
template <class T>
T DSgd(const T& alpha, const T& p, double cos_h, double sin2_h) {
  using std::exp;
  using std::log1p;
  const double c2 = cos_h * cos_h;
  const T y = (sin2_h / c2) / alpha;  // tan^2 th_h / alpha
  return exp(-1.0 - y - p * log1p(y)) / (alpha * UpperGammaAt1(1.0 - p) * kPi * (c2 * c2));
}

// The SGD specular lobe in the Walter form (Walter et al. 2007 eq. 20):
//   f_r = ks D_SGD(h) G(wi, wo) F(wi.h) / (4 cos_i cos_o)       [1/sr, without the cosine]
// What differs from the paper, and why: the paper's G is the Smith G of the SGD, which has no
// closed form (the paper evaluates it numerically and fits an approximation); here G is the
// closed-form V-groove G of Cook & Torrance 1982 (models/microfacet/masking.h VGroove), which
// needs no table. F is Schlick's (1994 eq. 15) with one scalar f0, as in "cook-torrance", and
// the RGB weight ks holds the colour (the paper fits F0 per channel; ks and a per-channel F0
// would trade off). Hand-written, not a Microfacet<> composition: the SGD has two shape
// parameters (alpha, p) where Microfacet<> has one alpha.
// Energy conserving in the white furnace (tests/models/test_physics.cc) for ks <= 1.
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; alpha [1e-6, 1] (log); p [0, 2];
// f0 [0, 1].
struct Sgd {
  static constexpr std::string_view kName = "sgd";
  static constexpr std::string_view kDoc =
      "shifted gamma microfacet lobe (Bagher 2012), V-groove G, Schlick F, RGB weight ks";
  static constexpr bool kEnergyConserving = true;
  static constexpr std::array<ParamSpec, 6> kParams = {{
      {"ks_r", "1", 0.0, 1e3, 0.1, false, "specular weight, red", ParamRole::kWeightR},
      {"ks_g", "1", 0.0, 1e3, 0.1, false, "specular weight, green", ParamRole::kWeightG},
      {"ks_b", "1", 0.0, 1e3, 0.1, false, "specular weight, blue", ParamRole::kWeightB},
      {"alpha", "1", 1e-6, 1.0, 0.01, true, "SGD alpha (shift and width in tan^2 th_h)"},
      {"p", "1", 0.0, 2.0, 0.5, false, "SGD power p (0: Beckmann; larger: longer tails)"},
      {"f0", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence (Schlick)"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T lobe = DSgd(p[3], p[4], g.cos_h, g.sin2_h) * VGroove::G<void>(p[3], g) *
                   FSchlickOneMinusCos(p[5], OneMinusCosD(g)) / (4.0 * g.cos_i * g.cos_o);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * lobe;
  }
};

}  // namespace brdfit
