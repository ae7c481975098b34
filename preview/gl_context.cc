#include "preview/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

#include "core/sanitizer.h"
#include "preview/gl.h"

#if BRDFIT_ASAN
#include <sanitizer/lsan_interface.h>
#endif

namespace brdfit::preview {
namespace {

std::string EglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(e);
  }
}

[[noreturn]] void Fail(const std::string& step) {
  throw GlUnavailableError(
      "headless OpenGL unavailable: " + step + " (" + EglErrorName(eglGetError()) +
      "). brdfit renders through EGL surfaceless with Mesa: install libegl1 and "
      "libgl1-mesa-dri (scripts/setup-deps.sh)");
}

}  // namespace

HeadlessGlContext::HeadlessGlContext() {
#if BRDFIT_ASAN
  // Under ASan only: LeakSanitizer's exit-time check can crash in its own tracer (signal 11
  // while stopping the threads) once Mesa llvmpipe's worker threads exist, failing a process
  // that did nothing wrong (make test-asan: the urp_steps golden test every run,
  // RenderCli.FourPanelComparison512 now and then). Check for leaks now, before any GL thread
  // exists; LeakSanitizer then skips its exit-time check. Leaks after this point go unseen.
  static const bool checked = [] {
    __lsan_do_leak_check();
    return true;
  }();
  (void)checked;
#endif
  // The EXT entry point: libepoxy-style wrappers abort on eglGetPlatformDisplay.
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client_ext == nullptr || std::string(client_ext).find("EGL_MESA_platform_surfaceless") ==
                                   std::string::npos) {
    Fail("EGL client extension EGL_MESA_platform_surfaceless is missing");
  }
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) Fail("eglGetPlatformDisplayEXT not found");
  EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY) Fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) failed");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor)) Fail("eglInitialize failed (no Mesa DRI driver?)");
  display_ = dpy;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(dpy);
    Fail("eglBindAPI(EGL_OPENGL_API) failed");
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  // No config and no surface: EGL_KHR_no_config_context + EGL_KHR_surfaceless_context.
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT) {
    eglTerminate(dpy);
    Fail("eglCreateContext(OpenGL 3.3 core) failed");
  }
  context_ = ctx;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    Fail("eglMakeCurrent(EGL_NO_SURFACE) failed");
  }
}

// The display is not terminated: eglTerminate unloads Mesa's driver, after which
// LeakSanitizer can no longer name the library of the driver's process-lifetime allocations
// (they show as "<unknown module>" and cannot be suppressed by name). The display is a
// per-process singleton in EGL, so a later context reuses it.
HeadlessGlContext::~HeadlessGlContext() {
  auto dpy = static_cast<EGLDisplay>(display_);
  eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(dpy, static_cast<EGLContext>(context_));
}

std::string HeadlessGlContext::Description() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return str(GL_RENDERER) + " / " + str(GL_VERSION);
}

}  // namespace brdfit::preview
