// CPU evaluation of a factored BRDF from its two textures: the reference for metrics and for
// the GLSL preview (same maps, same bilinear texel-centre lookups as GL_LINEAR; factor_param.h).
#pragma once

#include <array>

#include "factor/factor_param.h"
#include "core/rgb_image.h"
#include "models/geometry.h"

namespace brdfit {

class FactoredBrdf {
 public:
  FactoredBrdf() = default;
  // Throws InputError if a texture is smaller than 2 x 2, not square where its map needs it,
  // or holds a negative or non-finite value.
  FactoredBrdf(FactorParam param, RgbImage p, RgbImage q);

  FactorParam param() const { return param_; }
  const FactorParamSpec& spec() const { return GetFactorParamSpec(param_); }
  const RgbImage& p() const { return p_; }
  const RgbImage& q() const { return q_; }

  // f_r in 1/sr, without the cosine, linear RGB. Zero when wi or wo is at or below the
  // horizon (the factors are defined on the upper hemisphere only).
  std::array<double, 3> Eval(const Vec3& wi, const Vec3& wo) const;
  // At half/difference angles (any phi_h gives the same value: the factors are isotropic).
  std::array<double, 3> Eval(const HalfDiffAngles& a) const;

 private:
  FactorParam param_ = FactorParam::kMcCool;
  RgbImage p_, q_;
};

// Bilinear lookup of an RGB texture.
inline std::array<double, 3> SampleTexture(const RgbImage& img, const Bilinear& b) {
  std::array<double, 3> v{0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const float* t = &img.rgb[3 * static_cast<std::size_t>(b.index[k])];
    for (int c = 0; c < 3; ++c) v[c] += b.weight[k] * t[c];
  }
  return v;
}

}  // namespace brdfit
