// The cached system: reuse gives the same answer as a fresh build, per-material zero cells are
// handled exactly (low-rank correction or rebuild), the cache keys on everything the matrix
// depends on, and bad options are input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "factor/factor.h"
#include "core/error.h"
#include "tests/factor/factor_test_util.h"

namespace brdfit {
namespace {

double MaxLogDiff(const RgbImage& a, const RgbImage& b) {
  EXPECT_EQ(a.rgb.size(), b.rgb.size());
  double m = 0;
  for (std::size_t k = 0; k < a.rgb.size(); ++k) {
    m = std::max(m, std::abs(std::log(static_cast<double>(a.rgb[k]) / b.rgb[k])));
  }
  return m;
}

// A second material on the same grid: different factors, same mask.
Table OtherMaterial(const Grid& g) {
  return testing::Tabulate(g, [](const Vec3& wi, const Vec3& wo, const HalfDiffAngles& a) {
    const double d = std::exp(-20 * std::sin(a.theta_h) * std::sin(a.theta_h));
    return testing::Rgb{0.1 + d * wi.z, 0.2 + d, 0.05 + 3 * d * wo.z};
  });
}

TEST(FactorSystem, SolidAngleWeightsAreFractionsOfTheDomain) {
  // Half of the (theta_h, theta_d, phi_d) box (by measure) has both directions above the
  // horizon: the weights of those cells sum to 1/2 (up to cells cut by the horizon).
  Grid g;
  g.n_theta_h = g.n_theta_d = 45;
  g.n_phi_d = 90;
  std::vector<std::uint8_t> all(g.NumCells(), 1);
  FactorSystemOptions o;
  o.resolution = 8;
  const auto s = FactorSystem::Build(g, all, o);
  const double sum = std::accumulate(s->row_weights().begin(), s->row_weights().end(), 0.0);
  EXPECT_NEAR(sum, 0.5, 5e-3);
  o.weighting = FactorWeighting::kCell;
  const auto c = FactorSystem::Build(g, all, o);
  EXPECT_NEAR(std::accumulate(c->row_weights().begin(), c->row_weights().end(), 0.0),
              static_cast<double>(c->num_rows()) / g.NumCells(), 1e-12);
}

TEST(FactorSystem, ReusedSolveEqualsFreshSolve) {
  const Grid g = testing::SmallGrid();
  const Table a = testing::McCoolProductTable(g);
  const Table b = OtherMaterial(g);
  for (FactorParam param : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    FactorOptions o;
    o.param = param;
    o.resolution = 16;
    FactorSystemCache cache;
    const Factorization ra = Factor(a, o, &cache);
    const Factorization rb = Factor(b, o, &cache);
    EXPECT_FALSE(ra.stats.system_reused);
    EXPECT_TRUE(rb.stats.system_reused);
    EXPECT_EQ(cache.size(), 1u);
    const Factorization fresh = Factor(b, o);  // private cache: built from scratch
    EXPECT_FALSE(fresh.stats.system_reused);
    EXPECT_EQ(rb.brdf.p(), fresh.brdf.p());  // same matrix, same factorization: bit equal
    EXPECT_EQ(rb.brdf.q(), fresh.brdf.q());
  }
}

TEST(FactorSystem, CacheKeysOnEverythingTheMatrixDependsOn) {
  const Grid g = testing::SmallGrid();
  Table t = testing::McCoolProductTable(g);
  FactorSystemCache cache(16);
  FactorOptions o;
  o.resolution = 16;
  bool hit = true;
  cache.GetOrBuild(g, t.valid, o, &hit);
  EXPECT_FALSE(hit);
  cache.GetOrBuild(g, t.valid, o, &hit);
  EXPECT_TRUE(hit);
  auto miss = [&](FactorOptions changed, const std::vector<std::uint8_t>& mask) {
    bool h = true;
    cache.GetOrBuild(g, mask, changed, &h);
    return !h;
  };
  FactorOptions x = o;
  x.lambda *= 2;
  EXPECT_TRUE(miss(x, t.valid));
  x = o;
  x.resolution = 20;
  EXPECT_TRUE(miss(x, t.valid));
  x = o;
  x.param = FactorParam::kHalfDiff;
  EXPECT_TRUE(miss(x, t.valid));
  x = o;
  x.weighting = FactorWeighting::kCell;
  EXPECT_TRUE(miss(x, t.valid));
  x = o;
  x.max_theta = 1.2;
  EXPECT_TRUE(miss(x, t.valid));
  std::vector<std::uint8_t> mask = t.valid;
  mask[mask.size() / 2] ^= 1;
  EXPECT_TRUE(miss(o, mask));
  EXPECT_EQ(cache.size(), 7u);
}

// Cells with a zero channel are masked for that material. With few of them the cached system
// is corrected (PCG); with many a system without them is built. Both must equal factoring a
// table in which those cells are invalid.
void CheckZeroCells(std::size_t every, bool expect_rebuild) {
  const Grid g = testing::SmallGrid();
  Table t = testing::McCoolProductTable(g);
  Table holes = t;
  std::size_t zeroed = 0;
  for (std::size_t idx = 0; idx < g.NumCells(); idx += every) {
    if (!t.valid[idx]) continue;
    t.Value(idx)[1] = 0;  // one channel zero: the whole cell leaves log space
    holes.valid[idx] = 0;
    ++zeroed;
  }
  FactorOptions o;
  o.resolution = 16;
  FactorSystemCache cache;
  Factor(testing::McCoolProductTable(g), o, &cache);  // warm the cache with the full mask
  const Factorization r = Factor(t, o, &cache);
  EXPECT_EQ(r.stats.nonpositive_cells, zeroed);
  EXPECT_EQ(r.stats.system_rebuilt, expect_rebuild);
  if (!expect_rebuild) {
    EXPECT_TRUE(r.stats.system_reused);
    EXPECT_GT(r.stats.pcg_iterations, 0);
  }
  const Factorization ref = Factor(holes, o);
  EXPECT_LE(MaxLogDiff(r.brdf.p(), ref.brdf.p()), 1e-6);
  EXPECT_LE(MaxLogDiff(r.brdf.q(), ref.brdf.q()), 1e-6);
}

TEST(FactorSystem, ResidualFromNormalEquationsMatchesExplicitResidual) {
  // FactorSolveInfo::weighted_rms uses |y - Ax|_W^2 = y^T W y - x^T b - |Lx|^2; an explicit
  // pass over the rows must agree, with and without dropped rows (low-rank correction).
  const Grid g = testing::SmallGrid();
  const Table t = OtherMaterial(g);  // not a product: a residual well above rounding
  FactorOptions o;
  o.resolution = 16;
  for (FactorParam param : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    o.param = param;
    const auto s = FactorSystem::Build(g, t.valid, o);
    RowValues y(s->num_rows(), 3);
    for (std::size_t r = 0; r < s->num_rows(); ++r) {
      for (int c = 0; c < 3; ++c) y(r, c) = std::log(t.Value(s->row_cells()[r])[c]);
    }
    for (const std::vector<std::uint32_t>& removed :
         {std::vector<std::uint32_t>{}, std::vector<std::uint32_t>{3, 50, 700, 1234}}) {
      Eigen::MatrixX3d x;
      FactorSolveInfo info;
      ASSERT_TRUE(s->Solve(y, removed, &x, &info));
      const double explicit_rms = s->WeightedRms(y, removed, x);
      EXPECT_GT(explicit_rms, 1e-3);
      EXPECT_NEAR(info.weighted_rms, explicit_rms, 1e-6 * explicit_rms);
    }
  }
}

TEST(FactorSystem, FewZeroCellsUseTheLowRankCorrection) {
  CheckZeroCells(997, false);
}

TEST(FactorSystem, ManyZeroCellsRebuild) {
  CheckZeroCells(3, true);
}

TEST(FactorSystem, BadOptionsAndEmptyTablesAreInputErrors) {
  const Grid g = testing::SmallGrid();
  const Table t = testing::McCoolProductTable(g);
  FactorOptions o;
  o.resolution = 16;
  FactorOptions bad = o;
  bad.lambda = 0;
  EXPECT_THROW(Factor(t, bad), InputError);
  bad = o;
  bad.resolution = 2;
  EXPECT_THROW(Factor(t, bad), InputError);
  bad = o;
  bad.max_theta = 2;
  EXPECT_THROW(Factor(t, bad), InputError);
  EXPECT_THROW(Factor(Table::Empty(g), o), InputError);
  Table zeros = t;
  for (double& v : zeros.rgb) v = 0;
  EXPECT_THROW(Factor(zeros, o), InputError);
}

}  // namespace
}  // namespace brdfit
