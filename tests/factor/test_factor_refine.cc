// Refinement, diffuse + products and sums of products (factor/factor_refine.h): recovery of
// tables that lie inside the form, recovery of Lambert + separable-microfacet tables up to
// texture interpolation, and monotone improvement of the relative loss.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "factor/factor.h"
#include "factor/factor_metrics.h"
#include "factor/factor_refine.h"
#include "tests/factor/factor_test_util.h"

namespace brdfit {
namespace {

using testing::Rgb;

// Knot values of smooth log-profiles in the system's layout (p then q), per channel: a table
// built from them through the system's own rows is exactly inside the factored form.
Eigen::MatrixX3d TrueLogTexels(const FactorSystem& sys, double scale) {
  const int np = sys.num_p(), nq = sys.num_q();
  Eigen::MatrixX3d x(np + nq, 3);
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < np; ++i) {
      const double t = static_cast<double>(i) / (np - 1);
      x(i, c) = scale * (0.3 + 0.2 * c) * t * t;  // log p, 0 at the normal (the gauge)
    }
    for (int i = 0; i < nq; ++i) {
      const double t = static_cast<double>(i % np) / (np - 1);
      x(np + i, c) = std::log(0.8 - 0.2 * c) - scale * (6.0 - c) * t * t;  // a highlight
    }
  }
  return x;
}

// f = d + sum_k exp(a_r^T x_k) on every row of the system; other cells invalid.
Table TableInForm(const FactorSystem& sys, const Grid& grid, const Rgb& d,
                  const std::vector<Eigen::MatrixX3d>& terms) {
  Table t = Table::Empty(grid);
  for (std::size_t r = 0; r < sys.num_rows(); ++r) {
    const std::uint32_t cell = sys.row_cells()[r];
    for (int c = 0; c < 3; ++c) {
      double v = d[c];
      for (const auto& x : terms) {
        double lg = 0;
        for (int j = sys.row_start()[r]; j < sys.row_start()[r + 1]; ++j) {
          lg += sys.vals()[j] * x(sys.cols()[j], c);
        }
        v += std::exp(lg);
      }
      t.Value(cell)[c] = v;
    }
    t.valid[cell] = 1;
  }
  return t;
}

// max |f_model / f_table - 1| over the system's rows, from the refined log-texels.
double MaxRelativeError(const FactorSystem& sys, const Table& t, const RefineResult& r) {
  double worst = 0;
  for (std::size_t row = 0; row < sys.num_rows(); ++row) {
    const double* m = t.Value(sys.row_cells()[row]);
    for (int c = 0; c < 3; ++c) {
      double v = r.diffuse[c];
      for (const auto& x : r.terms) {
        double lg = 0;
        for (int j = sys.row_start()[row]; j < sys.row_start()[row + 1]; ++j) {
          lg += sys.vals()[j] * x(sys.cols()[j], c);
        }
        v += std::exp(lg);
      }
      worst = std::max(worst, std::abs(v / m[c] - 1));
    }
  }
  return worst;
}

Eigen::MatrixX3d LogLinearStart(const FactorSystem& sys, const Table& t) {
  RowValues y(static_cast<Eigen::Index>(sys.num_rows()), 3);
  for (std::size_t r = 0; r < sys.num_rows(); ++r) {
    for (int c = 0; c < 3; ++c) y(r, c) = std::log(t.Value(sys.row_cells()[r])[c]);
  }
  Eigen::MatrixX3d x;
  FactorSolveInfo info;
  EXPECT_TRUE(sys.Solve(y, {}, &x, &info));
  return x;
}

class DiffusePlusProduct : public ::testing::TestWithParam<FactorParam> {};

TEST_P(DiffusePlusProduct, TableInsideTheFormIsRecoveredTo1e6) {
  const Grid grid = testing::SmallGrid();
  FactorSystemOptions so;
  so.param = GetParam();
  so.resolution = 16;
  so.lambda = 1e-20;  // the smoothness term biases by O(lambda): off, the form itself
  auto sys = FactorSystem::Build(grid, std::vector<std::uint8_t>(grid.NumCells(), 1), so);
  const Rgb d{0.05, 0.12, 0.2};  // kd = pi d: a Lambert body under the lobe
  const Table t = TableInForm(*sys, grid, d, {TrueLogTexels(*sys, 1.0)});

  RefineOptions ro;
  ro.diffuse = true;
  ro.max_iterations = 200;
  ro.tolerance = 1e-15;
  ro.max_rows = sys->num_rows();
  const RefineResult r = RefineFactorization(*sys, t, LogLinearStart(*sys, t), {}, ro);
  ASSERT_EQ(r.terms.size(), 1u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.diffuse[c], d[c], 1e-6 * d[c]) << "channel " << c;
  EXPECT_LE(MaxRelativeError(*sys, t, r), 1e-6);
  EXPECT_LT(r.rel_rms, 1e-6);
  EXPECT_GT(r.rel_rms_start, 1e-2);  // the log-linear start cannot express d
}

INSTANTIATE_TEST_SUITE_P(Params, DiffusePlusProduct,
                         ::testing::Values(FactorParam::kMcCool, FactorParam::kHalfDiff));

