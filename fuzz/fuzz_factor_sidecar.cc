// Fuzz harness: the factorization sidecar (io/factor_io.h, ReadFactorFiles). The input is the
// JSON sidecar; the two EXR textures it can name ("f.p.exr", "f.q.exr") are valid files written
// once per process by WriteFactorFiles (the EXR reader itself is fuzz_exr's job).
// After a successful read: the sidecar agrees with the images (sizes, parameterization, factor
// names), and writing the result and reading it back gives the same images and sidecar.
#include <cstring>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/factor_io.h"

namespace brdfit::fuzz {

namespace {

// Valid textures beside the fuzzed sidecar: p is 3 x 2, q is 2 x 4, parameterization "pq".
void WriteTexturesOnce() {
  static const bool done = [] {
    FactorFiles f;
    f.sidecar = {{"parameterization", "pq"}};
    f.p.image = RgbImage::Filled(3, 2, 0.25f);
    f.q.image = RgbImage::Filled(2, 4, 2.0f);
    f.q.image.At(1, 3)[2] = -1.5f;
    WriteFactorFiles(FactorFilePaths(ScratchDir(), "f"), f);
    return true;
  }();
  (void)done;
}

void CheckAgreement(const FactorFiles& f) {
  const std::string param = f.sidecar.at("parameterization").get<std::string>();
  const FactorTextureFile* tex[2] = {&f.p, &f.q};
  const char* names[2] = {"p", "q"};
  for (int k = 0; k < 2; ++k) {
    const auto& t = f.sidecar.at("textures").at(names[k]);
    CheckInvariant(t.at("width") == tex[k]->image.width && t.at("height") == tex[k]->image.height,
                   "sidecar size disagrees with the image");
    CheckInvariant(tex[k]->attributes.at(kExrAttrFactor) == names[k], "factor name");
    CheckInvariant(tex[k]->attributes.at(kExrAttrParameterization) == param, "parameterization");
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
  const FactorPaths out = FactorFilePaths(out_dir, "g");
  WriteFactorFiles(out, f);
  const FactorFiles back = ReadFactorFiles(out.json);
  CheckAgreement(back);
  CheckInvariant(back.p.image == f.p.image && back.q.image == f.q.image, "round trip images");
  CheckInvariant(back.sidecar.at("parameterization") == f.sidecar.at("parameterization"),
                 "round trip parameterization");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzFactorSidecar)
