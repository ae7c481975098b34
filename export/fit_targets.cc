#include "export/fit_targets.h"

#include "core/error.h"
#include "export/lobe_material.h"

namespace brdfit::exports {

namespace {

const std::vector<FitTarget>& Targets() {
  static const std::vector<FitTarget> t = {
      {"gltf",
       Format::kGlb,
       {"lambert+ggx-hc"},
       "glTF 2.0 metallic-roughness + KHR_materials_specular, height-correlated masking as "
       "three.js and the Sample Viewer evaluate it: exact for a grey ks"},
      {"threejs",
       Format::kThreejs,
       {},
       "three.js ShaderMaterial running brdfit's GLSL: every model exact"},
      {"blender",
       Format::kBlender,
       {"lambert+ggx"},
       "Blender 3.4 Cycles Diffuse + Glossy (GGX, separable masking) node tree: exact; its "
       "Principled BSDF material is approximate"},
      {"mitsuba",
       Format::kMitsuba,
       {"lambert+ggx"},
       "Mitsuba 3 blendbsdf of diffuse and roughconductor (separable masking): exact"},
      {"pbrt",
       Format::kPbrt,
       {"lambert+ggx-hc"},
       "pbrt-v4 mix of diffuse and conductor (height-correlated masking): exact for a grey ks "
       "(to 1e-3)"},
  };
  return t;
}

}  // namespace

std::string FitTargetNames() {
  std::string s;
  for (const FitTarget& t : Targets()) s += (s.empty() ? "" : ", ") + std::string(t.name);
  return s;
}

const FitTarget& FitTargetOf(const std::string& name) {
  for (const FitTarget& t : Targets()) {
    if (name == t.name) return t;
  }
  throw InputError("--target '" + name + "': expected one of " + FitTargetNames());
}

Fidelity ExportFidelity(const FitResult& fit, const FitTarget& target) {
  if (target.format == Format::kThreejs) return {};
  if (!IsExportable(fit.model)) {
    return {{"the " + std::string(target.name) + " export takes only " +
             std::string(ExportableModels()) + ", not " + fit.model}};
  }
  const LobeMaterial m = FromFit(fit);
  switch (target.format) {
    case Format::kGltf:
    case Format::kGlb:
      return ToGltf(m).fidelity;
    case Format::kMitsuba:
      return ToMitsuba(m).fidelity;
    case Format::kPbrt:
      return ToPbrt(m).fidelity;
    case Format::kBlender:
      return ToBlender(m).fidelity;
    case Format::kThreejs:
      break;
  }
  return {};
}

}  // namespace brdfit::exports
