// Triangle meshes for preview objects (`"shape": "mesh"` in docs/scenes.md): Wavefront OBJ
// read with tinyobjloader (Debian libtinyobjloader-dev), validated, with smooth vertex normals
// computed when the file has none, and placed in the scene by the object's centre and radius.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "models/geometry.h"

namespace brdfit::preview {

struct Mesh {
  std::vector<Vec3> positions;         // per vertex
  std::vector<Vec3> normals;           // per vertex, unit length
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
  // A bounding sphere (the bounding box's centre and the farthest vertex from it): the
  // renderer culls lights with it, and placement scales it.
  Vec3 bound_centre;
  double bound_radius = 0;
  std::size_t dropped_triangles = 0;  // zero-area triangles left out
  bool computed_normals = false;      // the file had none (or not for every corner)

  std::size_t NumTriangles() const { return indices.size() / 3; }
};

// Parses OBJ text (v, vn, f; polygons are triangulated; materials and texture coordinates are
// ignored). Throws InputError naming `source` for text that is not a usable mesh: no triangle,
// coordinates that are not finite or beyond kMaxMeshCoordinate (products of two must not
// overflow), out-of-range indices, more than kMaxMeshVertices vertices.
inline constexpr std::size_t kMaxMeshVertices = 20'000'000;
inline constexpr double kMaxMeshCoordinate = 1e100;
Mesh ParseObj(const std::string& text, const std::filesystem::path& source);

// Reads and parses an OBJ file (io/input_file.h: InputError for a missing or unreadable file).
Mesh LoadObj(const std::filesystem::path& path);

// The mesh in world space. normalize: its bounding sphere becomes (centre, radius). Otherwise
// the file's coordinates are kept, scaled by `radius` and moved by `centre`. Throws
// InputError when the placed coordinates overflow.
Mesh PlaceMesh(const Mesh& mesh, const Vec3& centre, double radius, bool normalize);

}  // namespace brdfit::preview
