// The ES module of `brdfit export --format threejs`: a three.js ShaderMaterial that evaluates the
// fitted model with brdfit's own GLSL (the preview's twins of models/, so the export is the
// model itself, in float32), lit by the scene's three.js directional lights (docs/exports.md,
// "three.js ShaderMaterial").
#pragma once

#include <string>
#include <vector>

#include "export/provenance.h"

namespace brdfit::exports {

struct ThreejsAnalytic {
  std::string model;            // registry name
  std::vector<double> params;   // in the model's parameter order (uParams)
  std::string brdf_glsl;        // preview::AnalyticBrdfSource(model): EvalBrdf and what it needs
};

// `import createMaterial from './m.mjs'; mesh.material = createMaterial();` (three.js r152+ on
// WebGL 2, which compiles it as GLSL ES 3.00).
std::string ThreejsModule(const ThreejsAnalytic& a, const Provenance& p);

}  // namespace brdfit::exports
