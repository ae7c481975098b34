// One headless GL context per test binary. If EGL/Mesa is missing the tests FAIL with the
// context's message (CI installs Mesa through scripts/setup-deps.sh): never a silent skip.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "preview/gl_context.h"

namespace brdfit::preview::testing {

inline HeadlessGlContext* SharedContext(std::string* error) {
  static std::unique_ptr<HeadlessGlContext> ctx;
  static std::string failure;
  static bool tried = false;
  if (!tried) {
    tried = true;
    try {
      ctx = std::make_unique<HeadlessGlContext>();
    } catch (const GlUnavailableError& e) {
      failure = e.what();
    }
  }
  *error = failure;
  return ctx.get();
}

}  // namespace brdfit::preview::testing

// Fails the test (fatally) when no context can be made.
#define BRDFIT_REQUIRE_GL()                                                      \
  do {                                                                          \
    std::string gl_error_;                                                      \
    if (!::brdfit::preview::testing::SharedContext(&gl_error_)) {               \
      FAIL() << "headless OpenGL is required for this test: " << gl_error_;     \
    }                                                                           \
  } while (0)
