// The ES module of `brdfit export --format threejs`: a three.js ShaderMaterial that evaluates the
// fitted model with brdfit's own GLSL (the preview's twins of models/, so the export is the
// model itself, in float32), lit by the scene's three.js directional lights (docs/exports.md,
// "three.js ShaderMaterial").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/rgb_image.h"
#include "export/provenance.h"

namespace brdfit::exports {

struct ThreejsAnalytic {
  std::string model;           // registry name
  std::vector<double> params;  // in the model's parameter order (uParams)
  std::string brdf_glsl;       // preview::AnalyticBrdfSource(model): EvalBrdf and what it needs
};

// `import createMaterial from './m.mjs'; mesh.material = createMaterial();` (three.js r152+ on
// WebGL 2, which compiles it as GLSL ES 3.00).
std::string ThreejsModule(const ThreejsAnalytic& a, const Provenance& p);

// A factorization (`brdfit factor`'s sidecar and textures): each texture becomes a half-float
// RGBA THREE.DataTexture (linear filtering, clamp to edge; halfdiff's q repeats in its rows, as
// the preview samples them), with the preview's lookup code (factored.glsl).
struct ThreejsFactored {
  std::string parameterization;  // "mccool" | "halfdiff"
  std::array<double, 3> diffuse{};
  std::vector<RgbImage> p, q;  // one per term
  std::string brdf_glsl;       // preview::FactoredBrdfSource(parameterization, rank)
};
// `fidelity` receives what half floats could not hold (values above 65504 are clipped).
std::string ThreejsFactoredModule(const ThreejsFactored& f, const Provenance& p,
                                  Fidelity* fidelity);

// IEEE 754 binary16 of f, rounded to nearest even; |f| beyond the largest half (65504) and
// non-finite values give +-65504 and set *clipped.
std::uint16_t ToHalf(float f, bool* clipped);

}  // namespace brdfit::exports
