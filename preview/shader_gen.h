// Generates the shading program for one (object, material, light set): only the model twins
// and light types the scene uses are compiled in, with exact light counts as #defines
// (Three.js style: NUM_DIR_LIGHTS-like counts instead of run-time branches).
#pragma once

#include <string>

#include "core/table.h"
#include "preview/scene.h"

namespace brdfit::preview {

struct ShaderVariant {
  MaterialKind material = MaterialKind::kAnalytic;
  std::string model;                                     // kAnalytic: registry name
  ThetaHMapping theta_h_mapping = ThetaHMapping::kSqrt;  // kMeasured
  std::string factor_param = "mccool";                   // kFactored
  int factor_rank = 1;  // kFactored: products in the sum, 1..kMaxFactorTextureTerms (FACTOR_RANK)
  int num_directional = 0, num_point = 0, num_spot = 0;
  bool punctual_pi = true;
  bool mesh = false;  // a triangle mesh (object.vert), else an analytic sphere (sphere.vert)

  std::string Key() const;  // cache key, also printed by --explain
};

// Sphere: a screen rectangle (glsl/sphere.vert); mesh: a Three.js-style vertex stage (object.vert).
std::string ShadeVertexSource(const ShaderVariant& v);
std::string ShadeFragmentSource(const ShaderVariant& v);
std::string ToneMapFragmentSource(ToneMap t, Encoding e);

// The preview's BRDF code for an analytic model, without #version or #defines: common.glsl
// (constants, light structs, BrdfGeometry, MakeBrdfGeometry, BuildFrame), the lobes' GLSL twins
// and `uniform float uParams[N]; vec3 EvalBrdf(const in BrdfGeometry g)` -- for shaders outside
// the preview (the three.js ShaderMaterial export, docs/exports.md).
std::string AnalyticBrdfSource(const std::string& model);
// The same for a factorization ("mccool" | "halfdiff", rank 1..kMaxFactorTextureTerms): the
// FACTOR_* #defines, common.glsl and factored.glsl (uniforms uFactorDiffuse, uFactorP, uFactorQ,
// uFactorP2, ...). Throws InputError for another parameterization or rank.
std::string FactoredBrdfSource(const std::string& parameterization, int rank);
std::string FullscreenVertexSource();

}  // namespace brdfit::preview
