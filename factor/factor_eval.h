// CPU evaluation of a factored BRDF from its two textures: the reference for metrics and for
// the GLSL preview (same maps, same bilinear texel-centre lookups as GL_LINEAR; factor_param.h).
#pragma once

#include <array>
#include <vector>

#include "factor/factor_param.h"
#include "core/rgb_image.h"
#include "models/geometry.h"

namespace brdfit {

// One product of the factored form: two textures in the maps of the parameterization.
struct FactorTerm {
  RgbImage p, q;
};

// f(wi, wo) = d + sum_k term_k(wi, wo), d = kd / pi the diffuse value (1/sr, RGB, >= 0; zero
// for the pure homomorphic form), term_k = p_k(wi) q_k(wh) p_k(wo) (mccool) or
// p_k(wh) q_k(theta_d, phi_d) (halfdiff). Rank 1 without diffuse is McCool et al. 2001's form;
// a sum of products is their section 3 / Kautz & McCool 1999's multi-term separable expansion.
class FactoredBrdf {
 public:
  FactoredBrdf() = default;
  // Rank 1, no diffuse term. Throws InputError if a texture is smaller than 2 x 2, not square
  // where its map needs it, or holds a negative or non-finite value.
  FactoredBrdf(FactorParam param, RgbImage p, RgbImage q);
  // Any rank >= 1 (every term checked as above); `diffuse` must be finite and >= 0.
  FactoredBrdf(FactorParam param, std::array<double, 3> diffuse, std::vector<FactorTerm> terms);

  FactorParam param() const { return param_; }
  const FactorParamSpec& spec() const { return GetFactorParamSpec(param_); }
  int rank() const { return static_cast<int>(terms_.size()); }
  const std::vector<FactorTerm>& terms() const { return terms_; }
  const std::array<double, 3>& diffuse() const { return diffuse_; }
  bool has_diffuse() const { return diffuse_[0] > 0 || diffuse_[1] > 0 || diffuse_[2] > 0; }
  // The first term's textures (the only ones at rank 1).
  const RgbImage& p() const { return terms_.at(0).p; }
  const RgbImage& q() const { return terms_.at(0).q; }

  // f_r in 1/sr, without the cosine, linear RGB. Zero when wi or wo is at or below the
  // horizon (the factors are defined on the upper hemisphere only).
  std::array<double, 3> Eval(const Vec3& wi, const Vec3& wo) const;
  // At half/difference angles (any phi_h gives the same value: the factors are isotropic).
  std::array<double, 3> Eval(const HalfDiffAngles& a) const;

 private:
  FactorParam param_ = FactorParam::kMcCool;
  std::array<double, 3> diffuse_{0, 0, 0};
  std::vector<FactorTerm> terms_;
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
