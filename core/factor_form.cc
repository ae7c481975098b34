#include "core/factor_form.h"

#include <fmt/core.h>

#include <stdexcept>

namespace brdfit {
namespace {

constexpr std::size_t kBytesPerTexel = 3 * sizeof(float);  // float32 RGB
constexpr std::size_t kDiffuseBytes = 3 * sizeof(float);   // one RGB uniform

std::size_t TextureBytes(const FactorTextureSize& t) {
  if (t.width < 0 || t.height < 0) {
    throw std::invalid_argument(fmt::format("texture size {} x {}", t.width, t.height));
  }
  return kBytesPerTexel * static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
}

}  // namespace

std::string FactorFormLabel(const FactorForm& form) {
  std::string s = form.parameterization;
  if (form.diffuse) s += "+d";
  if (form.rank() != 1) s += fmt::format(" r{}", form.rank());
  return s;
}

FactorCost ComputeFactorCost(const FactorForm& form) {
  const bool mccool = form.parameterization == "mccool";
  if (!mccool && form.parameterization != "halfdiff") {
    throw std::invalid_argument("unknown parameterization '" + form.parameterization + "'");
  }
  FactorCost c;
  for (const FactorForm::Term& t : form.terms)
    c.texture_bytes += TextureBytes(t.p) + TextureBytes(t.q);
  if (form.diffuse) c.texture_bytes += kDiffuseBytes;
  c.fetches_per_light = 2 * form.rank();
  c.fetches_per_fragment = mccool ? form.rank() : 0;
  return c;
}

std::string BytesText(std::size_t bytes) {
  if (bytes < 1024) return fmt::format("{} B", bytes);
  if (bytes < 1024 * 1024) return fmt::format("{:.1f} KiB", bytes / 1024.0);
  return fmt::format("{:.2f} MiB", bytes / (1024.0 * 1024.0));
}

std::string FactorCostText(const FactorCost& cost) {
  std::string s = fmt::format("{}, {} fetches per light", BytesText(cost.texture_bytes),
                              cost.fetches_per_light);
  if (cost.fetches_per_fragment > 0)
    s += fmt::format(" + {} per fragment", cost.fetches_per_fragment);
  return s;
}

}  // namespace brdfit
