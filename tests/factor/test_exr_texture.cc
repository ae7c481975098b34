// OpenEXR float32 RGB textures: exact round trips, attributes, errors naming the file.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "core/error.h"
#include "io/exr_texture.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("brdfit_test_exr_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

RgbImage RandomImage(int w, int h, std::uint32_t seed) {
  RgbImage img = RgbImage::Filled(w, h, 0.0f);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-30, 30);
  for (float& v : img.rgb) v = std::exp(u(rng)) * (rng() % 2 ? 1.0f : -1.0f);
  if (img.rgb.size() < 7) return img;
  // Values that a lossy or half-float path would not keep.
  img.rgb[0] = std::numeric_limits<float>::denorm_min();
  img.rgb[1] = std::numeric_limits<float>::max();
  img.rgb[2] = 0.0f;
  img.rgb[3] = -0.0f;
  img.rgb[4] = std::numeric_limits<float>::infinity();
  img.rgb[5] = std::numeric_limits<float>::quiet_NaN();
  img.rgb[6] = 1.0f + std::numeric_limits<float>::epsilon();
  return img;
}

TEST(ExrTexture, WriteReadIsBitExactWithAttributes) {
  const fs::path dir = TempDir("roundtrip");
  for (auto [w, h] : {std::pair{7, 3}, std::pair{64, 64}, std::pair{1, 1}}) {
    const RgbImage img = RandomImage(w, h, w * 100 + h);
    const ExrAttributes attrs = {{"brdfit:formula", "f(wi,wo) = p(wi) q(wh) p(wo)"},
                                 {"brdfit:units", "1/sr"},
                                 {"brdfit:empty", ""},
                                 {"brdfit:utf8", "θ_h ∈ [0, π/2]"}};
    const fs::path path = dir / "t.exr";
    WriteRgbExr(path, img, attrs);
    ExrAttributes back;
    const RgbImage r = ReadRgbExr(path, &back);
    ASSERT_EQ(r.width, w);
    ASSERT_EQ(r.height, h);
    ASSERT_EQ(r.rgb.size(), img.rgb.size());
    EXPECT_EQ(std::memcmp(r.rgb.data(), img.rgb.data(), img.rgb.size() * sizeof(float)), 0);
    for (const auto& [k, v] : attrs) {
      ASSERT_TRUE(back.count(k)) << k;
      EXPECT_EQ(back.at(k), v);
    }
  }
  // Only the destination exists: the temporary file was renamed into place.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(ExrTexture, RowZeroIsTheFirstScanLine) {
  const fs::path dir = TempDir("rows");
  RgbImage img = RgbImage::Filled(2, 3, 0.0f);
  img.At(1, 2)[0] = 5.0f;  // column 1, row 2
  WriteRgbExr(dir / "r.exr", img, {});
  const RgbImage r = ReadRgbExr(dir / "r.exr");
  EXPECT_EQ(r.At(1, 2)[0], 5.0f);
  EXPECT_EQ(r.At(0, 0)[0], 0.0f);
  fs::remove_all(dir);
}

TEST(ExrTexture, BadInputsAreInputErrorsNamingTheFile) {
  const fs::path dir = TempDir("bad");
  auto expect_error = [](const fs::path& p, const std::string& what) {
    try {
      ReadRgbExr(p);
      FAIL() << "no error for " << p;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error(dir / "missing.exr", "no such file");
  std::ofstream(dir / "text.exr") << "not an image";
  expect_error(dir / "text.exr", "not an OpenEXR file");

  // Truncated: a valid file cut in half.
  WriteRgbExr(dir / "full.exr", RandomImage(32, 32, 1), {});
  const auto size = fs::file_size(dir / "full.exr");
  fs::copy_file(dir / "full.exr", dir / "cut.exr");
  fs::resize_file(dir / "cut.exr", size / 2);
  expect_error(dir / "cut.exr", "damaged");

  // A valid EXR without a G channel.
  {
    Imf::Header header(2, 2);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));
    std::vector<float> px(4, 1.0f);
    Imf::OutputFile file((dir / "rb.exr").c_str(), header);
    Imf::FrameBuffer fb;
    for (const char* c : {"R", "B"}) {
      fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), sizeof(float),
                              2 * sizeof(float)));
    }
    file.setFrameBuffer(fb);
    file.writePixels(2);
  }
  expect_error(dir / "rb.exr", "missing channel G");
  fs::remove_all(dir);
}

TEST(ExrTexture, RejectsReservedAttributeNamesAndBadBuffers) {
  const fs::path dir = TempDir("reserved");
  const RgbImage img = RandomImage(4, 4, 2);
  EXPECT_THROW(WriteRgbExr(dir / "a.exr", img, {{"channels", "x"}}), InputError);
  EXPECT_THROW(WriteRgbExr(dir / "a.exr", img, {{"", "x"}}), InputError);
  RgbImage bad = img;
  bad.rgb.pop_back();
  EXPECT_THROW(WriteRgbExr(dir / "a.exr", bad, {}), InputError);
  EXPECT_FALSE(fs::exists(dir / "a.exr"));
  EXPECT_THROW(WriteRgbExr(dir, img, {}), OutputError);  // destination is a directory
  fs::remove_all(dir);
}

}  // namespace
}  // namespace brdfit
