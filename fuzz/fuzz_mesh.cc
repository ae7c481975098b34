// Fuzz harness: Wavefront OBJ meshes of preview objects (io/obj_mesh.h ParseObj, which uses
// tinyobjloader; docs/scenes.md). The input is the OBJ text.
// After a successful parse: at least one triangle, every index in range, every position
// finite, every normal of unit length, every kept triangle of non-zero area, a finite bounding
// sphere that holds every vertex; placing the mesh keeps all of that finite.
#include <cmath>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "preview/mesh.h"

namespace brdfit::fuzz {

namespace {

bool Finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void CheckMesh(const Mesh& m) {
  CheckInvariant(m.NumTriangles() >= 1 && m.indices.size() % 3 == 0, "no triangles");
  CheckInvariant(m.positions.size() == m.normals.size(), "normals per vertex");
  for (std::uint32_t i : m.indices) CheckInvariant(i < m.positions.size(), "index out of range");
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    CheckInvariant(Finite(m.positions[v]), "non-finite position");
    CheckInvariant(Finite(m.normals[v]) && std::abs(Length(m.normals[v]) - 1) < 1e-9,
                   "normal not unit");
  }
  CheckInvariant(Finite(m.bound_centre) && std::isfinite(m.bound_radius) && m.bound_radius > 0,
                 "bounding sphere");
  for (const Vec3& p : m.positions) {
    CheckInvariant(Length(p - m.bound_centre) <= m.bound_radius * (1 + 1e-9),
                   "vertex outside bound");
  }
}

}  // namespace

int FuzzMesh(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Mesh mesh;
  try {
    mesh = ParseObj(text, "fuzz.obj");
  } catch (const InputError&) {
    return 0;
  }
  CheckMesh(mesh);
  CheckMesh(preview::PlaceMesh(mesh, {1, -2, 3}, 0.5, true));
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzMesh)
