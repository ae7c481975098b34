// The headless context and the framebuffer round trip: an RGBA32F clear colour comes back
// exactly (no 8-bit quantization, no row flip error).
#include <gtest/gtest.h>

#include "preview/gl_objects.h"
#include "tests/preview/gl_test_env.h"

namespace brdfit::preview {
namespace {

TEST(GlContext, CoreProfileThreeThreeOrLater) {
  BRDFIT_REQUIRE_GL();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(Framebuffer, Float32RoundTripAndTopRowFirst) {
  BRDFIT_REQUIRE_GL();
  Framebuffer fbo(7, 5);
  fbo.Bind();
  glClearColor(0.123456789f, 3.5f, 1e-5f, 1.0f);  // HDR and tiny values survive RGBA32F
  glClear(GL_COLOR_BUFFER_BIT);
  // Paint the top row (GL y = 4) with a scissored clear.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 4, 7, 1);
  glClearColor(7.0f, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const Image img = fbo.ReadRgba();
  ASSERT_EQ(img.width, 7);
  ASSERT_EQ(img.height, 5);
  EXPECT_EQ(img.At(3, 0)[0], 7.0f);  // top row first
  EXPECT_EQ(img.At(3, 4)[0], 0.123456789f);
  EXPECT_EQ(img.At(6, 2)[1], 3.5f);
  EXPECT_EQ(img.At(0, 1)[2], 1e-5f);
}

}  // namespace
}  // namespace brdfit::preview
