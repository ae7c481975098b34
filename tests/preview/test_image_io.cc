// PNG and EXR writers round-trip through their readers; EXR keeps float32 exactly.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "io/image_io.h"
#include "tests/scratch_dir.h"

namespace brdfit::preview {
namespace {

TEST(ImageIo, ExrRoundTripIsExact) {
  Image img(5, 3);
  for (std::size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = 1e-6f * i * i + 0.1f * i;
  img.At(4, 2)[0] = 1234.5f;
  const ScratchDir scratch;
  const auto path = scratch / "a.exr";
  WriteExr(path, img);
  const Image back = ReadExr(path);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  EXPECT_EQ(back.rgba, img.rgba);
}

TEST(ImageIo, PngQuantizesAndClamps) {
  Image img(4, 2);
  img.At(0, 0)[0] = 0.5f;   // -> 128
  img.At(1, 0)[1] = 2.0f;   // clamped -> 255
  img.At(2, 1)[2] = -1.0f;  // clamped -> 0
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) img.At(x, y)[3] = 1.0f;
  const ScratchDir scratch;
  const auto path = scratch / "a.png";
  WritePng(path, img);
  const Image back = ReadPng(path);
  ASSERT_EQ(back.width, 4);
  EXPECT_FLOAT_EQ(back.At(0, 0)[0], 128.0f / 255.0f);
  EXPECT_FLOAT_EQ(back.At(1, 0)[1], 1.0f);
  EXPECT_FLOAT_EQ(back.At(2, 1)[2], 0.0f);
  EXPECT_FLOAT_EQ(back.At(3, 1)[3], 1.0f);
}

TEST(ImageIo, BadInputsNameTheFile) {
  const ScratchDir scratch;
  const auto path = scratch / "not_an_image.png";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    std::fputs("hello", f);
    std::fclose(f);
  }
  try {
    ReadPng(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not_an_image.png"), std::string::npos);
  }
  EXPECT_THROW(WriteImageByExtension(scratch / "x.jpg", Image(1, 1), Image(1, 1)), InputError);
}

}  // namespace
}  // namespace brdfit::preview
