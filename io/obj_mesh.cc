#include "io/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/input_file.h"

namespace brdfit {
namespace {

bool Finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A number token of an OBJ line: the whole token, finite.
bool FiniteNumber(const std::string& t) {
  if (t.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && std::isfinite(v);
}

// A face corner index: a non-zero integer that fits an int (negative: relative to the end).
bool CornerIndex(const std::string& t, bool may_be_empty) {
  if (t.empty()) return may_be_empty;
  std::size_t i = t[0] == '-' ? 1 : 0;
  if (i == t.size() || t.size() - i > 10) return false;
  for (std::size_t k = i; k < t.size(); ++k) {
    if (t[k] < '0' || t[k] > '9') return false;
  }
  const long long v = std::stoll(t);
  return v != 0 && v >= -2147483647LL && v <= 2147483647LL;
}

// The lines tinyobjloader reads leniently, checked first (Wavefront OBJ, "B1. Object Files"):
// it read "v a b c" as (0, 0, 0), an index past 2^31 as another vertex, and "vn 0 0 0" or NaN
// normals as directions. Throws InputError naming the file and the line.
void CheckObjLines(const std::string& text, const std::filesystem::path& source) {
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<std::string> tok;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) tok.push_back(line.substr(start, i - start));
    }
    if (tok.empty()) continue;
    const auto fail = [&](const std::string& problem) {
      throw InputError(source, "line " + std::to_string(line_no) + ": " + problem);
    };
    const std::string& key = tok[0];
    const std::size_t n = tok.size() - 1;
    if (key == "v" || key == "vn" || key == "vt") {
      const std::size_t lo = key == "vt" ? 1 : 3, hi = key == "v" ? 7 : 3;
      if (n < lo || n > hi)
        fail("'" + key + "' takes " + std::to_string(lo) + " to " + std::to_string(hi) +
             " numbers, not " + std::to_string(n));
      for (std::size_t k = 1; k <= n; ++k) {
        if (!FiniteNumber(tok[k]))
          fail("'" + key + "' value '" + tok[k] + "' is not a finite number");
      }
      if (key == "vn" && std::strtod(tok[1].c_str(), nullptr) == 0 &&
          std::strtod(tok[2].c_str(), nullptr) == 0 && std::strtod(tok[3].c_str(), nullptr) == 0) {
        fail("'vn 0 0 0' is not a direction");
      }
    } else if (key == "f") {
      if (n < 3) fail("a face needs at least 3 corners");
      for (std::size_t k = 1; k <= n; ++k) {
        const std::string& c = tok[k];
        const std::size_t s1 = c.find('/'), s2 = s1 == std::string::npos ? s1 : c.find('/', s1 + 1);
        const std::string v = c.substr(0, s1);
        const std::string t = s1 == std::string::npos ? "" : c.substr(s1 + 1, s2 - s1 - 1);
        const std::string nrm = s2 == std::string::npos ? "" : c.substr(s2 + 1);
        if (!CornerIndex(v, false) || !CornerIndex(t, true) || !CornerIndex(nrm, true) ||
            (s2 != std::string::npos && c.find('/', s2 + 1) != std::string::npos)) {
          fail("face corner '" + c +
               "' is not v, v/t, v//n or v/t/n with non-zero indices "
               "within 2^31");
        }
      }
    }
  }
}

}  // namespace