TEST(FactorRefine, LambertPlusSeparableMicrofacetThroughFactor) {
  // A physical table, not built from the knots: kd / pi + p(wi) q(wh) p(wo) with the smooth
  // factors of the recovery tests. What remains is the textures' bilinear interpolation
  // (FactorRecovery: <= 1e-3 in ln at 128^2), within which the lobe's tail and d trade off:
  // d comes back to 5 %.
  const Rgb d{0.04, 0.08, 0.15};
  const Table t = testing::Tabulate(testing::SmallGrid(), [&](const Vec3& wi, const Vec3& wo,
                                                              const HalfDiffAngles& a) {
    const Rgb pi = testing::TrueP(testing::ThetaOf(wi)), po = testing::TrueP(testing::ThetaOf(wo));
    const Rgb q = testing::TrueQh(a.theta_h);
    return Rgb{d[0] + pi[0] * q[0] * po[0], d[1] + pi[1] * q[1] * po[1],
               d[2] + pi[2] * q[2] * po[2]};
  });
  FactorOptions o;
  o.resolution = 128;
  o.lambda = 1e-9;
  o.diffuse = true;
  o.refine_iterations = 100;
  const Factorization with = Factor(t, o);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(with.brdf.diffuse()[c], d[c], 0.05 * d[c]) << "channel " << c;
  EXPECT_LE(FactorLnRatioRmse(t, with.brdf), 2e-3);
  o.diffuse = false;
  const double without = FactorLnRatioRmse(t, Factor(t, o).brdf);
  EXPECT_GT(without, 10 * FactorLnRatioRmse(t, with.brdf));  // rank 1 alone cannot express d
}

TEST(FactorRefine, SecondTermRecoversASumOfTwoProducts) {
  const Grid grid = testing::SmallGrid();
  FactorSystemOptions so;
  so.resolution = 16;
  so.lambda = 1e-12;
  auto sys = FactorSystem::Build(grid, std::vector<std::uint8_t>(grid.NumCells(), 1), so);
  // A broad lobe and a sharp one with a different colour: not a single product.
  Eigen::MatrixX3d sharp = TrueLogTexels(*sys, 4.0);
  sharp.col(0).swap(sharp.col(2));
  const Table t = TableInForm(*sys, grid, {0, 0, 0}, {TrueLogTexels(*sys, 0.5), sharp});

  RefineOptions ro;
  ro.max_rows = sys->num_rows();
  ro.max_iterations = 200;
  const Eigen::MatrixX3d x0 = LogLinearStart(*sys, t);
  const RefineResult one = RefineFactorization(*sys, t, x0, {}, ro);
  ro.rank = 2;
  const RefineResult two = RefineFactorization(*sys, t, x0, {}, ro);
  ASSERT_EQ(two.terms.size(), 2u);
  EXPECT_LE(one.rel_rms, one.rel_rms_start);
  EXPECT_LT(two.rel_rms, 0.05 * one.rel_rms);
  EXPECT_LT(two.rel_rms, 1e-3);
}

TEST(FactorRefine, RefinementNeverIncreasesTheRelativeLoss) {
  // Rank 1, no diffuse: the log-linear solution is the start, LM only accepts descents of its
  // objective (relative loss + smoothness); the relative loss alone may trade a little.
  for (FactorParam param : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    const Table t = testing::McCoolProductTable(testing::SmallGrid());
    FactorOptions o;
    o.param = param;
    o.resolution = 16;
    o.refine = true;
    auto sys = FactorSystem::Build(t.grid, t.valid, o);
    const RefineResult rr = RefineFactorization(*sys, t, LogLinearStart(*sys, t), {}, {});
    EXPECT_GT(rr.rows, 0u);
    EXPECT_LE(rr.objective, rr.objective_start) << ToString(param);
    EXPECT_LE(rr.rel_rms, 1.01 * rr.rel_rms_start) << ToString(param);
    const Factorization r = Factor(t, o);
    EXPECT_EQ(r.stats.refine_rows, rr.rows);
    EXPECT_EQ(r.brdf.rank(), 1);
    EXPECT_FALSE(r.brdf.has_diffuse());
  }
}

TEST(FactorRefine, SparseAndDenseStepsAgree) {
  // The sparse LDL^T path (halfdiff at full resolution) solves the same normal equations as
  // the dense one: forced on a small problem, both end at the same point.
  const Table t = testing::HalfDiffProductTable(testing::SmallGrid());
  FactorSystemOptions so;
  so.param = FactorParam::kHalfDiff;
  so.resolution = 12;
  auto sys = FactorSystem::Build(t.grid, t.valid, so);
  RefineOptions ro;
  ro.diffuse = true;
  ro.rank = 2;
  const Eigen::MatrixX3d x0 = LogLinearStart(*sys, t);
  const RefineResult dense = RefineFactorization(*sys, t, x0, {}, ro);
  ro.dense_limit = 0;
  const RefineResult sparse = RefineFactorization(*sys, t, x0, {}, ro);
  EXPECT_NEAR(sparse.objective, dense.objective, 1e-9 * dense.objective_start);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sparse.diffuse[c], dense.diffuse[c], 1e-6);
}

TEST(FactorRefine, BadRankIsAnInputError) {
  const Table t = testing::McCoolProductTable(testing::SmallGrid());
  FactorOptions o;
  o.resolution = 8;
  o.rank = 0;
  EXPECT_THROW(Factor(t, o), InputError);
  o.rank = kMaxFactorRank + 1;
  EXPECT_THROW(Factor(t, o), InputError);
}

}  // namespace
}  // namespace brdfit
