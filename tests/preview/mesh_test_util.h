// OBJ text of simple shapes for the mesh tests, generated here (no third-party data).
#pragma once

#include <cmath>
#include <string>

#include "models/geometry.h"

namespace brdfit::preview::testing {

// A UV sphere of radius r about the origin, with exact unit normals (vn) when with_normals.
inline std::string UvSphereObj(int n_theta, int n_phi, double r, bool with_normals) {
  std::string s = "# UV sphere\n";
  for (int i = 0; i <= n_theta; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      const Vec3 n = FromSpherical(kPi * i / n_theta, 2 * kPi * j / n_phi);
      // y up: swap so the poles are on the y axis.
      const Vec3 p{n.x, n.z, -n.y};
      char line[160];
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", r * p.x, r * p.y, r * p.z);
      s += line;
      if (with_normals) {
        std::snprintf(line, sizeof line, "vn %.17g %.17g %.17g\n", p.x, p.y, p.z);
        s += line;
      }
    }
  }
  auto id = [&](int i, int j) { return std::to_string(i * n_phi + (j % n_phi) + 1); };
  auto corner = [&](int i, int j) { return with_normals ? id(i, j) + "//" + id(i, j) : id(i, j); };
  for (int i = 0; i < n_theta; ++i) {
    for (int j = 0; j < n_phi; ++j) {
      // Quads (triangulated by the reader); the pole rows give zero-area triangles, left out.
      s += "f " + corner(i, j) + " " + corner(i + 1, j) + " " + corner(i + 1, j + 1) + " " +
           corner(i, j + 1) + "\n";
    }
  }
  return s;
}

// A unit cube [-1, 1]^3 as six quads, no normals.
inline std::string CubeObj() {
  return "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
         "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
}

}  // namespace brdfit::preview::testing
