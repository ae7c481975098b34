// Materials ready to render: what a MaterialSpec resolves to after loading (pipeline/material_loader.h).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/factor_form.h"
#include "core/image.h"
#include "core/table.h"
#include "preview/scene.h"

namespace brdfit::preview {

// A factorization as textures (McCool, Ang, Ahmad 2001; factor/factor_param.h, core/factor_form.h):
//   f = d + sum_k term_k, d the diffuse value (1/sr), K = terms.size() in [1, 4] products:
//   mccool:   term_k = p_k(wi) q_k(wh) p_k(wo), p on the parabolic disk map, q on the sqrt-theta
//             disk map;
//   halfdiff: term_k = p_k(wh) q_k(theta_d, phi_d), p on the sqrt-theta disk, q on the
//             (theta_d, phi_d) rectangle (phi_d periodic).
// Rows as stored (row 0 first), RGB in rgba with alpha 1.
inline constexpr int kMaxFactorTextureTerms = 4;  // FACTOR_RANK of preview/glsl/factored.glsl
struct FactorTextures {
  std::string parameterization;  // "mccool" or "halfdiff"
  Vec3 diffuse{0, 0, 0};         // d = kd / pi, 1/sr, linear RGB
  struct Term {
    Image p, q;
  };
  std::vector<Term> terms;
  // CPU evaluation of the same factorization (FactoredBrdf::Eval, factor/factor_eval.h: the
  // textures as float32 and the diffuse value), for the reference renderer.
  std::function<std::array<double, 3>(const Vec3& wi, const Vec3& wo)> eval;

  bool has_diffuse() const { return diffuse.x > 0 || diffuse.y > 0 || diffuse.z > 0; }
  int rank() const { return static_cast<int>(terms.size()); }
  // Label ("mccool+d r2") and cost of the form (core/factor_form.h).
  FactorForm form() const {
    FactorForm f{parameterization, has_diffuse(), {}};
    for (const Term& t : terms)
      f.terms.push_back({{t.p.width, t.p.height}, {t.q.width, t.q.height}});
    return f;
  }
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
