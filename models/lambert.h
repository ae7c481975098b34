// Lambertian diffuse reflection.
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/param.h"

namespace brdfit {

// Lambert 1760; normalized form f_r = rho_d / pi (the cosine integrates to pi over the hemisphere).
// f_r in 1/sr, without the cosine. Energy conserving for rho_d <= 1 (albedo = rho_d).
struct Lambert {
  static constexpr std::string_view kName = "lambert";
  static constexpr std::string_view kDoc = "Lambertian diffuse, f = kd / pi";
  static constexpr bool kEnergyConserving = true;
  static constexpr std::array<ParamSpec, 3> kParams = {{
      {"kd_r", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, red", ParamRole::kWeightR},
      {"kd_g", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, green", ParamRole::kWeightG},
      {"kd_b", "1", 0.0, 1.0, 0.5, false, "diffuse albedo, blue", ParamRole::kWeightB},
  }};

  template <class T>
  static void Eval(const T* p, const Geometry& /*g*/, T rgb[3]) {
    for (int c = 0; c < 3; ++c) rgb[c] = p[c] * kInvPi;
  }
};

}  // namespace brdfit
