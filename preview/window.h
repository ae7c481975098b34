// The preview in a window (GLFW, OpenGL 3.3 core on the display's GLX/EGL): the same renderer
// as the headless path, shown on screen and redrawn when the view changes. Left-drag orbits the
// camera around its target, the scroll wheel moves it closer or farther, R resets the view,
// Esc or Q closes. Needs a display (X11 or Wayland); without one it throws GlUnavailableError
// naming the problem, and `brdfit render` exits 2.
#pragma once

#include "preview/explain.h"
#include "core/image.h"
#include "preview/material.h"
#include "preview/scene.h"

namespace brdfit::preview {

struct WindowOptions {
  bool compare = false;  // show the comparison panels (scene 'comparison') instead of the scene
  int max_frames = 0;    // close after this many frames (0: when the user closes the window)
  bool capture_screen = false;  // read the window back after each render (last_screen)
};

struct WindowResult {
  int frames = 0;      // frames shown
  int renders = 0;     // frames that were re-rendered (the view changed)
  Image last_linear;   // the last rendered frame (linear; display values for --compare)
  Image last_display;  // ... and as displayed
  Image last_screen;   // capture_screen: the window's pixels (8-bit, k/255), rows top to bottom
};

// True when this build has window support (GLFW found at configure time).
bool WindowSupported();

// Opens the window and runs until it is closed (or max_frames). Throws GlUnavailableError when
// no window can be created (no display, no GLFW in this build, no OpenGL 3.3 core context).
WindowResult RunPreviewWindow(Scene scene, const MaterialSet& materials,
                              const WindowOptions& options, ExplainLog* log);

}  // namespace brdfit::preview
