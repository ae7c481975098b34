// Synthetic tables for the factorization tests: exact products of known smooth factors.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "core/table.h"
#include "factor/factor_eval.h"
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

// A factorization built by hand, not solved: `rank` terms of smooth positive textures, term k
// at resolution `res` >> k (so terms differ in size; halfdiff's q is res x res/2, not square),
// term k's lobe narrower and weaker with k, plus `diffuse` (1/sr).
inline FactoredBrdf HandBuiltFactoredBrdf(FactorParam param, int rank,
                                          std::array<double, 3> diffuse, int res = 16) {
  const FactorParamSpec& spec = GetFactorParamSpec(param);
  std::vector<FactorTerm> terms;
  for (int k = 0; k < rank; ++k) {
    const int n = std::max(4, res >> k);
    auto fill = [&](FactorMap map, int w, int h, double scale, double floor) {
      RgbImage img = RgbImage::Filled(w, h, 0.0f);
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
          // Disk maps: squared radius of the texel centre; the rectangle: theta_d and phi_d.
          const double s = DiskTexelCentre(i, w), t = DiskTexelCentre(j, h);
          const double r2 = map == FactorMap::kThetaDPhiD ? 0.0 : s * s + t * t;
          const double rect = map == FactorMap::kThetaDPhiD
                                  ? 0.3 * (i + 0.5) / w + 0.1 * std::cos(2 * kPi * (j + 0.5) / h)
                                  : 0.0;
          for (int c = 0; c < 3; ++c) {
            img.At(i, j)[c] = static_cast<float>(floor + scale * (1 + 0.15 * c) *
                                                             std::exp(-(2.0 + k) * r2 + rect));
          }
        }
      }
      return img;
    };
    FactorTerm term;
    const bool rect_q = spec.q.map == FactorMap::kThetaDPhiD;
    // mccool: p dimensionless near 1, q the lobe (1/sr); halfdiff: p the lobe, q near 1.
    const double lobe = 0.6 / (1 + k);
    term.p = param == FactorParam::kMcCool ? fill(spec.p.map, n, n, 0.5, 0.5)
                                           : fill(spec.p.map, n, n, lobe, 0.01);
    term.q = param == FactorParam::kMcCool ? fill(spec.q.map, n, n, lobe, 0.01)
                                           : fill(spec.q.map, n, rect_q ? n / 2 : n, 0.5, 0.5);
    terms.push_back(std::move(term));
  }
  return FactoredBrdf(param, diffuse, std::move(terms));
}

}  // namespace brdfit::testing
