// Published D, G and F terms that no catalog model uses, kept out of the headers the fitter
// includes (models/microfacet/): the tutorial variants (tests/models/tutorial_variants.h) are
// built on them, and tests check them against the papers' and tutorials' printed forms
// (test_terms.cc, test_oracles.cc, test_physics.cc). docs/models.md ("Formula variants in
// tutorials and course notes") maps each printed formula to one of these.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "models/geometry.h"
#include "models/math.h"
#include "models/param.h"

namespace brdfit {

// --- D ----------------------------------------------------------------------------------------

// Walter et al. 2007 eq. 30 (Blinn 1977 normalized as a microfacet distribution):
//   D(h) = (n + 2) / (2 pi) cos^n th.
// The normalized Blinn-Phong BRDF (models/blinn_phong.h) uses (n + 8)/(8 pi) instead: that is
// the BRDF normalization including an implicit G and the 1/(4 cos cos).
template <class T>
T DBlinnPhong(const T& n, double cos_h, double sin2_h) {
  return (n + 2.0) / (2.0 * kPi) * PowCos(cos_h, sin2_h, n);
}

// --- G ----------------------------------------------------------------------------------------

// Smith G1 for GGX in Walter et al. 2007's closed form (eq. 34):
//   G1(v) = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta_v)) = 1 / (1 + Lambda_GGX(v)).
template <class T>
T G1SmithGgx(const T& alpha, const Vec3& v) {
  using std::sqrt;
  return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * Tan2Theta(v)));
}

// Implicit G = cos_i cos_o: visibility G / (4 cos_i cos_o) = 1/4 (Hoffman 2010, "Physics and
// Math of Shading", SIGGRAPH course: the G hidden in the Blinn-Phong BRDF).
struct ImplicitG {
  static constexpr std::string_view kName = "implicit";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& g) {
    return T(g.cos_i * g.cos_o);
  }
};

// Kelemen & Szirmay-Kalos 2001, "A Microfacet Based Coupled Specular-Matte BRDF Model with
// Importance Sampling" (Eurographics short): G / (cos_i cos_o) ~ 2 / (1 + wi.wo) = 1 / cos_d^2
// (their approximation of the Torrance-Sparrow / Cook-Torrance G).
struct KelemenG {
  static constexpr std::string_view kName = "Kelemen";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& g) {
    return T(g.cos_i * g.cos_o / (g.cos_d * g.cos_d));
  }
};

// Neumann, Neumann, Szirmay-Kalos 1999, "Compact Metallic Reflectance Models" (CGF 18(3)):
//   G / (cos_i cos_o) = 1 / max(cos_i, cos_o).
struct NeumannG {
  static constexpr std::string_view kName = "Neumann";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& g) {
    return T(std::min(g.cos_i, g.cos_o));  // cos_i cos_o / max(cos_i, cos_o)
  }
};

// Ashikhmin & Premoze 2007, "Distribution-based BRDFs" (tech. report):
//   G / (cos_i cos_o) = 1 / (cos_i + cos_o - cos_i cos_o).
struct AshikhminPremozeG {
  static constexpr std::string_view kName = "Ashikhmin-Premoze";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& g) {
    return T(g.cos_i * g.cos_o / (g.cos_i + g.cos_o - g.cos_i * g.cos_o));
  }
};

// No masking, G = 1 (Ward 1992's implicit visibility 1 / (cos_i cos_o); too bright at grazing
// angles).
struct NoMasking {
  static constexpr std::string_view kName = "none";
  template <class Ndf, class T>
  static T G(const T& /*alpha*/, const Geometry& /*g*/) {
    return T(1.0);
  }
};

// --- F ----------------------------------------------------------------------------------------

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering" (CGF 13(3)), eq. 15:
//   F = F0 + (1 - F0)(1 - c)^5.
template <class T>
T FSchlick(const T& f0, double c) {
  return f0 + (1.0 - f0) * Pow5(1.0 - c);
}

// Schlick with a grazing value F90 (Lagarde & de Rousiers 2014, "Moving Frostbite to PBR",
// Listing 1):  F = F0 + (F90 - F0)(1 - c)^5.
template <class T>
T FSchlickF90(const T& f0, const T& f90, double c) {
  return f0 + (f90 - f0) * Pow5(1.0 - c);
}

