#include "export/lobe_material.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "core/error.h"

namespace brdfit::exports {

namespace {

double Param(const FitResult& fit, std::string_view name) {
  for (std::size_t i = 0; i < fit.param_names.size(); ++i) {
    if (fit.param_names[i] == name) return fit.params[i];
  }
  throw InputError("fit of " + fit.model + " has no parameter " + std::string(name));
}

Rgb Triple(const FitResult& fit, const std::string& prefix) {
  return {Param(fit, prefix + "_r"), Param(fit, prefix + "_g"), Param(fit, prefix + "_b")};
}

double MaxOf(const Rgb& v) {
  return std::max({v[0], v[1], v[2]});
}

}  // namespace

const char* ExportableModels() {
  return "lambert+ggx-hc, lambert+ggx, lambert+ggx-f0, ue4, lambert+ggx+sheen, lambert+ggx+ggx, "
         "oren-nayar-fujii+ggx, burley-2012+ggx";
}

bool IsExportable(const std::string& model) {
  return model == "lambert+ggx-hc" || model == "lambert+ggx" || model == "lambert+ggx-f0" ||
         model == "ue4" || model == "lambert+ggx+sheen" || model == "lambert+ggx+ggx" ||
         model == "oren-nayar-fujii+ggx" || model == "burley-2012+ggx";
}

LobeMaterial FromFit(const FitResult& fit) {
  if (fit.Failed()) throw InputError("the fit of " + fit.model + " failed: nothing to export");
  if (!IsExportable(fit.model)) {
    throw InputError("model " + fit.model + " cannot be exported (exportable: " +
                     ExportableModels() + "; fit one of those, e.g. --model lambert+ggx-hc)");
  }
  LobeMaterial m;
  m.model = fit.model;
  if (fit.model == "ue4") {
    m.ue4 = true;
    m.base = Triple(fit, "base");
    m.metallic = Param(fit, "metallic");
    m.alpha = Param(fit, "alpha");
    m.masking = Masking::kSchlickSmithUe4;
    m.fresnel = LobeFresnel::kSchlick;
    for (int c = 0; c < 3; ++c) {
      m.kd[c] = (1 - m.metallic) * m.base[c];
      m.spec[c] = 0.04 * (1 - m.metallic) + m.base[c] * m.metallic;
    }
    return m;
  }
  if (fit.model == "oren-nayar-fujii+ggx") {
    m.body = Body::kOrenNayarFujii;
    m.kd = Triple(fit, "oren-nayar-fujii.kd");
    m.body_roughness = Param(fit, "oren-nayar-fujii.sigma");
  } else if (fit.model == "burley-2012+ggx") {
    m.body = Body::kBurley2012;
    m.kd = Triple(fit, "burley-2012.kd");
    m.body_roughness = std::sqrt(std::max(Param(fit, "burley-2012.alpha"), 0.0));
  } else {
    m.kd = Triple(fit, "lambert.kd");
  }
  if (fit.model == "lambert+ggx-f0") {
    m.spec = Triple(fit, "ggx-f0.f0");
    m.alpha = Param(fit, "ggx-f0.alpha");
    m.masking = Masking::kHeightCorrelated;
    m.fresnel = LobeFresnel::kSchlick;
  } else if (fit.model == "lambert+ggx+ggx") {
    // models/sum.h qualifies repeated lobes by their index: ggx1, ggx2.
    Rgb ks[2] = {Triple(fit, "ggx1.ks"), Triple(fit, "ggx2.ks")};
    double alpha[2] = {Param(fit, "ggx1.alpha"), Param(fit, "ggx2.alpha")};
    const int first = MaxOf(ks[1]) > MaxOf(ks[0]) ? 1 : 0;
    m.spec = ks[first];
    m.alpha = alpha[first];
    m.second = LobeMaterial::SecondLobe{ks[1 - first], alpha[1 - first]};
    m.masking = Masking::kSeparable;
  } else {
    const std::string lobe = fit.model == "lambert+ggx-hc" ? "ggx-hc" : "ggx";
    m.spec = Triple(fit, lobe + ".ks");
    m.alpha = Param(fit, lobe + ".alpha");
    m.masking = lobe == "ggx" ? Masking::kSeparable : Masking::kHeightCorrelated;
  }
  if (fit.model == "lambert+ggx+sheen") {
    m.sheen_color = Triple(fit, "sheen.sheen");
    m.sheen_alpha = Param(fit, "sheen.alpha");
    m.sheen = MaxOf(m.sheen_color) > 0;
  }
  return m;
}

}  // namespace brdfit::exports
