// The seed corpora (fuzz/corpus, written by fuzz/make_seeds.cc) must hold inputs the readers
// accept: a fuzzer starting from rejected seeds spends its time on the first format check.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "fuzz/harness_util.h"
#include "io/exr_texture.h"
#include "io/factor_io.h"
#include "io/hdf5_table.h"
#include "io/nbrdf.h"
#include "io/rgl_bsdf_file.h"
#include "preview/scene.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(BRDFIT_SOURCE_DIR) / "fuzz" / "corpus";

// A seed without its leading mode byte, as a file.
fs::path WithoutModeByte(const fs::path& seed, const std::string& name) {
  std::ifstream in(seed, std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  EXPECT_GE(bytes.size(), 1u) << seed;
  return fuzz::WriteScratch(name, bytes.data() + 1, bytes.size() - 1);
}

TEST(FuzzSeeds, Hdf5TablesAreAccepted) {
  for (const char* name : {"sqrt-2x3x4.h5", "linear-3x2x2.h5", "single-cell.h5",
                           "nan-in-masked.h5"}) {
    EXPECT_NO_THROW(ReadHdf5Table(kCorpus / "hdf5_table" / name)) << name;
  }
  EXPECT_EQ(ReadHdf5Table(kCorpus / "hdf5_table" / "sqrt-2x3x4.h5").grid.NumCells(), 24u);
}

TEST(FuzzSeeds, NbrdfArchiveIsAccepted) {
  const fs::path zip = WithoutModeByte(kCorpus / "nbrdf" / "archive-two", "seed.zip");
  EXPECT_EQ(ListNbrdfMaterials(zip), (std::vector<std::string>{"alpha", "beta"}));
  const NbrdfNetwork a = ReadNbrdf(zip, "alpha");
  EXPECT_EQ(a.k1.rows(), 6);
  EXPECT_EQ(a.k1.cols(), 4);
  const NbrdfNetwork b = ReadNbrdf(zip, "beta");  // the deflated member
  EXPECT_EQ(b.k2.rows(), 21);
  EXPECT_EQ(b.k3.cols(), 3);
}

TEST(FuzzSeeds, ExrTexturesAreAccepted) {
  for (const auto& e : fs::directory_iterator(kCorpus / "exr")) {
    EXPECT_NO_THROW(ReadRgbExr(e.path())) << e.path();
  }
}

TEST(FuzzSeeds, ScenesAreAccepted) {
  for (const auto& e : fs::directory_iterator(kCorpus / "scene")) {
    EXPECT_NO_THROW(preview::LoadScene(e.path())) << e.path();
  }
}

TEST(FuzzSeeds, RglBsdfFilesAreAcceptedAndTheAnisotropicOneRefused) {
  for (const char* name : {"rgb-4x4", "rgb-1phi-valid", "spectral-3x3"}) {
    EXPECT_NO_THROW(ReadRglBsdf(kCorpus / "rgl_bsdf" / name)) << name;
  }
  EXPECT_EQ(ReadRglBsdf(kCorpus / "rgl_bsdf" / "rgb-1phi-valid").valid.size(), 2u * 3 * 3);
  EXPECT_THROW(ReadRglBsdf(kCorpus / "rgl_bsdf" / "anisotropic"), InputError);
}

}  // namespace
}  // namespace brdfit
