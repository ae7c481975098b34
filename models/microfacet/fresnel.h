// Fresnel reflectance F(c), c = cos of the angle between the light and the microfacet normal
// (c = wi.h = wo.h = Geometry::cos_d inside microfacet lobes; tutorials write v.h or l.h: equal).
//
// Free functions (F...) implement the formulas; policy types (...Fresnel) publish the extra
// parameters a lobe gains by choosing them and evaluate F from the lobe's parameter block:
//   static constexpr std::array<ParamSpec, K> kParams;
//   template <class T> static T F(const T* fresnel_params, const Geometry& g);
// Schlick's (1 - c)^5 is evaluated from 1 - c = OneMinusCosD(g), accurate at retro-reflection.
// Only the terms catalog models use live here (the fitter instantiates them); the other
// published forms (F90, Far Cry 3, exact dielectric and conductor) are in
// tests/models/variant_terms.h with the tutorial variants built on them.
#pragma once

#include <array>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering" (CGF 13(3)), eq. 15:
//   F = F0 + (1 - F0)(1 - c)^5, from 1 - c (no cancellation for c -> 1).
template <class T>
T FSchlickOneMinusCos(const T& f0, double one_minus_c) {
  return f0 + (1.0 - f0) * Pow5(one_minus_c);
}

// --- Policy types ------------------------------------------------------------------------------

// F = 1: the Fresnel factor is folded into the lobe's RGB weight (the default for fitting:
// with F0 fitted, F0 and the weight trade off).
struct NoFresnel {
  static constexpr std::string_view kName = "folded into weight";
  static constexpr std::array<ParamSpec, 0> kParams = {};
  template <class T>
  static T F(const T* /*p*/, const Geometry& /*g*/) {
    return T(1.0);
  }
};

struct SchlickFresnel {
  static constexpr std::string_view kName = "Schlick";
  static constexpr std::array<ParamSpec, 1> kParams = {{
      {"f0", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence (Schlick)"},
  }};
  template <class T>
  static T F(const T* p, const Geometry& g) {
    return FSchlickOneMinusCos(p[0], OneMinusCosD(g));
  }
};

}  // namespace brdfit
