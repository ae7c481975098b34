// Fuzz harness: a factorization's sidecar + EXR files together (io/factor_io.h,
// ReadFactorFiles). Byte 0 picks the file the rest of the input becomes, in a folder holding a
// valid rank-2 factorization (fuzz/factor_checks.h) under stem "h": 0 the sidecar, 1 h.p.exr,
// 2 h.q.exr, 3 h.p2.exr, 4 h.q2.exr (the others stay valid). After a successful read: the
// checks of fuzz_factor_sidecar (agreement, round trip).
#include <array>
#include <filesystem>
#include <string>

#include "fuzz/factor_checks.h"
#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/factor_io.h"

namespace brdfit::fuzz {

namespace {

namespace fs = std::filesystem;

constexpr const char* kStem = "h";

// The valid files' names (sidecar first, then p, q, p2, q2) and bytes, written once.
struct ValidSet {
  std::array<std::string, 5> names, bytes;
};

const ValidSet& Valid() {
  static const ValidSet v = [] {
    const fs::path dir = ScratchDir() / "files-valid";
    fs::create_directories(dir);
    const FactorPaths paths = FactorFilePaths(dir, kStem, 2);
    WriteFactorFiles(paths, ValidFactorFiles());
    const std::array<fs::path, 5> files = {paths.json, paths.terms[0].p, paths.terms[0].q,
                                           paths.terms[1].p, paths.terms[1].q};
    ValidSet s;
    for (std::size_t i = 0; i < files.size(); ++i) {
      s.names[i] = files[i].filename().string();
      s.bytes[i] = ReadAllBytes(files[i]);
    }
    return s;
  }();
  return v;
}

}  // namespace

int FuzzFactorFiles(const std::uint8_t* data, std::size_t size) {
  const ValidSet& valid = Valid();
  ByteReader in(data, size);
  const std::size_t target = in.U8() % valid.names.size();
  const std::string_view rest = in.Rest();
  const fs::path dir = ScratchDir() / "files";
  fs::create_directories(dir);
  for (std::size_t i = 0; i < valid.names.size(); ++i) {
    const std::string_view bytes = i == target ? rest : std::string_view(valid.bytes[i]);
    WriteScratch("files/" + valid.names[i], bytes.data(), bytes.size());
  }
  FactorFiles f;
  try {
    f = ReadFactorFiles(dir / valid.names[0]);
  } catch (const InputError&) {
    return 0;
  }
  CheckFactorAgreement(f);
  CheckFactorRoundTrip(f, ScratchDir() / "files-out");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzFactorFiles)
