// A current OpenGL 3.3+ core context: headless through EGL surfaceless (Mesa llvmpipe, no GPU,
// no display; docs/preview.md). Rendering goes into the renderer's own framebuffer objects.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace brdfit::preview {

// EGL or a core context could not be created (no Mesa DRI driver, no EGL_MESA_platform_surfaceless).
class GlUnavailableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class HeadlessGlContext {
 public:
  // Creates and makes current an OpenGL >= 3.3 core context on the surfaceless platform.
  // Throws GlUnavailableError with the failing step and a hint (install libgl1-mesa-dri).
  HeadlessGlContext();
  ~HeadlessGlContext();
  HeadlessGlContext(const HeadlessGlContext&) = delete;
  HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

  // "Mesa llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile) Mesa 22.3.6".
  std::string Description() const;

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace brdfit::preview
