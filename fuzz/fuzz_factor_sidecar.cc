// Fuzz harness: the factorization sidecar (io/factor_io.h, ReadFactorFiles). The input is the
// JSON sidecar; the EXR textures it can name ("f.p.exr", "f.q.exr", "f.p2.exr", "f.q2.exr") are
// valid files written once per process by WriteFactorFiles (the EXR reader itself is fuzz_exr's
// job). After a successful read: the sidecar agrees with the images (sizes, parameterization,
// factor names, rank), the diffuse value is finite and >= 0, and writing the result and reading
// it back gives the same images, diffuse value and sidecar.
#include <cmath>
#include <cstring>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/factor_io.h"

namespace brdfit::fuzz {

namespace {

// Valid textures beside the fuzzed sidecar, parameterization "pq", rank 2: p is 3 x 2, q is
// 2 x 4, p2 is 2 x 2, q2 is 3 x 3 (f.factor.json, overwritten by each input, is the rank-2
// sidecar of them).
void WriteTexturesOnce() {
  static const bool done = [] {
    FactorFiles f;
    f.sidecar = {{"parameterization", "pq"}};
    f.diffuse = {0.01, 0.02, 0.03};
    f.terms.resize(2);
    f.terms[0].p.image = RgbImage::Filled(3, 2, 0.25f);
    f.terms[0].q.image = RgbImage::Filled(2, 4, 2.0f);
    f.terms[0].q.image.At(1, 3)[2] = -1.5f;
    f.terms[1].p.image = RgbImage::Filled(2, 2, 0.5f);
    f.terms[1].q.image = RgbImage::Filled(3, 3, 1.0f);
    WriteFactorFiles(FactorFilePaths(ScratchDir(), "f", 2), f);
    return true;
  }();
  (void)done;
}

void CheckAgreement(const FactorFiles& f) {
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

}  // namespace

int FuzzFactorSidecar(const std::uint8_t* data, std::size_t size) {
  WriteTexturesOnce();
  const auto json = WriteScratch("f.factor.json", data, size);
  FactorFiles f;
  try {
    f = ReadFactorFiles(json);
  } catch (const InputError&) {
    return 0;
  }
  CheckAgreement(f);

  const auto out_dir = ScratchDir() / "out";
  std::filesystem::create_directories(out_dir);
  const FactorPaths out = FactorFilePaths(out_dir, "g", static_cast<int>(f.terms.size()));
  WriteFactorFiles(out, f);
  const FactorFiles back = ReadFactorFiles(out.json);
  CheckAgreement(back);
  CheckInvariant(back.terms.size() == f.terms.size(), "round trip rank");
  for (std::size_t k = 0; k < f.terms.size(); ++k) {
    CheckInvariant(
        back.terms[k].p.image == f.terms[k].p.image && back.terms[k].q.image == f.terms[k].q.image,
        "round trip images");
  }
  CheckInvariant(back.diffuse == f.diffuse, "round trip diffuse value");
  CheckInvariant(back.sidecar.at("parameterization") == f.sidecar.at("parameterization"),
                 "round trip parameterization");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzFactorSidecar)
