// Hostile HDF5 tables (fuzz/regressions/hdf5_table/crafted-*, written by fuzz/make_seeds.cc):
// tiny files declaring huge or overflowing shapes must be rejected with a message naming the
// problem, before anything is allocated; a damaged file that libhdf5 fails to open must not
// leave HDF5 objects or file descriptors behind (a long batch over bad files would run out).
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/exr_texture.h"
#include "io/factor_io.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/nbrdf.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

fs::path Crafted(const std::string& name) {
  return fs::path(BRDFIT_SOURCE_DIR) / "fuzz" / "regressions" / "hdf5_table" / name;
}

std::string RejectionOf(const fs::path& file) {
  try {
    ReadHdf5Table(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(HostileHdf5Tables, HugeDeclaredGridIsRejectedBeforeAllocating) {
  const std::string msg = RejectionOf(Crafted("crafted-huge-declared-grid.h5"));
  EXPECT_NE(msg.find("grid 1024x1024x1024 is too large"), std::string::npos) << msg;
}

TEST(HostileHdf5Tables, ShapeProductOverflowIsRejected) {
  // 2^31 x 2^31 x 2^31 wraps to 0 in 64 bits.
  const std::string msg = RejectionOf(Crafted("crafted-product-overflow.h5"));
  EXPECT_NE(msg.find("is too large"), std::string::npos) << msg;
}

TEST(HostileHdf5Tables, AxisLongerThanAnIntIsRejected) {
  const std::string msg = RejectionOf(Crafted("crafted-axis-2pow31.h5"));
  EXPECT_NE(msg.find("2147483648x1x1 is too large"), std::string::npos) << msg;
}

TEST(HostileHdf5Tables, DeclaredButUnwrittenValuesAreRejected) {
  const std::string msg = RejectionOf(Crafted("crafted-unwritten-values.h5"));
  EXPECT_NE(msg.find("dataset /values declares data that the file does not store"),
            std::string::npos)
      << msg;
}

TEST(HostileHdf5Tables, StringAttributeArrayIsRejected) {
  // Read as one string, its 64 pointers overflowed a char* on the stack (ASan).
  const std::string msg = RejectionOf(Crafted("crafted-vlen-string-array-attr.h5"));
  EXPECT_NE(msg.find("/@format must hold a single value"), std::string::npos) << msg;
}

TEST(HostileHdf5Tables, HugeElementTypeIsRejected) {
  // Found by fuzz_hdf5_table: a float type of 1,768,710,518 bytes per element made libhdf5
  // allocate a 1.7 GB conversion buffer to read 2 axis values.
  const std::string msg = RejectionOf(Crafted("axis-float-1.7GB-elements"));
  EXPECT_NE(msg.find("dataset /axes/theta_h has 1768710518-byte elements (at most 8)"),
            std::string::npos)
      << msg;
}

TEST(HostileHdf5Tables, RejectedFilesLeaveNothingOpen) {
  // libhdf5 fails inside H5Fopen on this file (found by fuzz_hdf5_table).
  const fs::path bad =
      fs::path(BRDFIT_SOURCE_DIR) / "fuzz/regressions/hdf5_table/libhdf5-leak-failed-open";
  const std::size_t fds = fuzz::OpenFdCount(bad.parent_path());
  for (int i = 0; i < 200; ++i) {
    EXPECT_THROW(ReadHdf5Table(bad), InputError);
  }
  EXPECT_EQ(fuzz::OpenFdCount(bad.parent_path()), fds);
  EXPECT_EQ(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE | H5F_OBJ_DATASET | H5F_OBJ_GROUP |
                                              H5F_OBJ_ATTR),
            0);
}

// ---- other readers ------------------------------------------------------------------------

fs::path Regression(const std::string& reader, const std::string& name) {
  return fs::path(BRDFIT_SOURCE_DIR) / "fuzz" / "regressions" / reader / name;
}

template <class F>
std::string MessageOf(F read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(HostileExr, HugeDeclaredImageIsRejectedBeforeAllocating) {
  // 16 kB declaring 32768 x 32768 float RGB pixels (12 GB) and storing none.
  const std::string msg =
      MessageOf([] { ReadRgbExr(Regression("exr", "crafted-32768x32768-no-pixels.exr")); });
  EXPECT_NE(msg.find("unsupported data window 32768 x 32768"), std::string::npos) << msg;
}

TEST(HostileExr, AttributeSizeThatDisagreesWithItsValueIsRejected) {
  // A channel list declaring 311 bytes that ends after 1: OpenEXR reads the next attribute from
  // inside it, a string declaring 1.8 GB, and allocates that (found by the factor_files fuzzer).
  const std::string msg =
      MessageOf([] { ReadRgbExr(Regression("exr", "crafted-chlist-size-hides-huge-string.exr")); });
  EXPECT_NE(msg.find("attribute 'channels' of type 'chlist' declares 311 bytes, its channel list "
                     "is not that long"),
            std::string::npos)
      << msg;
}

TEST(HostileExr, LargeWindowInAFewBytesIsRejectedBeforeDecoding) {
  // A valid 2 x 2 image whose data window is rewritten to 4096 x 4096: 201 MB of float RGB from
  // a file of a few kilobytes, more than zlib's largest compression factor (1032:1) can hold.
  const fs::path dir = fs::path(::testing::TempDir()) / "hostile-exr-window";
  fs::create_directories(dir);
  const fs::path file = dir / "window.exr";
  RgbImage image;
  image.width = image.height = 2;
  image.rgb.assign(12, 0.5f);
  WriteRgbExr(file, image, {});
  std::string bytes = fuzz::ReadAllBytes(file);
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t box[4] = {0, 0, 4095, 4095};
  std::memcpy(&bytes[at + key.size() + 4], box, sizeof(box));
  bytes.append(4096, '\0');  // room for the line-offset table OpenEXR reads (256 ZIP chunks)
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  const std::string msg = MessageOf([&] { ReadRgbExr(file); });
  EXPECT_NE(msg.find(fmt::format("data window 4096 x 4096 needs more pixel data than {} bytes can "
                                 "hold",
                                 bytes.size())),
            std::string::npos)
      << msg;
}

TEST(HostileFactorSidecar, NonStringFormatIsAnInputError) {
  // Was an uncaught nlohmann::json::type_error.
  const std::string msg = MessageOf(
      [] { ReadFactorFiles(Regression("factor_sidecar", "crafted-format-not-string.json")); });
  EXPECT_NE(msg.find("not a brdfit-factorization sidecar"), std::string::npos) << msg;
}

TEST(HostileFactorSidecar, TexturesOutsideRegularFilesAreRejected) {
  const std::string msg = MessageOf(
      [] { ReadFactorFiles(Regression("factor_sidecar", "crafted-absolute-file.json")); });
  // Refused before any read: a texture is a file name in the sidecar's own folder.
  EXPECT_NE(msg.find("crafted-absolute-file.json: textures.p.file '/dev/zero' is not a file name "
                     "in the sidecar's folder"),
            std::string::npos)
      << msg;
}

TEST(HostileFactorSidecar, NonFiniteTexelsAreRejected) {
  // Were read, drawn as NaN, and broke the write -> read round trip of fuzz_factor_files.
  FactorFiles f;
  f.sidecar = {{"parameterization", "pq"}};
  f.terms.resize(1);
  f.terms[0].p.image = RgbImage::Filled(2, 2, 0.5f);
  f.terms[0].q.image = RgbImage::Filled(3, 2, 0.5f);
  f.terms[0].q.image.At(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
  const fs::path dir = fuzz::ScratchDir() / "nan-texel";
  fs::create_directories(dir);
  const FactorPaths paths = FactorFilePaths(dir, "n");
  WriteFactorFiles(paths, f);
  const std::string msg = MessageOf([&] { ReadFactorFiles(paths.json); });
  EXPECT_NE(msg.find(paths.terms[0].q.string() + ": texel (2, 1) channel G is nan"),
            std::string::npos)
      << msg;
}

TEST(HostileFitReport, OptionsThatAreNotJsonAreAnInputError) {
  // Was accepted, then FitParamsJson (brdfit fit --json when resuming) threw json::parse_error.
  const std::string msg = MessageOf(
      [] { ReadFitReport(Regression("fit_report", "crafted-options-not-json.h5")); });
  EXPECT_NE(msg.find("/entries/00000@options is not JSON"), std::string::npos) << msg;
}

TEST(HostileNbrdf, HugeElementTypeIsRejected) {
  // Found by fuzz_nbrdf: a kernel of class FLOAT with gigabytes per element (libhdf5 callocs
  // a conversion buffer of that size). The regression input is a member image after a mode byte.
  std::ifstream in(Regression("nbrdf", "kernel-float-huge-elements"), std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  ASSERT_GT(bytes.size(), 1u);
  const fs::path zip = fuzz::WriteNbrdfZip("hostile.zip", std::string_view(bytes).substr(1));
  const std::string msg = MessageOf([&] { ReadNbrdf(zip, "m"); });
  EXPECT_NE(msg.find("-byte elements (at most 8)"), std::string::npos) << msg;
}

}  // namespace
}  // namespace brdfit
