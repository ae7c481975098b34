// Synthetic tables for the factorization tests: exact products of known smooth factors.
#pragma once

#include <array>
#include <cmath>
#include <functional>

#include "core/table.h"
#include "models/geometry.h"

namespace brdfit::testing {

using Rgb = std::array<double, 3>;

// Tabulates f at the cell centres of a grid; cells with a direction at or below the horizon
// are invalid (as MERL).
inline Table Tabulate(
    const Grid& grid,
    const std::function<Rgb(const Vec3&, const Vec3&, const HalfDiffAngles&)>& f) {
  Table t = Table::Empty(grid);
  for (std::size_t idx = 0; idx < grid.NumCells(); ++idx) {
    const HalfDiffAngles a = grid.CellCentre(idx);
    Vec3 wi, wo;
    FromHalfDiff(a, 0.0, &wi, &wo);
    if (wi.z <= 0 || wo.z <= 0) continue;
    const Rgb v = f(wi, wo, a);
    for (int c = 0; c < 3; ++c) t.Value(idx)[c] = v[c];
    t.valid[idx] = 1;
  }
  return t;
}

// Known factors (smooth, positive, isotropic; p(normal) = 1 as the mccool gauge).
//   log p_c(theta) = a_c (1 - cos theta) + b_c (1 - cos theta)^2
//   q_c(theta_h)   = k_c exp(-s sin^2 theta_h)
inline Rgb TrueP(double theta) {
  const double u = 1 - std::cos(theta);
  return {std::exp(0.30 * u - 0.2 * u * u), std::exp(0.50 * u), std::exp(0.70 * u + 0.3 * u * u)};
}
inline Rgb TrueQh(double theta_h) {
  const double s2 = std::sin(theta_h) * std::sin(theta_h);
  return {0.8 * std::exp(-3.0 * s2), 0.5 * std::exp(-2.5 * s2), 0.3 * std::exp(-2.0 * s2)};
}
// q of halfdiff: log q_c = a_c (1 - cos theta_d) + b sin^2 theta_d cos(2 phi_d) (period pi,
// symmetric in phi_d <-> pi - phi_d, 1 at theta_d = 0).
inline Rgb TrueQd(double theta_d, double phi_d) {
  const double u = 1 - std::cos(theta_d);
  const double v = std::sin(theta_d) * std::sin(theta_d) * std::cos(2 * phi_d);
  return {std::exp(0.6 * u + 0.2 * v), std::exp(0.4 * u + 0.15 * v), std::exp(0.2 * u + 0.1 * v)};
}

inline double ThetaOf(const Vec3& w) {
  return std::acos(std::clamp(w.z, -1.0, 1.0));
}

inline Table McCoolProductTable(const Grid& grid) {
  return Tabulate(grid, [](const Vec3& wi, const Vec3& wo, const HalfDiffAngles& a) {
    const Rgb pi = TrueP(ThetaOf(wi)), po = TrueP(ThetaOf(wo)), q = TrueQh(a.theta_h);
    return Rgb{pi[0] * q[0] * po[0], pi[1] * q[1] * po[1], pi[2] * q[2] * po[2]};
  });
}

inline Table HalfDiffProductTable(const Grid& grid) {
  return Tabulate(grid, [](const Vec3&, const Vec3&, const HalfDiffAngles& a) {
    const Rgb p = TrueQh(a.theta_h), q = TrueQd(a.theta_d, a.phi_d);
    return Rgb{p[0] * q[0], p[1] * q[1], p[2] * q[2]};
  });
}

inline Grid SmallGrid() {
  Grid g;
  g.n_theta_h = 24;
  g.n_theta_d = 24;
  g.n_phi_d = 48;
  g.theta_h_mapping = ThetaHMapping::kLinear;
  return g;
}

}  // namespace brdfit::testing
