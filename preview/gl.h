// OpenGL core-profile declarations. libOpenGL (glvnd) exports every core entry point, so the
// prototypes are linked directly (no loader, no libepoxy: it aborts on eglGetPlatformDisplay).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace brdfit::preview {

// Throws std::runtime_error naming `what` if glGetError reports an error.
void CheckGl(const char* what);

}  // namespace brdfit::preview
