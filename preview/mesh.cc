#include "preview/mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace brdfit::preview {
namespace {

bool Finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Mesh PlaceMesh(const Mesh& mesh, const Vec3& centre, double radius, bool normalize) {
  Mesh out = mesh;
  const Vec3 origin = normalize ? mesh.bound_centre : Vec3{0, 0, 0};
  const double scale = normalize ? radius / std::max(mesh.bound_radius, 1e-300) : radius;
  for (Vec3& p : out.positions) p = centre + scale * (p - origin);
  // A uniform scale and a translation leave unit normals unchanged.
  out.UpdateBounds();
  if (!Finite(out.bound_centre) || !std::isfinite(out.bound_radius) || !(out.bound_radius > 0)) {
    throw InputError("placing the mesh (radius " + std::to_string(radius) +
                     ") gives coordinates out of range");
  }
  return out;
}

}  // namespace brdfit::preview
