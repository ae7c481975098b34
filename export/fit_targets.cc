#include "export/fit_targets.h"

#include "core/error.h"

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
       {"lambert+ggx", "lambert+ggx+ggx", "oren-nayar-fujii+ggx", "burley-2012+ggx"},
       "Blender 3.4 Cycles node tree of a body (Diffuse BSDF: Lambert or Fujii's Oren-Nayar; "
       "Principled BSDF with Specular 0: Burley 2012) and one Glossy BSDF (GGX, separable "
       "masking) per lobe: exact; its Principled BSDF material is approximate"},
      {"mitsuba",
       Format::kMitsuba,
       {"lambert+ggx", "lambert+ggx+ggx", "burley-2012+ggx"},
       "Mitsuba 3 blendbsdf of a body (diffuse: Lambert; principled with specular 0: Burley "
       "2012) and roughconductor (separable masking), a nested blendbsdf for two lobes: exact"},
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

const FitTarget* FitTargetForFormat(Format format) {
  if (format == Format::kThreejs) return nullptr;
  const Format f = format == Format::kGltf ? Format::kGlb : format;
  for (const FitTarget& t : Targets()) {
    if (t.format == f) return &t;
  }
  return nullptr;
}

Fidelity ExportFidelity(const FitResult& fit, const FitTarget& target) {
  return FidelityOf(fit, target.format);
}

}  // namespace brdfit::exports
