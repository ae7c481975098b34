// Shadowing-masking terms G(wi, wo) of the microfacet BRDF f = D G F / (4 cos_i cos_o).
//
// Each policy type has
//   template <class Ndf, class T> static T G(const T& alpha, const Geometry& g);
// Ndf supplies Lambda for the Smith terms; the others ignore it. Every G is symmetric in
// (wi, wo), so every microfacet lobe built from them is reciprocal. docs/models.md ("Formula
// variants in tutorials and course notes") maps the G and visibility forms printed in tutorials
// and lecture notes (Schlick-k choices, V-groove denominators, visibility terms) onto these types;
// the visibility terms no catalog model uses are in tests/models/variant_terms.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"

namespace brdfit {

// Separable ("uncorrelated") Smith masking-shadowing, Heitz 2014 eq. 98:
//   G2 = G1(wi) G1(wo),  G1(v) = 1 / (1 + Lambda(v))   (Smith 1967; Walter et al. 2007 eq. 23).
struct SmithSeparable {
  static constexpr std::string_view kName = "Smith separable";
  template <class Ndf, class T>
  static T G(const T& alpha, const Geometry& g) {
    return 1.0 / ((1.0 + Ndf::Lambda(alpha, g.wi)) * (1.0 + Ndf::Lambda(alpha, g.wo)));
  }
};

// Height-correlated Smith masking-shadowing, Heitz 2014 eq. 99:
//   G2 = 1 / (1 + Lambda(wi) + Lambda(wo)).
// For GGX this is the G inside Frostbite's V_SmithGGXCorrelated (Lagarde & de Rousiers 2014,
// "Moving Frostbite to PBR", Listing 2), without the second division by 4 cos_i cos_o that the
// URP workshop 2025's PBR step adds (docs/models.md).
struct SmithHeightCorrelated {
  static constexpr std::string_view kName = "Smith height-correlated";
  template <class Ndf, class T>
  static T G(const T& alpha, const Geometry& g) {
    return 1.0 / (1.0 + Ndf::Lambda(alpha, g.wi) + Ndf::Lambda(alpha, g.wo));
  }
};

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering" (CGF 13(3)),
// approximation of Smith's G1:  G1(c) = c / (c (1 - k) + k),  G2 = G1(cos_i) G1(cos_o).
// Published choices of k differ; each one is a named option (sources: docs/models.md):
//   kAlphaHalf    Karis 2013's k = alpha / 2 before its roughness remap; mebiusbox 2018 eq. 74
//   kAlphaSqHalf  mebiusbox 2018's shader code (a*a*0.5 with a = roughness^2, against its eq. 74)
//   kUe4          Karis 2013 (UE4, analytic lights); OpenGL course 2023 §1.3
//   kBeckmannFit  Schlick 1994 for Beckmann m; Tokoi's lecture notes
enum class SchlickK {
  kAlphaHalf,    // k = alpha / 2
  kAlphaSqHalf,  // k = alpha^2 / 2
  kUe4,          // k = (r + 1)^2 / 8, r = sqrt(alpha)
  kBeckmannFit,  // k = alpha sqrt(2 / pi)
};

template <class T>
T SchlickKValue(SchlickK choice, const T& alpha) {
  using std::sqrt;
  switch (choice) {
    case SchlickK::kAlphaHalf:
      return 0.5 * alpha;
    case SchlickK::kAlphaSqHalf:
      return 0.5 * alpha * alpha;
    case SchlickK::kUe4: {
      const T r1 = sqrt(alpha) + 1.0;  // alpha >= 1e-4 in bounds: sqrt' is finite
      return 0.125 * r1 * r1;
    }
    case SchlickK::kBeckmannFit:
      return std::sqrt(2.0 / kPi) * alpha;
  }
  return T(0.0);
}

template <SchlickK K>
struct SchlickSmith {
  static constexpr std::string_view kName = "Schlick-Smith";
  template <class Ndf, class T>
  static T G(const T& alpha, const Geometry& g) {
    const T k = SchlickKValue(K, alpha);
    const T gi = g.cos_i / (g.cos_i * (1.0 - k) + k);
    const T go = g.cos_o / (g.cos_o * (1.0 - k) + k);
    return gi * go;
  }
};

// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics" (ACM TOG 1(1)), V-groove
// geometric attenuation (after Torrance & Sparrow 1967):
//   G = min(1, 2 (n.h)(n.wo) / (wo.h), 2 (n.h)(n.wi) / (wo.h)).
// wi.h == wo.h, so the printed variants that divide by h.l, v.h or l.h all agree.
struct VGroove {
  static constexpr std::string_view kName = "V-groove";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& g) {
    const double s = 2.0 * g.cos_h / g.cos_d;
    return T(std::min({1.0, s * g.cos_o, s * g.cos_i}));
  }
};

}  // namespace brdfit
