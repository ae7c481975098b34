// The analytic Jacobian of Lambert + N Lafortune lobes (fit/lafortune_gradient.h) against the
// autodiff Jets the other models use: the value bit for bit equal to the model's double Eval,
// the gradient in optimization space within 1e-10 (relative to the gradient's largest entry),
// over cell-centre geometries of the MERL grid and parameters spanning forward, retro and
// near-horizontal lobes, both signs of the softplus argument, the exponent's range, a lobe
// clipped to zero where its base is not positive, and cxy^2 below the softplus guard.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/table.h"
#include "fit/block_compress.h"
#include "fit/lafortune_gradient.h"
#include "fit/param_layout.h"
#include "models/geometry.h"
#include "models/lafortune.h"

namespace brdfit::internal {
namespace {

template <class M>
void CheckAgainstJets(const std::vector<std::vector<double>>& lobe_params) {
  using G = AnalyticGradient<M>;
  static_assert(G::kAvailable);
  constexpr int P = G::P;
  using Jet = ceres::Jet<double, P>;
  const ParamLayout layout = ParamLayout::Of(M::kParams);
  const Grid grid = Grid::Merl();
  int checked = 0;
  for (const auto& lp : lobe_params) {
    std::vector<double> p = {0.2, 0.1, 0.05};
    for (int k = 0; k < G::kLobes; ++k) {
      for (int i = 0; i < 5; ++i) p.push_back(lp[static_cast<std::size_t>(i)] * (1 + 0.1 * k));
    }
    ASSERT_EQ(p.size(), static_cast<std::size_t>(P));
    std::vector<double> x(P);
    for (int i = 0; i < P; ++i) x[i] = layout.ToOpt(i, p[i]);
    Jet pj[P];
    SeedParams<Jet, P>(layout, x.data(), pj);
    for (std::size_t cell = 7; cell < grid.NumCells(); cell += 9973) {
      const Geometry g = MakeGeometry(grid.CellCentre(cell));
      if (!(g.cos_i > 1e-3 && g.cos_o > 1e-3)) continue;
      double rgb[3], grad[3 * P], direct[3], value_only[3];
      const auto prepared = G::Prepare(p.data(), layout);
      G::Eval(prepared, g, rgb, grad);
      G::Eval(prepared, g, value_only, nullptr);
      M::Eval(p.data(), g, direct);
      ASSERT_EQ(std::memcmp(rgb, direct, sizeof rgb), 0) << cell;
      ASSERT_EQ(std::memcmp(value_only, direct, sizeof rgb), 0) << cell;
      Jet rj[3];
      M::Eval(pj, g, rj);
      for (int c = 0; c < 3; ++c) {
        double scale = 0;
        for (int i = 0; i < P; ++i) scale = std::max(scale, std::abs(rj[c].v[i]));
        for (int i = 0; i < P; ++i) {
          ASSERT_NEAR(grad[c * P + i], rj[c].v[i], 1e-10 * std::max(scale, 1e-300))
              << "cell " << cell << " channel " << c << " parameter " << i;
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

// rho_r, rho_g, rho_b, cxy, n per lobe (later lobes scaled by 1.1, 1.2).
const std::vector<std::vector<double>> kLobes = {
    {0.5, 0.4, 0.3, -1.0, 20.0},    // Phong-like forward lobe
    {0.2, 0.3, 0.1, -0.7, 3.0},     // |cxy| < 1: softplus argument negative
    {0.1, 0.1, 0.2, -1.8, 150.0},   // |cxy| > 1: positive, large
    {0.3, 0.2, 0.2, 0.9, 8.0},      // retro-reflective (clipped where base <= 0)
    {0.05, 0.05, 0.05, -19.5, 1.5}, // near-horizontal
    {0.4, 0.4, 0.4, 1e-120, 5.0},   // cxy^2 below 1e-200: no softplus term
};

TEST(LafortuneGradient, OneLobeMatchesAutodiff) {
  CheckAgainstJets<Sum<Lambert, Lafortune>>(kLobes);
}

TEST(LafortuneGradient, ThreeLobesMatchAutodiff) {
  CheckAgainstJets<Sum<Lambert, Lafortune, Lafortune, Lafortune>>(kLobes);
}

// The initializer's basis column (LafortuneColumn, fit/grid_init.cc): Lafortune::Eval's values
// bit for bit, written at the given stride.
TEST(LafortuneGradient, ColumnMatchesEval) {
  const Grid grid = Grid::Merl();
  std::vector<Geometry> g;
  for (std::size_t cell = 3; cell < grid.NumCells(); cell += 4999) {
    g.push_back(MakeGeometry(grid.CellCentre(cell)));
  }
  for (const auto& lobe : kLobes) {
    for (const double w : {1.0, 0.37}) {
      const double p[5] = {w, 0.5 * w, 2.0 * w, lobe[3], lobe[4]};
      constexpr std::size_t kStride = 12;
      std::vector<double> col(g.size() * kStride, -1.0);
      LafortuneColumn(p, g.data(), g.size(), col.data() + 3, kStride);
      for (std::size_t s = 0; s < g.size(); ++s) {
        double rgb[3];
        Lafortune::Eval(p, g[s], rgb);
        ASSERT_EQ(std::memcmp(rgb, &col[s * kStride + 3], sizeof rgb), 0) << s;
        ASSERT_EQ(col[s * kStride], -1.0);  // nothing written outside its slots
      }
    }
  }
}

// The compressed block's per-channel Gram matrices (fit/block_cost.h) rely on this: channel c's
// gradient is zero outside ChannelColumns()[c], which ascend and end with the residual's column.
TEST(LafortuneGradient, ChannelColumnsHoldEveryNonZero) {
  using M = Sum<Lambert, Lafortune, Lafortune, Lafortune>;
  using G = AnalyticGradient<M>;
  constexpr int P = G::P;
  const auto cols = G::ChannelColumns();
  const ParamLayout layout = ParamLayout::Of(M::kParams);
  std::vector<double> p = {0.2, 0.1, 0.05};
  for (int k = 0; k < G::kLobes; ++k) {
    for (int i = 0; i < 5; ++i) {
      p.push_back(kLobes[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)]);
    }
  }
  const auto prepared = G::Prepare(p.data(), layout);
  const Grid grid = Grid::Merl();
  for (int ch = 0; ch < 3; ++ch) {
    ASSERT_EQ(cols[ch][G::kC - 1], P);
    for (int j = 1; j < G::kC; ++j) ASSERT_LT(cols[ch][j - 1], cols[ch][j]);
  }
  int nonzero = 0;
  for (std::size_t cell = 11; cell < grid.NumCells(); cell += 7919) {
    double rgb[3], grad[3 * P];
    G::Eval(prepared, MakeGeometry(grid.CellCentre(cell)), rgb, grad);
    for (int ch = 0; ch < 3; ++ch) {
      for (int i = 0; i < P; ++i) {
        const bool listed =
            std::find(cols[ch].begin(), cols[ch].end() - 1, i) != cols[ch].end() - 1;
        if (!listed) {
          ASSERT_EQ(grad[ch * P + i], 0.0) << "channel " << ch << " parameter " << i;
        }
        nonzero += listed && grad[ch * P + i] != 0.0;
      }
    }
  }
  EXPECT_GT(nonzero, 1000);
}

}  // namespace
}  // namespace brdfit::internal