// The "Far Cry 3" approximation, as quoted by the URP workshop 2025 (step 9; docs/models.md):
//   F = F0 + (1 - F0) exp(-6 c).
template <class T>
T FFarCry3(const T& f0, double c) {
  return f0 + (1.0 - f0) * std::exp(-6.0 * c);
}

// Exact unpolarized Fresnel reflectance of a dielectric with relative IOR eta > 1 (light
// arriving from the rarer medium), in Cook & Torrance 1982's form (Appendix):
//   g = sqrt(eta^2 - 1 + c^2),
//   F = (g - c)^2 / (2 (g + c)^2) * (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2).
// Tokoi's lecture notes print g = sqrt(n^2 + c^2 + 1) and "- 1" in the last denominator (two
// typos); this is the correct form. Equal to the s/p amplitude form with Snell's law (tested).
template <class T>
T FDielectric(const T& eta, double c) {
  using std::sqrt;
  const T g = sqrt(eta * eta - 1.0 + c * c);  // eta > 1: the radicand is >= c^2 > 0
  const T gpc = g + c;
  const T gmc = g - c;
  const T ratio = (c * gpc - 1.0) / (c * gmc + 1.0);
  return 0.5 * (gmc * gmc) / (gpc * gpc) * (1.0 + ratio * ratio);
}

// F0 = ((eta - 1) / (eta + 1))^2 (the above at c = 1), and its inverse (shader code such as the
// URP workshop 2025's FresnelReflectanceAverageDielectric recovers eta from F0 this way).
template <class T>
T F0FromIor(const T& eta) {
  const T r = (eta - 1.0) / (eta + 1.0);
  return r * r;
}
template <class T>
T IorFromF0(const T& f0) {
  using std::sqrt;
  const T s = sqrt(f0);
  return (1.0 + s) / (1.0 - s);
}

// Unpolarized Fresnel reflectance of a conductor with complex IOR eta + i k, closed form of
// the Fresnel equations (Born & Wolf, "Principles of Optics", §14.2; the arrangement of
// Pharr, Jakob, Humphreys, "Physically Based Rendering" 3rd ed. §8.2.1, FrConductor):
//   a^2 + b^2 = sqrt((eta^2 - k^2 - s^2)^2 + 4 eta^2 k^2),
//   a = sqrt((a^2 + b^2 + eta^2 - k^2 - s^2) / 2),
//   Rs = (a^2 + b^2 + c^2 - 2 a c) / (a^2 + b^2 + c^2 + 2 a c),
//   Rp = Rs (c^2 (a^2 + b^2) + s^4 - 2 a c s^2) / (c^2 (a^2 + b^2) + s^4 + 2 a c s^2),
//   F = (Rs + Rp) / 2,   s^2 = 1 - c^2.
template <class T>
T FConductor(const T& eta, const T& k, double c) {
  using std::sqrt;
  const double c2 = c * c;
  const double s2 = 1.0 - c2;
  const T t0 = eta * eta - k * k - s2;
  const T a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
  const T a = sqrt(0.5 * (a2b2 + t0));  // a2b2 >= |t0|; a > 0 for eta > 0
  const T t1 = a2b2 + c2;
  const T t2 = 2.0 * c * a;
  const T rs = (t1 - t2) / (t1 + t2);
  const T t3 = c2 * a2b2 + s2 * s2;
  const T t4 = t2 * s2;
  const T rp = rs * (t3 - t4) / (t3 + t4);
  return 0.5 * (rs + rp);
}

struct FarCry3Fresnel {
  static constexpr std::string_view kName = "Far Cry 3";
  static constexpr std::array<ParamSpec, 1> kParams = {{
      {"f0", "1", 0.0, 1.0, 0.04, false, "Fresnel reflectance at normal incidence"},
  }};
  template <class T>
  static T F(const T* p, const Geometry& g) {
    return FFarCry3(p[0], g.cos_d);
  }
};

struct DielectricFresnel {
  static constexpr std::string_view kName = "exact dielectric";
  static constexpr std::array<ParamSpec, 1> kParams = {{
      {"ior", "1", 1.01, 4.0, 1.5, false, "relative index of refraction eta (exact Fresnel)"},
  }};
  template <class T>
  static T F(const T* p, const Geometry& g) {
    return FDielectric(p[0], g.cos_d);
  }
};

}  // namespace brdfit
