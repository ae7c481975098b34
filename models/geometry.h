// Local shading geometry shared by every model, the fitter, the synthesizer and the preview.
//
// Conventions (docs/conventions.md):
//  * Local frame: z is the surface normal. Directions wi (towards the light) and wo
//    (towards the viewer) point AWAY from the surface and are unit length.
//  * Half/difference angles after Rusinkiewicz 1998, "A New Change of Variables for
//    Efficient BRDF Representation" (EGWR): h = normalize(wi + wo); theta_d and phi_d are the
//    spherical angles of wi after rotating h to the pole (rotate by -phi_h about z, then by
//    -theta_h about y). phi_d is folded to [0, pi) (reciprocity: swapping wi and wo adds pi).
//  * Directions are data, never optimized: geometry is always double.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace brdfit {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kInvPi = std::numbers::inv_pi;

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 Cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double Length(const Vec3& a) { return std::sqrt(Dot(a, a)); }
inline Vec3 Normalize(const Vec3& a) { return (1.0 / Length(a)) * a; }

// Unit vector from spherical angles (theta from +z, phi from +x towards +y).
inline Vec3 FromSpherical(double theta, double phi) {
  const double s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

// Rotations about the frame axes (right-handed, angle in radians).
inline Vec3 RotateZ(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}
inline Vec3 RotateY(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

// Rusinkiewicz 1998 half/difference angles of an isotropic configuration.
struct HalfDiffAngles {
  double theta_h = 0;  // [0, pi/2]
  double theta_d = 0;  // [0, pi/2]
  double phi_d = 0;    // [0, pi), folded by reciprocity
};

// (wi, wo) -> (theta_h, theta_d, phi_d). At retro-reflection (wi == wo, theta_h = theta_d = 0)
// phi_d is undefined and returned as 0.
inline HalfDiffAngles ToHalfDiff(const Vec3& wi, const Vec3& wo) {
  const Vec3 h = Normalize(wi + wo);
  const double theta_h = std::acos(std::clamp(h.z, -1.0, 1.0));
  const double phi_h = std::atan2(h.y, h.x);
  const Vec3 d = RotateY(RotateZ(wi, -phi_h), -theta_h);
  const double theta_d = std::acos(std::clamp(d.z, -1.0, 1.0));
  double phi_d = std::atan2(d.y, d.x);
  if (phi_d < 0) phi_d += kPi;
  if (phi_d >= kPi) phi_d -= kPi;  // atan2 can return exactly pi
  return {theta_h, theta_d, phi_d};
}

// (theta_h, theta_d, phi_d) and the half-vector azimuth phi_h -> (wi, wo).
// The inverse of ToHalfDiff up to the phi_d fold (which swaps wi and wo).
inline void FromHalfDiff(const HalfDiffAngles& a, double phi_h, Vec3* wi, Vec3* wo) {
  const Vec3 h = FromSpherical(a.theta_h, phi_h);
  const Vec3 d = FromSpherical(a.theta_d, a.phi_d);
  *wi = RotateZ(RotateY(d, a.theta_h), phi_h);
  *wo = 2.0 * Dot(*wi, h) * h - *wi;  // mirror wi about h
}

// Everything a model needs about one (wi, wo) pair, computed once per sample.
// Quantities that cancel catastrophically near the normal are computed from components.
struct Geometry {
  Vec3 wi, wo, h;
  double cos_i = 0;   // n . wi
  double cos_o = 0;   // n . wo
  double cos_h = 0;   // n . h
  double cos_d = 0;   // wi . h == wo . h
  double sin2_h = 0;  // 1 - cos_h^2, as h.x^2 + h.y^2 (no cancellation at theta_h -> 0)
  double cos_r = 0;   // wo . reflect(wi) (Phong's cos alpha_r), reflect(wi) = 2 (n.wi) n - wi
};

inline Geometry MakeGeometry(const Vec3& wi, const Vec3& wo) {
  Geometry g;
  g.wi = wi;
  g.wo = wo;
  g.h = Normalize(wi + wo);
  g.cos_i = wi.z;
  g.cos_o = wo.z;
  g.cos_h = g.h.z;
  g.cos_d = Dot(wi, g.h);
  g.sin2_h = g.h.x * g.h.x + g.h.y * g.h.y;
  g.cos_r = 2.0 * wi.z * wo.z - Dot(wi, wo);
  return g;
}

inline Geometry MakeGeometry(const HalfDiffAngles& a, double phi_h = 0.0) {
  Vec3 wi, wo;
  FromHalfDiff(a, phi_h, &wi, &wo);
  return MakeGeometry(wi, wo);
}

}  // namespace brdfit
