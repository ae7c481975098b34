#include "pipeline/factor_textures.h"

#include <fmt/core.h>

#include <utility>

#include "core/error.h"
#include "factor/factor.h"

namespace brdfit::pipeline {
namespace {

static_assert(preview::kMaxFactorTextureTerms == kMaxFactorRank,
              "the preview draws every rank the solver makes");

Image ToImage(const RgbImage& src) {
  Image img(src.width, src.height);
  for (std::size_t i = 0; i < static_cast<std::size_t>(src.width) * src.height; ++i) {
    for (int c = 0; c < 3; ++c) img.rgba[4 * i + c] = src.rgb[3 * i + c];
    img.rgba[4 * i + 3] = 1.0f;
  }
  return img;
}

}  // namespace

std::shared_ptr<const preview::FactorTextures> ToFactorTextures(FactoredBrdf brdf) {
  if (brdf.rank() > preview::kMaxFactorTextureTerms) {
    throw InputError(fmt::format("a factorization of rank {}: the preview draws at most {} terms",
                                 brdf.rank(), preview::kMaxFactorTextureTerms));
  }
  auto f = std::make_shared<preview::FactorTextures>();
  f->parameterization = ToString(brdf.param());
  const auto& d = brdf.diffuse();
  f->diffuse = {d[0], d[1], d[2]};
  for (const FactorTerm& t : brdf.terms()) f->terms.push_back({ToImage(t.p), ToImage(t.q)});
  auto shared = std::make_shared<const FactoredBrdf>(std::move(brdf));
  f->eval = [shared](const Vec3& wi, const Vec3& wo) { return shared->Eval(wi, wo); };
  return f;
}

}  // namespace brdfit::pipeline
