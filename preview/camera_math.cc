#include "preview/camera_math.h"

#include <cmath>

namespace brdfit::preview {

Eigen::Matrix4d ViewMatrix(const Camera& c) {
  const Vec3 f = Normalize(c.target - c.position);
  const Vec3 s = Normalize(Cross(f, c.up));
  const Vec3 u = Cross(s, f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.row(0) << s.x, s.y, s.z, -Dot(s, c.position);
  m.row(1) << u.x, u.y, u.z, -Dot(u, c.position);
  m.row(2) << -f.x, -f.y, -f.z, Dot(f, c.position);
  return m;
}

Eigen::Matrix4d ProjectionMatrix(const Camera& c, double aspect) {
  const double t = 1.0 / std::tan(c.fov_y / 2);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (c.far + c.near) / (c.near - c.far);
  m(2, 3) = 2 * c.far * c.near / (c.near - c.far);
  m(3, 2) = -1;
  return m;
}

Vec3 PixelRayView(const Camera& c, int width, int height, int x, int y) {
  const double th = std::tan(c.fov_y / 2), aspect = static_cast<double>(width) / height;
  const double nx = 2.0 * (x + 0.5) / width - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / height;
  return Normalize(Vec3{nx * th * aspect, ny * th, -1.0});
}

}  // namespace brdfit::preview
