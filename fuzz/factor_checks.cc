#include "fuzz/factor_checks.h"

#include <cmath>
#include <string>

#include "fuzz/harness_util.h"

namespace brdfit::fuzz {

FactorFiles ValidFactorFiles() {
  FactorFiles f;
  f.sidecar = {{"parameterization", "pq"}};
  f.diffuse = {0.01, 0.02, 0.03};
  f.terms.resize(2);
  f.terms[0].p.image = RgbImage::Filled(3, 2, 0.25f);
  f.terms[0].q.image = RgbImage::Filled(2, 4, 2.0f);
  f.terms[0].q.image.At(1, 3)[2] = -1.5f;
  f.terms[1].p.image = RgbImage::Filled(2, 2, 0.5f);
  f.terms[1].q.image = RgbImage::Filled(3, 3, 1.0f);
  return f;
}

void CheckFactorAgreement(const FactorFiles& f) {
  const std::string param = f.sidecar.at("parameterization").get<std::string>();
  CheckInvariant(!f.terms.empty() && f.terms.size() <= kFactorFileMaxRank, "rank");
  for (double d : f.diffuse) CheckInvariant(std::isfinite(d) && d >= 0, "diffuse value");
  for (std::size_t k = 0; k < f.terms.size(); ++k) {
    for (const bool q : {false, true}) {
      const FactorTextureFile& tex = q ? f.terms[k].q : f.terms[k].p;
      const std::string name = FactorTextureName(static_cast<int>(k), q);
      const auto& t = f.sidecar.at("textures").at(name);
      CheckInvariant(t.at("width") == tex.image.width && t.at("height") == tex.image.height,
                     "sidecar size disagrees with the image");
      CheckInvariant(tex.attributes.at(kExrAttrFactor) == name, "factor name");
      CheckInvariant(tex.attributes.at(kExrAttrParameterization) == param, "parameterization");
    }
  }
}

void CheckFactorRoundTrip(const FactorFiles& f, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const FactorPaths out = FactorFilePaths(dir, "g", static_cast<int>(f.terms.size()));
  WriteFactorFiles(out, f);
  const FactorFiles back = ReadFactorFiles(out.json);
  CheckFactorAgreement(back);
  CheckInvariant(back.terms.size() == f.terms.size(), "round trip rank");
  for (std::size_t k = 0; k < f.terms.size(); ++k) {
    CheckInvariant(
        back.terms[k].p.image == f.terms[k].p.image && back.terms[k].q.image == f.terms[k].q.image,
        "round trip images");
  }
  CheckInvariant(back.diffuse == f.diffuse, "round trip diffuse value");
  CheckInvariant(back.sidecar.at("parameterization") == f.sidecar.at("parameterization"),
                 "round trip parameterization");
}

}  // namespace brdfit::fuzz