void Mesh::UpdateBounds() {
  Vec3 lo = positions.front(), hi = lo;
  for (const Vec3& p : positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  bound_centre = 0.5 * (lo + hi);
  double r2 = 0;
  for (const Vec3& p : positions) {
    const Vec3 d = p - bound_centre;
    r2 = std::max(r2, Dot(d, d));
  }
  bound_radius = std::sqrt(r2);
}

Mesh ParseObj(const std::string& text, const std::filesystem::path& source) {
  CheckObjLines(text, source);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // From a string with empty material text: `mtllib` lines never open other files.
  if (!reader.ParseFromString(text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    throw InputError(source, "not a readable OBJ mesh: " + (why.empty() ? "parse error" : why));
  }
  const tinyobj::attrib_t& a = reader.GetAttrib();
  const std::size_t num_positions = a.vertices.size() / 3;
  const std::size_t num_normals = a.normals.size() / 3;
  if (num_positions > kMaxMeshVertices) {
    throw InputError(source, "more than " + std::to_string(kMaxMeshVertices) + " vertices");
  }

  // One output vertex per distinct (position, normal) pair the faces use.
  Mesh m;
  std::map<std::pair<int, int>, std::uint32_t> vertex_of;
  bool every_corner_has_normal = true;
  std::vector<std::uint32_t> corners;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    const auto& fv = shape.mesh.num_face_vertices;
    std::size_t offset = 0;
    for (const unsigned char n : fv) {
      if (offset + n > idx.size()) throw InputError(source, "face indices run past the end");
      if (n != 3) {  // triangulation leaves only triangles; anything else is degenerate input
        offset += n;
        ++m.dropped_triangles;
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& c = idx[offset + k];
        if (c.vertex_index < 0 || static_cast<std::size_t>(c.vertex_index) >= num_positions) {
          throw InputError(source, "a face refers to vertex " + std::to_string(c.vertex_index + 1) +
                                       " of " + std::to_string(num_positions));
        }
        if (c.normal_index >= 0 && static_cast<std::size_t>(c.normal_index) >= num_normals) {
          throw InputError(source, "a face refers to normal " + std::to_string(c.normal_index + 1) +
                                       " of " + std::to_string(num_normals));
        }
        if (c.normal_index < 0) every_corner_has_normal = false;
        const auto key = std::make_pair(c.vertex_index, c.normal_index);
        auto [it, fresh] = vertex_of.emplace(key, static_cast<std::uint32_t>(m.positions.size()));
        if (fresh) {
          const std::size_t v = static_cast<std::size_t>(c.vertex_index);
          const Vec3 p{a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]};
          if (!Finite(p) || std::abs(p.x) > kMaxMeshCoordinate ||
              std::abs(p.y) > kMaxMeshCoordinate || std::abs(p.z) > kMaxMeshCoordinate) {
            throw InputError(source,
                             "vertex " + std::to_string(v + 1) + " is not finite or beyond 1e100");
          }
          Vec3 nrm{0, 0, 0};
          if (c.normal_index >= 0) {
            const std::size_t ni = static_cast<std::size_t>(c.normal_index);
            nrm = {a.normals[3 * ni], a.normals[3 * ni + 1], a.normals[3 * ni + 2]};
          }
          m.positions.push_back(p);
          m.normals.push_back(nrm);
        }
        corners.push_back(it->second);
      }
      offset += 3;
    }
  }

  // Zero-area triangles carry no surface and no normal: left out and counted. The others add
  // their unit normal weighted by the corner angle to each corner (Thurmer & Wuthrich 1998,
  // "Computing Vertex Normals from Polygonal Facets", JGT 3(1)): unlike area weights, the
  // result does not depend on how a polygon was split into triangles.
  std::vector<Vec3> corner_normal_sum(m.positions.size(), Vec3{0, 0, 0});
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    const Vec3* p[3] = {&m.positions[corners[t]], &m.positions[corners[t + 1]],
                        &m.positions[corners[t + 2]]};
    const Vec3 cross = Cross(*p[1] - *p[0], *p[2] - *p[0]);
    const double twice_area = Length(cross);
    if (!(twice_area > 0) || !std::isfinite(twice_area)) {
      ++m.dropped_triangles;
      continue;
    }
    const Vec3 face_normal = (1.0 / twice_area) * cross;
    for (int k = 0; k < 3; ++k) {
      m.indices.push_back(corners[t + k]);
      const Vec3 a = *p[(k + 1) % 3] - *p[k], b = *p[(k + 2) % 3] - *p[k];
      const double angle = std::atan2(Length(Cross(a, b)), Dot(a, b));
      corner_normal_sum[corners[t + k]] = corner_normal_sum[corners[t + k]] + angle * face_normal;
    }
  }
  if (m.indices.empty()) throw InputError(source, "no triangle with a non-zero area");

  // Normals: the file's where every corner has one, else the angle-weighted face normals
  // summed over the triangles sharing a position (smooth shading).
  m.computed_normals = !every_corner_has_normal;
  if (m.computed_normals) {
    std::vector<Vec3> by_position(num_positions, Vec3{0, 0, 0});
    for (const auto& [key, v] : vertex_of) {
      by_position[static_cast<std::size_t>(key.first)] =
          by_position[static_cast<std::size_t>(key.first)] + corner_normal_sum[v];
    }
    for (const auto& [key, v] : vertex_of)
      m.normals[v] = by_position[static_cast<std::size_t>(key.first)];
  }
  for (std::size_t v = 0; v < m.normals.size(); ++v) {
    const double len = Length(m.normals[v]);
    if (!(len > 0) || !std::isfinite(len)) {
      // A file normal of zero length, or a vertex only degenerate triangles use: take the
      // summed normal of the triangles around it; a vertex no triangle uses keeps +z (unused).
      const double alt = Length(corner_normal_sum[v]);
      m.normals[v] =
          alt > 0 && std::isfinite(alt) ? (1.0 / alt) * corner_normal_sum[v] : Vec3{0, 0, 1};
    } else {
      m.normals[v] = (1.0 / len) * m.normals[v];
    }
  }
  m.UpdateBounds();
  return m;
}

Mesh LoadObj(const std::filesystem::path& path) {
  const std::vector<char> bytes = ReadWholeFile(path);  // InputError naming the file
  return ParseObj(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace brdfit
