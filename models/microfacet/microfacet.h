// The microfacet specular lobe, assembled from an NDF, a masking term and a Fresnel term:
//
//   Walter form (default):  f = ks * D(h) G(wi, wo) F(wi.h) / (4 cos_i cos_o)
//       Walter et al. 2007 eq. 20 (the project default, and the form most tutorials use).
//   Cook-Torrance form:     f = ks * D(h) G(wi, wo) F(wi.h) / (pi cos_i cos_o)
//       Cook & Torrance 1982 as used by Ngan et al. 2005 (F/pi folded with ks).
//
// Parameters: ks_r, ks_g, ks_b (linear RGB weights, kWeight roles), alpha (Ndf::kAlpha), then
// Fresnel::kParams. f_r in 1/sr, without the cosine. Named models derive from this template
// and add kName/kDoc (models/ggx.h, models/beckmann.h, models/cook_torrance.h).
#pragma once

#include <array>
#include <string_view>
#include <tuple>

#include "models/geometry.h"
#include "models/microfacet/fresnel.h"
#include "models/microfacet/masking.h"
#include "models/microfacet/ndf.h"
#include "models/param.h"

namespace brdfit {

enum class MicrofacetForm { kWalter, kCookTorrance };

namespace detail {
template <std::size_t N, std::size_t M>
constexpr std::array<ParamSpec, N + M> ConcatSpecs(const std::array<ParamSpec, N>& a,
                                                   const std::array<ParamSpec, M>& b) {
  std::array<ParamSpec, N + M> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = a[i];
  for (std::size_t i = 0; i < M; ++i) out[N + i] = b[i];
  return out;
}

// RGB weight parameter specs shared by the specular lobes.
inline constexpr std::array<ParamSpec, 3> kSpecularWeights = {{
    {"ks_r", "1", 0.0, 1e3, 0.1, false, "specular weight, red", ParamRole::kWeightR},
    {"ks_g", "1", 0.0, 1e3, 0.1, false, "specular weight, green", ParamRole::kWeightG},
    {"ks_b", "1", 0.0, 1e3, 0.1, false, "specular weight, blue", ParamRole::kWeightB},
}};
}  // namespace detail

template <class Ndf, class Masking, class Fresnel, MicrofacetForm Form = MicrofacetForm::kWalter>
struct Microfacet {
  using NdfType = Ndf;
  using MaskingType = Masking;
  using FresnelType = Fresnel;
  static constexpr MicrofacetForm kForm = Form;

  static constexpr std::array<ParamSpec, 4 + std::tuple_size_v<decltype(Fresnel::kParams)>>
      kParams = detail::ConcatSpecs(
          detail::ConcatSpecs(detail::kSpecularWeights, std::array<ParamSpec, 1>{Ndf::kAlpha}),
          Fresnel::kParams);

  // D G F / (denominator) without the weight.
  template <class T>
  static T Shape(const T* p, const Geometry& g) {
    const T& alpha = p[3];
    constexpr double kScale = Form == MicrofacetForm::kWalter ? 4.0 : kPi;
    return Ndf::D(alpha, g) * Masking::template G<Ndf>(alpha, g) * Fresnel::F(p + 4, g) /
           (kScale * g.cos_i * g.cos_o);
  }

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T s = Shape(p, g);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * s;
  }
};

}  // namespace brdfit
