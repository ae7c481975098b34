// Texture parameterizations of the homomorphic factorization (docs/factorization.md).
//
// Two factored forms: McCool, Ang, Ahmad 2001, "Homomorphic Factorization of BRDFs for
// High-Performance Rendering" (SIGGRAPH), reciprocal form with the half vector; Kautz & McCool
// 1999, "Interactive Rendering with Arbitrary BRDFs using Separable Approximations" (EGWR),
// half-angle / difference parameterization:
//   mccool:    f(wi, wo) ~ p(wi) q(wh) p(wo)      p: dimensionless, q: 1/sr
//   halfdiff:  f(wi, wo) ~ p(wh) q(theta_d, phi_d) p: 1/sr,          q: dimensionless
// Every factor is stored as one N x N float RGB texture and looked up with bilinear weights at
// texel centres (OpenGL GL_LINEAR semantics), so the CPU evaluator and a shader agree.
//
// Texture maps (texel (i, j) = image column i, row j; row 0 is the first row of the EXR):
//
//  * Hemisphere disk maps, for factors of a direction w = (x, y, z), z >= 0:
//      (s, t) = rho(theta) (cos phi, sin phi),  s = -1 + (2 i + 1) / N,  t = -1 + (2 j + 1) / N.
//    Warps rho(theta), theta in [0, pi/2] -> rho in [0, 1]:
//      parabolic   rho = tan(theta / 2), i.e. (s, t) = (x, y) / (1 + z)
//                  (Heidrich & Seidel 1998, "View-independent Environment Maps", HWWS; the
//                  hemisphere map of McCool et al. 2001). Finer in theta at the horizon than
//                  at the pole: used for p(wi) of mccool, which varies most at grazing angles.
//      sqrt-theta  rho = sqrt(theta / (pi/2))  (MERL's theta_h warp, Matusik et al. 2003),
//                  i.e. theta = (pi/2) rho^2: resolution concentrated at the pole, for the
//                  half-vector factors q(wh) (mccool) and p(wh) (halfdiff), whose highlight
//                  peak sits at theta_h = 0.
//    Texels outside the unit disk (the corners) hold the rim value (rho clamped to 1), so
//    bilinear lookups next to the horizon stay defined.
//
//  * theta_d/phi_d rectangle, for q of halfdiff (Rusinkiewicz 1998 difference angles):
//      column i <-> theta_d = (i + 1/2) / N * pi/2   (clamped at the edges),
//      row    j <-> phi_d   = (j + 1/2) / N * pi     (periodic with period pi: reciprocity).
//
// Isotropic factors. For an isotropic table f depends on (theta_h, theta_d, phi_d) only. The
// log-space least-squares problem (data integrated over the half-vector azimuth phi_h, plus a
// rotation-invariant smoothness term) is strictly convex after the gauge is pinned and is
// invariant under rotating every factor about the normal, so its unique minimizer is
// rotation-invariant: p(wi), q(wh) of mccool and p(wh) of halfdiff are functions of the polar
// angle only. The solver therefore represents them as radial profiles (piecewise linear in rho
// on K knots) and bakes the profile into the disk texture; sampling several phi_h per cell of a
// 2-D texture would only approximate the same answer at K-fold cost. q(theta_d, phi_d) of
// halfdiff is genuinely two-dimensional and is solved texel by texel.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/enum_names.h"
#include "models/geometry.h"

