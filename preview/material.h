// Materials ready to render: what a MaterialSpec resolves to after loading (preview/loader.h).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/table.h"
#include "preview/image.h"
#include "preview/scene.h"

namespace brdfit::preview {

// Rank-1 factorization f(wi, wo) ~ p(wi) q(wo) as two textures over the hemisphere
// (McCool, Ang, Ahmad 2001). Filled from the factorization's files when they exist.
struct FactorTextures {
  Image p, q;
  std::string parameterization;  // how a direction maps to texture coordinates
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
