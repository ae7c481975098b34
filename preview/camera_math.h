// Camera transforms shared by the GPU renderer and the CPU reference: a look-at view matrix
// and an OpenGL perspective projection, and the view ray through a pixel centre.
#pragma once

#include <Eigen/Core>

#include "models/geometry.h"
#include "preview/scene.h"

namespace brdfit::preview {

// World -> view (camera at the origin looking down -z, y up), as gluLookAt.
Eigen::Matrix4d ViewMatrix(const Camera& c);
// View -> clip, as gluPerspective (aspect = width / height).
Eigen::Matrix4d ProjectionMatrix(const Camera& c, double aspect);

// Unit direction, in VIEW space, of the ray through the centre of pixel (x, y), rows counted
// from the top: ndc = (2 (x + 0.5) / W - 1, 1 - 2 (y + 0.5) / H), d ~ (ndc tan(fov/2) (aspect, 1), -1).
Vec3 PixelRayView(const Camera& c, int width, int height, int x, int y);

inline Vec3 Transform(const Eigen::Matrix4d& m, const Vec3& p, double w) {
  const Eigen::Vector4d r = m * Eigen::Vector4d(p.x, p.y, p.z, w);
  return {r.x(), r.y(), r.z()};
}

}  // namespace brdfit::preview
