// Triangle meshes from Wavefront OBJ files (preview objects, `"shape": "mesh"` in
// docs/scenes.md): read with tinyobjloader (Debian libtinyobjloader-dev), validated, with
// smooth vertex normals computed when the file has none. Placement: preview/mesh.h.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "models/geometry.h"

namespace brdfit {

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
  // Recomputes bound_centre and bound_radius from the positions (at least one).
  void UpdateBounds();
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

}  // namespace brdfit
