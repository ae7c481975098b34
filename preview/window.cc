#include "preview/window.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "core/sanitizer.h"
#include "preview/comparison.h"
#include "preview/gl_context.h"
#include "preview/renderer.h"

#if BRDFIT_HAVE_GLFW
#include "preview/gl.h"  // before GLFW: core-profile prototypes, no legacy gl.h
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

namespace brdfit::preview {

#if !BRDFIT_HAVE_GLFW

bool WindowSupported() {
  return false;
}

WindowResult RunPreviewWindow(Scene, const MaterialSet&, const WindowOptions&, ExplainLog*) {
  throw GlUnavailableError(
      "this brdfit was built without GLFW, so it has no window mode (install libglfw3-dev and "
      "reconfigure); render to a file instead");
}

#else

namespace {

std::string& LastGlfwError() {
  static std::string error;
  return error;
}

void OnGlfwError(int code, const char* description) {
  LastGlfwError() = std::string(description ? description : "unknown") + " (GLFW error " +
                    std::to_string(code) + ")";
}

// Orbit state, reached from GLFW's callbacks through the window's user pointer.
struct ViewState {
  Camera initial, camera;
  bool dragging = false;
  double last_x = 0, last_y = 0;
  bool dirty = true;
};

Vec3 Rotate(const Vec3& v, const Vec3& axis, double angle) {
  // Rodrigues' rotation formula; axis is a unit vector.
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * Cross(axis, v) + (1 - c) * Dot(axis, v) * axis;
}

// Orbits the camera around its target: dx turns about `up`, dy about the camera's right axis
// (kept away from the poles so that the view never flips).
void Orbit(Camera* cam, double dx, double dy) {
  const Vec3 up = Normalize(cam->up);
  Vec3 offset = cam->position - cam->target;
  offset = Rotate(offset, up, -dx);
  const Vec3 right = Normalize(Cross(offset, up));
  const Vec3 tilted = Rotate(offset, right, dy);
  const double polar = std::acos(std::clamp(Dot(Normalize(tilted), up), -1.0, 1.0));
  if (polar > 0.05 && polar < kPi - 0.05) offset = tilted;
  cam->position = cam->target + offset;
}

ViewState* StateOf(GLFWwindow* w) {
  return static_cast<ViewState*>(glfwGetWindowUserPointer(w));
}

void OnKey(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) glfwSetWindowShouldClose(w, GLFW_TRUE);
  if (key == GLFW_KEY_R) {
    ViewState* s = StateOf(w);
    s->camera = s->initial;
    s->dirty = true;
  }
}

void OnMouseButton(GLFWwindow* w, int button, int action, int) {
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  ViewState* s = StateOf(w);
  s->dragging = action == GLFW_PRESS;
  glfwGetCursorPos(w, &s->last_x, &s->last_y);
}

void OnCursor(GLFWwindow* w, double x, double y) {
  ViewState* s = StateOf(w);
  if (!s->dragging) return;
  int width = 1, height = 1;
  glfwGetWindowSize(w, &width, &height);
  // A drag across the whole window turns the view by 180 degrees.
  Orbit(&s->camera, kPi * (x - s->last_x) / std::max(width, 1),
        kPi * (y - s->last_y) / std::max(height, 1));
  s->last_x = x;
  s->last_y = y;
  s->dirty = true;
}

void OnScroll(GLFWwindow* w, double, double dy) {
  ViewState* s = StateOf(w);
  const Vec3 offset = s->camera.position - s->camera.target;
  s->camera.position = s->camera.target + std::pow(0.9, dy) * offset;
  s->dirty = true;
}

// Owns GLFW's global state and the window; destroyed after the renderer's GL objects.
class GlfwWindow {
 public:
  GlfwWindow(int width, int height, const std::string& title) {
    glfwSetErrorCallback(OnGlfwError);
    if (!glfwInit()) {
      throw GlUnavailableError("no window: GLFW could not start (" + LastGlfwError() +
                               "); is there a display (DISPLAY or WAYLAND_DISPLAY)? Without one, "
                               "render to a file (-o) or run under xvfb-run");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
      const std::string why = LastGlfwError();
      glfwTerminate();
      throw GlUnavailableError("no window: " + why + " (an OpenGL 3.3 core context is needed)");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
  }
  ~GlfwWindow() {
    glfwDestroyWindow(window_);
#if BRDFIT_ASAN
    // glfwTerminate closes the X display, which unloads Mesa's GLX driver: LeakSanitizer then
    // sees the driver's process-lifetime allocations with no module name and cannot suppress
    // them by library (cli/cmd_render.cc). Under ASan the process's exit cleans up instead, as
    // the headless context does (preview/gl_context.cc).
#else
    glfwTerminate();
#endif
  }
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;
  GLFWwindow* get() const {
    return window_;
  }

 private:
  GLFWwindow* window_ = nullptr;
};

// Shows a display-referred image (rows top to bottom) in the default framebuffer: uploaded to a
// texture, then blitted with the rows flipped (GL's origin is the bottom-left corner).
class Presenter {
 public:
  Presenter() {
    glGenTextures(1, &texture_);
    glGenFramebuffers(1, &framebuffer_);
  }
  ~Presenter() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  void Upload(const Image& display) {
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, display.width, display.height, 0, GL_RGBA, GL_FLOAT,
                 display.rgba.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    width_ = display.width;
    height_ = display.height;
  }

