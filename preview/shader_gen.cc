#include "preview/shader_gen.h"

#include <set>
#include <stdexcept>

#include "core/error.h"
#include "preview/glsl_models.h"
#include "preview/glsl_params.h"
#include "preview/glsl_sources.h"
#include "preview/material.h"

namespace brdfit::preview {
namespace {

constexpr const char* kVersion = "#version 330 core\n";

std::string Define(const std::string& name, int value) {
  return "#define " + name + " " + std::to_string(value) + "\n";
}

// Appends an embedded file after the files it names in "// brdfit-requires: <path>" lines,
// each file once.
void Include(const std::string& file, std::set<std::string>* included, std::string* src) {
  if (!included->insert(file).second) return;
  const std::string_view text = GlslSource(file);
  const std::string_view tag = "// brdfit-requires: ";
  for (std::size_t pos = text.find(tag); pos != std::string_view::npos;
       pos = text.find(tag, pos + 1)) {
    const std::size_t start = pos + tag.size();
    const std::size_t end = text.find('\n', start);
    std::string dep(text.substr(start, end - start));
    while (!dep.empty() && (dep.back() == ' ' || dep.back() == '\r')) dep.pop_back();
    Include(dep, included, src);
  }
  *src += "// ---- " + file + "\n" + std::string(text) + "\n";
}

// EvalBrdf for an analytic model: each lobe's generated parameter block (preview/glsl_params.h),
// its GLSL (the twin file, or the generated microfacet entry point) and a call on its slice of
// uParams.
std::string AnalyticEval(const std::string& model) {
  const auto lobes = GlslLobes(model);
  std::string src;
  std::set<std::string> included, declared;
  for (const auto& lobe : lobes) {
    if (!declared.insert(lobe.name).second) continue;
    src += "// ---- generated: " + lobe.params_struct + " from the kParams of " + lobe.name + "\n" +
           lobe.param_block;
    Include(lobe.file, &included, &src);
    if (!lobe.entry_point.empty()) {
      src += "// ---- generated: " + lobe.function + " from the term types of " + lobe.name + "\n" +
             lobe.entry_point;
    }
  }
  const std::size_t n = lobes.back().offset + lobes.back().count;
  src += "uniform float uParams[" + std::to_string(n) + "];\n";
  src += "vec3 EvalBrdf(const in BrdfGeometry g) {\n  vec3 f = vec3(0.0);\n";
  for (const auto& lobe : lobes) {
    src += "  f += " + lobe.function + "(" +
           GlslParamConstructor(lobe.name, "uParams", lobe.offset, lobe.count) + ", g);\n";
  }
  src += "  return f;\n}\n";
  return src;
}

}  // namespace

std::string ShaderVariant::Key() const {
  std::string k = std::string(ToString(material));
  if (material == MaterialKind::kAnalytic) k += ":" + model;
  if (material == MaterialKind::kMeasured) k += std::string(":") + ToString(theta_h_mapping);
  if (material == MaterialKind::kFactored)
    k += ":" + factor_param + " r" + std::to_string(factor_rank);
  k += " dir=" + std::to_string(num_directional) + " point=" + std::to_string(num_point) +
       " spot=" + std::to_string(num_spot) + (punctual_pi ? " pi" : "") + (mesh ? " mesh" : "");
  return k;
}

std::string ShadeVertexSource(const ShaderVariant& v) {
  return kVersion +
         std::string(GlslSource(v.mesh ? "preview/glsl/object.vert" : "preview/glsl/sphere.vert"));
}

std::string FullscreenVertexSource() {
  return kVersion + std::string(GlslSource("preview/glsl/fullscreen.vert"));
}

std::string ShadeFragmentSource(const ShaderVariant& v) {
  std::string src = kVersion;
  src += Define("NUM_DIR_LIGHTS", v.num_directional) + Define("NUM_POINT_LIGHTS", v.num_point) +
         Define("NUM_SPOT_LIGHTS", v.num_spot) + Define("PUNCTUAL_PI", v.punctual_pi ? 1 : 0) +
         Define("OBJECT_SPHERE", v.mesh ? 0 : 1);
  src += "// ---- preview/glsl/common.glsl\n" + std::string(GlslSource("preview/glsl/common.glsl"));
  switch (v.material) {
    case MaterialKind::kAnalytic:
      src += AnalyticEval(v.model);
      break;
    case MaterialKind::kMeasured: {
      src += Define("TABLE_SQRT_THETA_H", v.theta_h_mapping == ThetaHMapping::kSqrt ? 1 : 0);
      std::set<std::string> included;
      Include("preview/glsl/measured.glsl", &included, &src);
      break;
    }
    case MaterialKind::kFactored: {
      if (v.factor_rank < 1 || v.factor_rank > kMaxFactorTextureTerms) {
        throw std::logic_error("factored shader of rank " + std::to_string(v.factor_rank) +
                               ": outside [1, " + std::to_string(kMaxFactorTextureTerms) + "]");
      }
      src += Define("FACTOR_MCCOOL", v.factor_param == "mccool" ? 1 : 0) +
             Define("FACTOR_RANK", v.factor_rank);
      std::set<std::string> included;
      Include("preview/glsl/factored.glsl", &included, &src);
      break;
    }
  }
  src += "// ---- preview/glsl/shade.frag\n" + std::string(GlslSource("preview/glsl/shade.frag"));
  return src;
}

std::string AnalyticBrdfSource(const std::string& model) {
  return "// ---- preview/glsl/common.glsl\n" +
         std::string(GlslSource("preview/glsl/common.glsl")) + AnalyticEval(model);
}

std::string FactoredBrdfSource(const std::string& parameterization, int rank) {
  if (parameterization != "mccool" && parameterization != "halfdiff") {
    throw InputError("factorization parameterization '" + parameterization +
                     "': expected mccool or halfdiff");
  }
  if (rank < 1 || rank > kMaxFactorTextureTerms) {
    throw InputError("factorization of rank " + std::to_string(rank) + ": outside [1, " +
                     std::to_string(kMaxFactorTextureTerms) + "]");
  }
  std::string src = Define("FACTOR_MCCOOL", parameterization == "mccool" ? 1 : 0) +
                    Define("FACTOR_RANK", rank) + "// ---- preview/glsl/common.glsl\n" +
                    std::string(GlslSource("preview/glsl/common.glsl"));
  std::set<std::string> included;
  Include("preview/glsl/factored.glsl", &included, &src);
  return src;
}

std::string ToneMapFragmentSource(ToneMap t, Encoding e) {
  return kVersion + Define("TONE_MAPPING", static_cast<int>(t)) +
         Define("ENCODING", static_cast<int>(e)) +
         std::string(GlslSource("preview/glsl/tonemap.frag"));
}

}  // namespace brdfit::preview