namespace brdfit {

enum class FactorParam { kMcCool, kHalfDiff };

inline constexpr auto kFactorParamNames = MakeEnumNames<FactorParam>(
    "parameterization", {{FactorParam::kMcCool, "mccool"}, {FactorParam::kHalfDiff, "halfdiff"}});
constexpr const auto& EnumNamesOf(FactorParam) {
  return kFactorParamNames;
}
// FromString<FactorParam> under the name its callers use.
inline FactorParam FactorParamFromString(const std::string& s) {
  return FromString<FactorParam>(s);
}

// The map of one factor texture.
enum class FactorMap { kDiskParabolic, kDiskSqrtTheta, kThetaDPhiD };

inline constexpr auto kFactorMapNames =
    MakeEnumNames<FactorMap>("texture map", {{FactorMap::kDiskParabolic, "disk-parabolic"},
                                             {FactorMap::kDiskSqrtTheta, "disk-sqrt-theta"},
                                             {FactorMap::kThetaDPhiD, "theta_d-phi_d"}});
constexpr const auto& EnumNamesOf(FactorMap) {
  return kFactorMapNames;
}
// The map's formula and texel convention in one line (written into the EXR headers).
const char* MapFormula(FactorMap m);

// What one texture of a parameterization holds (also written into the EXR header).
struct FactorTextureSpec {
  FactorMap map;
  const char* argument;  // "wi and wo", "wh", "(theta_d, phi_d)"
  const char* units;     // "1", "1/sr"
};

struct FactorParamSpec {
  FactorParam param;
  const char* formula;  // human-readable, e.g. "f(wi,wo) = p(wi) q(wh) p(wo)"
  FactorTextureSpec p, q;
  int p_uses;  // how many times p enters the product (2 for mccool: the gauge moves 2c to q)
  const char* gauge;
};

const FactorParamSpec& GetFactorParamSpec(FactorParam p);

// ---- hemisphere disk maps ------------------------------------------------------------------

inline double DiskRadius(FactorMap m, double theta) {
  theta = std::clamp(theta, 0.0, kPi / 2);
  if (m == FactorMap::kDiskParabolic) return std::tan(theta / 2);
  return std::sqrt(theta / (kPi / 2));  // kDiskSqrtTheta
}

inline double DiskTheta(FactorMap m, double rho) {
  rho = std::clamp(rho, 0.0, 1.0);
  if (m == FactorMap::kDiskParabolic) return 2 * std::atan(rho);
  return (kPi / 2) * rho * rho;
}

// Disk coordinates (s, t) of a direction with w.z >= 0 (directions below the horizon are
// clamped to the rim).
inline void DiskCoords(FactorMap m, const Vec3& w, double* s, double* t) {
  const double r_xy = std::hypot(w.x, w.y);
  if (m == FactorMap::kDiskParabolic && w.z >= 0) {
    *s = w.x / (1 + w.z);  // Heidrich & Seidel 1998 (no trigonometry)
    *t = w.y / (1 + w.z);
    return;
  }
  // At the pole the azimuth is undefined and rho = 0: any unit (cos phi, sin phi) works.
  if (r_xy == 0) {
    *s = *t = 0;
    return;
  }
  const double rho = DiskRadius(m, std::atan2(r_xy, w.z));
  *s = rho * w.x / r_xy;
  *t = rho * w.y / r_xy;
}

// Texel-centre coordinate of texel i on an axis of n texels spanning [-1, 1].
inline double DiskTexelCentre(int i, int n) {
  return -1.0 + (2.0 * i + 1.0) / n;
}

// ---- theta_d / phi_d rectangle -----------------------------------------------------------

inline double ThetaDOfColumn(double u, int n) {
  return (u + 0.5) / n * (kPi / 2);
}
inline double PhiDOfRow(double v, int n) {
  return (v + 0.5) / n * kPi;
}

// ---- interpolation weights -----------------------------------------------------------------

// Bilinear weights at a point given in texel units (u = 0 is the centre of column 0), as
// OpenGL GL_LINEAR: u clamps to [0, w-1] (CLAMP_TO_EDGE); v clamps or wraps (REPEAT).
struct Bilinear {
  std::array<int, 4> index{};  // texel index j * width + i
  std::array<double, 4> weight{};
};

inline Bilinear BilinearWeights(double u, double v, int width, int height, bool wrap_v) {
  u = std::clamp(u, 0.0, width - 1.0);
  int i0 = std::min(static_cast<int>(u), width - 2);
  const double fu = u - i0;
  int j0;
  double fv;
  int j1;
  if (wrap_v) {
    const double fl = std::floor(v);
    fv = v - fl;
    j0 = static_cast<int>(((static_cast<long long>(fl) % height) + height) % height);
    j1 = (j0 + 1) % height;
  } else {
    v = std::clamp(v, 0.0, height - 1.0);
    j0 = std::min(static_cast<int>(v), height - 2);
    fv = v - j0;
    j1 = j0 + 1;
  }
  Bilinear b;
  b.index = {j0 * width + i0, j0 * width + i0 + 1, j1 * width + i0, j1 * width + i0 + 1};
  b.weight = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
  return b;
}

// Bilinear weights of a disk-map lookup of direction w in an n x n texture.
inline Bilinear DiskLookup(FactorMap m, const Vec3& w, int n) {
  double s, t;
  DiskCoords(m, w, &s, &t);
  return BilinearWeights(0.5 * n * (s + 1) - 0.5, 0.5 * n * (t + 1) - 0.5, n, n, false);
}

// Bilinear weights of a theta_d/phi_d lookup in a width x height texture (columns theta_d,
// rows phi_d, phi_d periodic with period pi).
inline Bilinear ThetaDPhiDLookup(double theta_d, double phi_d, int width, int height) {
  return BilinearWeights(theta_d / (kPi / 2) * width - 0.5, phi_d / kPi * height - 0.5, width,
                         height, true);
}

// Linear weights of a radial profile with k knots at rho_i = i / (k - 1).
struct Linear2 {
  std::array<int, 2> index{};
  std::array<double, 2> weight{};
};

inline Linear2 ProfileWeights(double rho, int k) {
  const double u = std::clamp(rho, 0.0, 1.0) * (k - 1);
  const int i0 = std::min(static_cast<int>(u), k - 2);
  const double f = u - i0;
  return {{i0, i0 + 1}, {1 - f, f}};
}

}  // namespace brdfit
