// Fuzz harness: the factorization sidecar (io/factor_io.h, ReadFactorFiles). The input is the
// JSON sidecar; the EXR textures it can name ("f.p.exr", "f.q.exr", "f.p2.exr", "f.q2.exr") are
// valid files written once per process by WriteFactorFiles (the EXR beside a valid sidecar is
// fuzz_factor_files' job). After a successful read: the sidecar agrees with the images (sizes,
// parameterization, factor names, rank), the diffuse value is finite and >= 0, and writing the
// result and reading it back gives the same images, diffuse value and sidecar.
#include "fuzz/factor_checks.h"
#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/factor_io.h"

namespace brdfit::fuzz {

namespace {

// f.factor.json, overwritten by each input, is the rank-2 sidecar of them.
void WriteTexturesOnce() {
  static const bool done = [] {
    WriteFactorFiles(FactorFilePaths(ScratchDir(), "f", 2), ValidFactorFiles());
    return true;
  }();
  (void)done;
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
  CheckFactorAgreement(f);
  CheckFactorRoundTrip(f, ScratchDir() / "out");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzFactorSidecar)
