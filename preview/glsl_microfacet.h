// GLSL entry points of microfacet lobes, generated from their C++ type
// Microfacet<Ndf, Masking, Fresnel, Form> (models/microfacet/microfacet.h): the lobe calls the
// GLSL twin of each of its terms (models/glsl/ndf.glsl, masking.glsl, fresnel.glsl), so a term
// is written once in GLSL and the composition cannot differ from the C++ one. A catalog lobe
// that uses a term without a Glsl* specialization below does not compile.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "models/microfacet/microfacet.h"

namespace brdfit::preview {

// D(alpha, cos_h, sin2_h) and Lambda(alpha, v) of an NDF policy (models/glsl/ndf.glsl).
template <class Ndf>
struct GlslNdf;
template <>
struct GlslNdf<GgxNdf> {
  static constexpr std::string_view kD = "brdfit_DGgx";
  static constexpr std::string_view kLambda = "brdfit_LambdaGgx";
};
template <>
struct GlslNdf<BeckmannNdf> {
  static constexpr std::string_view kD = "brdfit_DBeckmann";
  static constexpr std::string_view kLambda = "brdfit_LambdaBeckmann";
};

// G(wi, wo) of a masking policy (models/glsl/masking.glsl) as a GLSL expression of the NDF's
// Lambda function, alpha and the geometry g.
template <class Masking>
struct GlslMasking;
inline std::string GlslSmithArgs(std::string_view lambda, const std::string& alpha) {
  const std::string l(lambda);
  return l + "(" + alpha + ", g.wi), " + l + "(" + alpha + ", g.wo)";
}
template <>
struct GlslMasking<SmithSeparable> {
  static std::string G(std::string_view lambda, const std::string& alpha) {
    return "brdfit_GSmithSeparable(" + GlslSmithArgs(lambda, alpha) + ")";
  }
};
template <>
struct GlslMasking<SmithHeightCorrelated> {
  static std::string G(std::string_view lambda, const std::string& alpha) {
    return "brdfit_GSmithHeightCorrelated(" + GlslSmithArgs(lambda, alpha) + ")";
  }
};
template <>
struct GlslMasking<SchlickSmith<SchlickK::kUe4>> {
  static std::string G(std::string_view /*lambda*/, const std::string& alpha) {
    return "brdfit_GSchlickSmith(brdfit_SchlickKUe4(" + alpha + "), g)";
  }
};
template <>
struct GlslMasking<VGroove> {
  static std::string G(std::string_view /*lambda*/, const std::string& /*alpha*/) {
    return "brdfit_GVGroove(g)";
  }
};

// F(cos_d) of a Fresnel policy (models/glsl/fresnel.glsl) from its parameters' GLSL names.
template <class Fresnel>
struct GlslFresnel;
template <>
struct GlslFresnel<NoFresnel> {
  static std::string F(const std::vector<std::string>& /*params*/) { return "1.0"; }
};
template <>
struct GlslFresnel<SchlickFresnel> {
  static std::string F(const std::vector<std::string>& params) {
    return "brdfit_FSchlick(" + params.at(0) + ", g.cos_d)";
  }
};

template <class M>
concept MicrofacetLobe = requires {
  typename M::NdfType;
  typename M::MaskingType;
  typename M::FresnelType;
};

// vec3 <function>(const in <params_struct> p, const in BrdfGeometry g): the weight times
// brdfit_MicrofacetShape(D, G, F, scale, g) (models/glsl/microfacet.glsl).
template <MicrofacetLobe M>
std::string GlslMicrofacetEntryPoint(const std::string& function,
                                     const std::string& params_struct) {
  using Ndf = typename M::NdfType;
  using Fresnel = typename M::FresnelType;
  static_assert(kNumParams<M> == 4 + std::tuple_size_v<decltype(Fresnel::kParams)>,
                "Microfacet parameters: ks_r, ks_g, ks_b, alpha, then the Fresnel parameters");
  auto field = [](std::size_t i) { return "p." + std::string(M::kParams[i].name); };
  std::vector<std::string> fresnel;
  for (std::size_t i = 4; i < kNumParams<M>; ++i) fresnel.push_back(field(i));
  const std::string alpha = field(3);
  const std::string scale = M::kForm == MicrofacetForm::kWalter ? "4.0" : "PI";
  return "vec3 " + function + "(const in " + params_struct + " p, const in BrdfGeometry g) {\n" +
         "  float D = " + std::string(GlslNdf<Ndf>::kD) + "(" + alpha + ", g.cos_h, g.sin2_h);\n" +
         "  float G = " + GlslMasking<typename M::MaskingType>::G(GlslNdf<Ndf>::kLambda, alpha) +
         ";\n" + "  float F = " + GlslFresnel<Fresnel>::F(fresnel) + ";\n" + "  return vec3(" +
         field(0) + ", " + field(1) + ", " + field(2) + ") * brdfit_MicrofacetShape(D, G, F, " +
         scale + ", g);\n}\n";
}

}  // namespace brdfit::preview
