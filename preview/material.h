// Materials ready to render: what a MaterialSpec resolves to after loading (pipeline/material_loader.h).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/table.h"
#include "core/image.h"
#include "preview/scene.h"

namespace brdfit::preview {

// A factorization as two textures (McCool, Ang, Ahmad 2001; factor/factor_param.h):
//   mccool:   f = p(wi) q(wh) p(wo), p on the parabolic disk map, q on the sqrt-theta disk map;
//   halfdiff: f = p(wh) q(theta_d, phi_d), p on the sqrt-theta disk, q on the (theta_d, phi_d)
//             rectangle (phi_d periodic).
// Rows as stored (row 0 first), RGB in rgba with alpha 1.
struct FactorTextures {
  std::string parameterization;  // "mccool" or "halfdiff"
  Image p, q;
  // CPU evaluation through the same textures (factor/factor_eval.h), for the reference renderer.
  std::function<std::array<double, 3>(const Vec3& wi, const Vec3& wo)> eval;
};

struct ResolvedMaterial {
  std::string name;
  MaterialKind kind = MaterialKind::kAnalytic;
  std::string model;                   // kAnalytic
  std::vector<double> params;          // kAnalytic, full vector
  std::shared_ptr<const Table> table;  // kMeasured
  std::shared_ptr<const FactorTextures> factors;  // kFactored
};

using MaterialSet = std::map<std::string, ResolvedMaterial>;

}  // namespace brdfit::preview
