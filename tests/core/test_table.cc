#include <gtest/gtest.h>

#include <random>

#include "core/table.h"

namespace brdfit {
namespace {

TEST(Grid, MerlThetaHBinEdgesMatchReference) {
  // MERL's sqrt mapping: bin 1 starts at 0.011 deg, bin 10 at 1.11 deg, bin 45 at 22.5 deg,
  // bin 89 at 88.0 deg.
  const Grid g = Grid::Merl();
  const double deg = 180.0 / kPi;
  EXPECT_NEAR(g.ThetaHAt(1) * deg, 0.0111, 1e-4);
  EXPECT_NEAR(g.ThetaHAt(10) * deg, 1.111, 1e-3);
  EXPECT_NEAR(g.ThetaHAt(45) * deg, 22.5, 1e-12);
  EXPECT_NEAR(g.ThetaHAt(89) * deg, 88.011, 1e-3);
}

TEST(Grid, CellCentreMapsBackToItsCell) {
  for (const auto mapping : {ThetaHMapping::kSqrt, ThetaHMapping::kLinear}) {
    Grid g{16, 12, 24, mapping};
    for (std::size_t idx = 0; idx < g.NumCells(); ++idx) {
      ASSERT_EQ(g.CellOf(g.CellCentre(idx)), idx);
    }
  }
}

TEST(Grid, MerlGeometricallyInvalidFractionAtBinCentres) {
  // About 24.8 % of the 1,458,000 cells are below the horizon at bin centres (docs/conventions.md).
  const Grid g = Grid::Merl();
  std::size_t below = 0;
  for (std::size_t idx = 0; idx < g.NumCells(); ++idx) below += !g.CellAboveHorizon(idx);
  const double fraction = static_cast<double>(below) / g.NumCells();
  EXPECT_NEAR(fraction, 0.248, 0.005);
}

// The mask computed from the axes' sines and cosines answers as CellAboveHorizon in every cell
// of the MERL grid and of small grids of both theta_h mappings (odd and even bin counts).
TEST(Grid, AboveHorizonMaskIsCellAboveHorizonEverywhere) {
  for (const Grid& g :
       {Grid::Merl(), Grid{16, 12, 24, ThetaHMapping::kLinear}, Grid{7, 9, 5, ThetaHMapping::kSqrt},
        Grid{1, 1, 1, ThetaHMapping::kLinear}}) {
    const std::vector<std::uint8_t> mask = g.AboveHorizonMask();
    ASSERT_EQ(mask.size(), g.NumCells());
    std::size_t above = 0;
    for (std::size_t idx = 0; idx < g.NumCells(); ++idx) {
      ASSERT_EQ(mask[idx] != 0, g.CellAboveHorizon(idx)) << idx << " of " << g.NumCells();
      above += mask[idx];
    }
    if (g.NumCells() > 100) {
      EXPECT_GT(above, 0u);
      EXPECT_LT(above, g.NumCells());  // both answers occur
    }
  }
}

TEST(Table, TrilinearReproducesAffineFunctionOfIndexCoordinates) {
  Grid g{8, 8, 16, ThetaHMapping::kLinear};
  Table t = Table::Empty(g);
  for (std::size_t idx = 0; idx < g.NumCells(); ++idx) {
    int ih, id, ip;
    g.Unindex(idx, &ih, &id, &ip);
    t.valid[idx] = 1;
    t.Value(idx)[0] = 1.0 + ih + 2.0 * id;  // affine in index coordinates, no phi dependence
    t.Value(idx)[1] = 2.0;
    t.Value(idx)[2] = 3.0;
  }
  const HalfDiffAngles a{g.ThetaHAt(3.2), g.ThetaDAt(5.9), g.PhiDAt(7.3)};
  const auto v = t.LookupTrilinear(a);
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR((*v)[0], 1.0 + 2.7 + 2.0 * 5.4, 1e-12);
  EXPECT_NEAR((*v)[1], 2.0, 1e-12);
}

TEST(Table, LookupSkipsInvalidCellsAndReportsAllInvalid) {
  Grid g{4, 4, 8, ThetaHMapping::kLinear};
  Table t = Table::Empty(g);
  const HalfDiffAngles a = g.CellCentre(1, 1, 1);
  EXPECT_FALSE(t.LookupNearest(a).has_value());
  EXPECT_FALSE(t.LookupTrilinear(a).has_value());
  const std::size_t idx = g.Index(1, 1, 1);
  t.valid[idx] = 1;
  t.Value(idx)[0] = 5.0;
  ASSERT_TRUE(t.LookupNearest(a).has_value());
  EXPECT_EQ((*t.LookupNearest(a))[0], 5.0);
  // Slightly off-centre: only one valid neighbour, so trilinear returns its value.
  const HalfDiffAngles b{g.ThetaHAt(1.7), g.ThetaDAt(1.6), g.PhiDAt(1.8)};
  EXPECT_EQ((*t.LookupTrilinear(b))[0], 5.0);
  EXPECT_EQ(t.CountValid(), 1u);
}

}  // namespace
}  // namespace brdfit
