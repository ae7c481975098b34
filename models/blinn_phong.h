// Normalized Blinn-Phong specular lobe ("blinn-phong").
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// Blinn 1977, "Models of Light Reflection for Computer Synthesized Pictures" (SIGGRAPH), with
// the (n + 8) / (8 pi) normalization of Sloan & Hoffman / Akenine-Moeller et al., "Real-Time
// Rendering" 3rd ed. eq. 7.49:
//   f_r = ks (n + 8) / (8 pi) cos^n th_h        [1/sr, without the cosine]
// cos^n th_h = exp(n log cos th_h) with log cos from log1p(-sin^2 th_h) near th_h = 0 (PowCos).
// Shading tutorials also use the un-normalized (H.N)^n (preview only; docs/models.md). The
// normalization is approximate: the albedo exceeds ks at grazing incidence for sharp lobes (its
// implicit G = cos_i cos_o), so NOT energy conserving.
//
// Parameters: ks_r, ks_g, ks_b [0, 1e3] linear weights; n = exponent [1, 1e5] (log).
struct BlinnPhong {
  static constexpr std::string_view kName = "blinn-phong";
  static constexpr std::string_view kDoc =
      "normalized Blinn-Phong lobe ks (n+8)/(8 pi) cos^n theta_h (Blinn 1977)";
  static constexpr bool kEnergyConserving = false;
  static constexpr std::array<ParamSpec, 4> kParams = {{
      {"ks_r", "1", 0.0, 1e3, 0.1, false, "specular weight, red", ParamRole::kWeightR},
      {"ks_g", "1", 0.0, 1e3, 0.1, false, "specular weight, green", ParamRole::kWeightG},
      {"ks_b", "1", 0.0, 1e3, 0.1, false, "specular weight, blue", ParamRole::kWeightB},
      {"n", "1", 1.0, 1e5, 100.0, true, "Blinn-Phong exponent (shininess)"},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    const T& n = p[3];
    const T spec = (n + 8.0) / (8.0 * kPi) * PowCos(g.cos_h, g.sin2_h, n);
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * spec;
  }
};

}  // namespace brdfit
