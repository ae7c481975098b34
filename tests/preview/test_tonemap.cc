// The GPU display pass (preview/glsl/tonemap.frag) against its C++ twin (preview/tonemap.h),
// and the twin against independent values: sRGB breakpoints (IEC 61966-2-1) and Reinhard.
#include <gtest/gtest.h>

#include <cmath>

#include "preview/renderer.h"
#include "preview/tonemap.h"
#include "tests/preview/gl_test_env.h"

namespace brdfit::preview {
namespace {

TEST(ToneMapTwin, IndependentValues) {
  DisplaySettings s;  // linear tone map, sRGB
  EXPECT_NEAR(ToneMapChannel(0.0031308, s), 0.0404500, 2e-7);  // the sRGB breakpoint
  EXPECT_NEAR(ToneMapChannel(0.5, s), 0.7353569830524495, 1e-12);
  EXPECT_DOUBLE_EQ(ToneMapChannel(2.0, s), 1.0);  // clamped
  s.encoding = Encoding::kLinear;
  s.tone_map = ToneMap::kReinhard;
  s.exposure = 2.0;
  EXPECT_DOUBLE_EQ(ToneMapChannel(1.5, s), 3.0 / 4.0);  // x / (1 + x) at x = 3
  s.tone_map = ToneMap::kUncharted2;
  s.exposure = 1.0;
  s.white_point = 4.0;
  EXPECT_NEAR(ToneMapChannel(4.0, s), 1.0, 1e-12);  // the white point maps to 1
  s.encoding = Encoding::kGamma2;
  s.tone_map = ToneMap::kLinear;
  EXPECT_DOUBLE_EQ(ToneMapChannel(0.25, s), 0.5);
}

TEST(ToneMapPass, GpuMatchesCppTwinForEveryOperatorAndEncoding) {
  BRDFIT_REQUIRE_GL();
  Renderer renderer;
  // A ramp of linear values from 0 to 8 (HDR), one per pixel.
  Image linear(64, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 64; ++x) {
      float* p = linear.At(x, y);
      p[0] = 8.0f * x / 63.0f;
      p[1] = 0.01f * x;
      p[2] = std::pow(2.0f, -12.0f + 0.25f * x);
      p[3] = y == 3 ? 0.0f : 1.0f;  // the last row is background
    }
  }
  Scene scene;
  scene.background = {0.25, 0.5, 0.75};
  for (ToneMap t : {ToneMap::kLinear, ToneMap::kReinhard, ToneMap::kUncharted2, ToneMap::kCineon}) {
    for (Encoding e : {Encoding::kLinear, Encoding::kSrgb, Encoding::kGamma2}) {
      scene.display = {t, 1.7, 6.0, e};
      const Image out = renderer.ToDisplay(linear, scene);
      double max_err = 0;
      for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 64; ++x) {
          for (int c = 0; c < 3; ++c) {
            const double in = y == 3 ? (c == 0 ? 0.25 : c == 1 ? 0.5 : 0.75) : linear.At(x, y)[c];
            max_err = std::max(max_err, std::abs(out.At(x, y)[c] - ToneMapChannel(in, scene.display)));
          }
        }
      }
      // Display values in [0, 1]; float32 pow/exp in the pass vs double in the twin.
      // 3e-4 is below a tenth of one 8-bit step (3.9e-3).
      EXPECT_LT(max_err, 3e-4) << ToString(t) << " " << ToString(e);
    }
  }
}

}  // namespace
}  // namespace brdfit::preview