  void Draw(int target_width, int target_height) const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, target_width, target_height);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBlitFramebuffer(0, 0, width_, height_, 0, target_height, target_width, 0, GL_COLOR_BUFFER_BIT,
                      GL_LINEAR);
  }

 private:
  GLuint texture_ = 0, framebuffer_ = 0;
  int width_ = 0, height_ = 0;
};

// The default framebuffer's back buffer as an image (what the next swap shows).
Image ReadWindow(int width, int height) {
  std::vector<unsigned char> raw(static_cast<std::size_t>(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  Image img(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const unsigned char* src = &raw[4 * (static_cast<std::size_t>(height - 1 - y) * width + x)];
      float* dst = img.At(x, y);
      for (int c = 0; c < 3; ++c) dst[c] = static_cast<float>(src[c]) / 255.0f;
      dst[3] = 1.0f;
    }
  }
  return img;
}

}  // namespace

bool WindowSupported() {
  return true;
}

WindowResult RunPreviewWindow(Scene scene, const MaterialSet& materials,
                              const WindowOptions& options, ExplainLog* log) {
  using Clock = std::chrono::steady_clock;
  const std::string title = options.compare ? "brdfit: comparison" : "brdfit: preview";
  GlfwWindow window(scene.width, scene.height, title);
  log->Add("note", std::string("window: OpenGL ") +
                       reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ", " +
                       reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
  ViewState view;
  view.initial = view.camera = scene.camera;
  glfwSetWindowUserPointer(window.get(), &view);
  glfwSetKeyCallback(window.get(), OnKey);
  glfwSetMouseButtonCallback(window.get(), OnMouseButton);
  glfwSetCursorPosCallback(window.get(), OnCursor);
  glfwSetScrollCallback(window.get(), OnScroll);

  WindowResult result;
  {
    Renderer renderer;  // its GL objects go before the context
    Presenter presenter;
    while (!glfwWindowShouldClose(window.get()) &&
           (options.max_frames <= 0 || result.frames < options.max_frames)) {
      int fb_width = 0, fb_height = 0;
      glfwGetFramebufferSize(window.get(), &fb_width, &fb_height);
      if (fb_width != scene.width || fb_height != scene.height) view.dirty = true;
      const bool render = view.dirty && fb_width > 0 && fb_height > 0;
      if (render) {
        const auto t0 = Clock::now();
        scene.camera = view.camera;
        scene.width = fb_width;
        scene.height = fb_height;
        ExplainLog* l = result.renders == 0 ? log : nullptr;  // only the first frame is explained
        if (options.compare) {
          ComparisonStats stats;
          result.last_display =
              RenderComparison(renderer, scene, materials, fb_width, fb_height, l, &stats);
          result.last_linear = result.last_display;
        } else {
          result.last_linear = renderer.RenderLinear(scene, materials, l);
          result.last_display = renderer.ToDisplay(result.last_linear, scene);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        presenter.Upload(result.last_display);
        view.dirty = false;
        ++result.renders;
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        const std::string status = title + " - " + std::to_string(fb_width) + "x" +
                                   std::to_string(fb_height) + ", " +
                                   std::to_string(static_cast<int>(std::lround(ms))) + " ms";
        glfwSetWindowTitle(window.get(), status.c_str());
      }
      presenter.Draw(fb_width, fb_height);
      // The window shows the same pixels until the next render: read them back once per render.
      if (options.capture_screen && render) result.last_screen = ReadWindow(fb_width, fb_height);
      glfwSwapBuffers(window.get());
      ++result.frames;
      if (options.max_frames > 0) {
        glfwPollEvents();
      } else {
        glfwWaitEventsTimeout(0.1);  // idle until the user does something
      }
    }
  }
  log->Add("note", "window: " + std::to_string(result.frames) + " frames shown, " +
                       std::to_string(result.renders) + " rendered");
  return result;
}

#endif

}  // namespace brdfit::preview
