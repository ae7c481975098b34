#include "factor/factor_eval.h"

#include <fmt/core.h>
#include <cmath>
#include <utility>

#include "core/error.h"

namespace brdfit {
namespace {

void CheckTexture(const RgbImage& img, const FactorTextureSpec& spec, const char* name) {
  if (img.width < 2 || img.height < 2 ||
      img.rgb.size() != 3 * static_cast<std::size_t>(img.width) * img.height) {
    throw InputError(
        fmt::format("texture {} is {} x {}: at least 2 x 2 needed", name, img.width, img.height));
  }
  if (spec.map != FactorMap::kThetaDPhiD && img.width != img.height) {
    throw InputError(fmt::format("texture {} ({} map) must be square, is {} x {}", name,
                                 ToString(spec.map), img.width, img.height));
  }
  for (float v : img.rgb) {
    if (!std::isfinite(v) || v < 0) {
      throw InputError(
          fmt::format("texture {} holds a negative or non-finite value ({})", name, v));
    }
  }
}

Bilinear Lookup(const FactorTextureSpec& spec, const RgbImage& img, const Vec3& w) {
  return DiskLookup(spec.map, w, img.width);  // disk maps are square
}

}  // namespace

FactoredBrdf::FactoredBrdf(FactorParam param, RgbImage p, RgbImage q)
    : param_(param), p_(std::move(p)), q_(std::move(q)) {
  CheckTexture(p_, spec().p, "p");
  CheckTexture(q_, spec().q, "q");
}

std::array<double, 3> FactoredBrdf::Eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return {0, 0, 0};
  const FactorParamSpec& s = spec();
  const Vec3 h = Normalize(wi + wo);
  std::array<double, 3> out;
  if (param_ == FactorParam::kMcCool) {
    // McCool et al. 2001: f = p(wi) q(wh) p(wo).
    const auto pi = SampleTexture(p_, Lookup(s.p, p_, wi));
    const auto po = SampleTexture(p_, Lookup(s.p, p_, wo));
    const auto qh = SampleTexture(q_, Lookup(s.q, q_, h));
    for (int c = 0; c < 3; ++c) out[c] = pi[c] * qh[c] * po[c];
  } else {
    // Kautz & McCool 1999: f = p(wh) q(theta_d, phi_d).
    const HalfDiffAngles a = ToHalfDiff(wi, wo);
    const auto ph = SampleTexture(p_, Lookup(s.p, p_, h));
    const auto qd = SampleTexture(q_, ThetaDPhiDLookup(a.theta_d, a.phi_d, q_.width, q_.height));
    for (int c = 0; c < 3; ++c) out[c] = ph[c] * qd[c];
  }
  return out;
}

std::array<double, 3> FactoredBrdf::Eval(const HalfDiffAngles& a) const {
  Vec3 wi, wo;
  FromHalfDiff(a, 0.0, &wi, &wo);
  return Eval(wi, wo);
}

}  // namespace brdfit
