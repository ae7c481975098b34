#include "factor/factor_eval.h"

#include <fmt/core.h>
#include <cmath>
#include <string>
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
    : FactoredBrdf(param, {0, 0, 0}, {FactorTerm{std::move(p), std::move(q)}}) {}

FactoredBrdf::FactoredBrdf(FactorParam param, std::array<double, 3> diffuse,
                           std::vector<FactorTerm> terms)
    : param_(param), diffuse_(diffuse), terms_(std::move(terms)) {
  if (terms_.empty()) throw InputError("a factorization needs at least one term");
  for (std::size_t k = 0; k < terms_.size(); ++k) {
    const std::string suffix = k == 0 ? "" : std::to_string(k + 1);
    CheckTexture(terms_[k].p, spec().p, ("p" + suffix).c_str());
    CheckTexture(terms_[k].q, spec().q, ("q" + suffix).c_str());
  }
  for (double d : diffuse_) {
    if (!std::isfinite(d) || d < 0) {
      throw InputError(fmt::format("diffuse value {} is negative or not finite", d));
    }
  }
}

std::array<double, 3> FactoredBrdf::Eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return {0, 0, 0};
  const FactorParamSpec& s = spec();
  const Vec3 h = Normalize(wi + wo);
  std::array<double, 3> out = diffuse_;
  const HalfDiffAngles a = param_ == FactorParam::kHalfDiff ? ToHalfDiff(wi, wo) : HalfDiffAngles{};
  for (const FactorTerm& t : terms_) {
    if (param_ == FactorParam::kMcCool) {
      // McCool et al. 2001: f = p(wi) q(wh) p(wo).
      const auto pi = SampleTexture(t.p, Lookup(s.p, t.p, wi));
      const auto po = SampleTexture(t.p, Lookup(s.p, t.p, wo));
      const auto qh = SampleTexture(t.q, Lookup(s.q, t.q, h));
      for (int c = 0; c < 3; ++c) out[c] += pi[c] * qh[c] * po[c];
    } else {
      // Kautz & McCool 1999: f = p(wh) q(theta_d, phi_d).
      const auto ph = SampleTexture(t.p, Lookup(s.p, t.p, h));
      const auto qd =
          SampleTexture(t.q, ThetaDPhiDLookup(a.theta_d, a.phi_d, t.q.width, t.q.height));
      for (int c = 0; c < 3; ++c) out[c] += ph[c] * qd[c];
    }
  }
  return out;
}

std::array<double, 3> FactoredBrdf::Eval(const HalfDiffAngles& a) const {
  Vec3 wi, wo;
  FromHalfDiff(a, 0.0, &wi, &wo);
  return Eval(wi, wo);
}

}  // namespace brdfit
