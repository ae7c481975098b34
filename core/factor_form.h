// A factored BRDF's form as stored and drawn (docs/factorization.md, "The stored form and its
// cost"): f = d + sum_k term_k, d the diffuse value (RGB, 1/sr) and K products of two textures
// each (McCool, Ang, Ahmad 2001; Kautz & McCool 1999 for sums of products):
//   mccool:   term_k = p_k(wi) q_k(wh) p_k(wo)
//   halfdiff: term_k = p_k(wh) q_k(theta_d, phi_d)
// Its label ("mccool+d r2") and what it costs a shader. Plain data: the report reads it from a
// sidecar, the preview from its textures, the factor layer from a FactoredBrdf.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace brdfit {

// The largest texture side of a halfdiff factorization: its q texture is solved texel by texel
// (factor/factor_system.h). Checked with the options, before any solve (cli/cmd_factor.cc,
// preview/scene.cc); mccool goes to kMaxFactorResolution.
inline constexpr int kMaxHalfDiffResolution = 256;
inline constexpr int kMaxFactorResolution = 1024;

struct FactorTextureSize {
  int width = 0, height = 0;
};

struct FactorForm {
  std::string parameterization;  // "mccool" or "halfdiff"
  bool diffuse = false;          // a diffuse value d is stored (and added by the shader)
  struct Term {
    FactorTextureSize p, q;
  };
  std::vector<Term> terms;  // rank K = terms.size()
  int rank() const { return static_cast<int>(terms.size()); }
};

// "mccool", "mccool+d" (with a diffuse value), "mccool r2" (rank 2), "halfdiff+d r3". Rank 1
// without diffuse is the bare parameterization, the name factorizations had before either.
std::string FactorFormLabel(const FactorForm& form);

// What drawing a factorization costs.
//   texture_bytes:        every texture as stored, float32 RGB (12 bytes a texel), plus 12
//                         bytes for the diffuse RGB when there is one. The preview uploads
//                         RGBA32F (4/3 of the texels' share).
//   fetches_per_light:    mccool 2 per term (p_k(wi), q_k(wh)); halfdiff 2 per term.
//   fetches_per_fragment: mccool 1 per term (p_k(wo), shared by the lights); halfdiff 0.
struct FactorCost {
  std::size_t texture_bytes = 0;
  int fetches_per_light = 0;
  int fetches_per_fragment = 0;
};
// Throws std::invalid_argument for an unknown parameterization or a negative texture size.
FactorCost ComputeFactorCost(const FactorForm& form);

// "768 B", "96.0 KiB", "1.50 MiB".
std::string BytesText(std::size_t bytes);
// "96.0 KiB, 4 fetches per light + 2 per fragment" (the fragment part only when there is one).
std::string FactorCostText(const FactorCost& cost);

}  // namespace brdfit
