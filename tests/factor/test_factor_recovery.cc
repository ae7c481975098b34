// Parameter recovery: tables that are exact products of known smooth factors are factored back
// into those factors (up to the gauge), and tables with holes give finite, smoothly filled
// textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "factor/factor.h"
#include "factor/factor_metrics.h"
#include "models/ggx.h"
#include "tests/factor/factor_test_util.h"
#include "tests/models/variant_terms.h"

namespace brdfit {
namespace {

using testing::Rgb;

// Independent log-RMSE oracle: every valid cell, evaluated at a random half-vector azimuth
// (the factors must be isotropic), channels pooled.
double LogRmseRandomPhiH(const Table& t, const FactoredBrdf& brdf, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> phi(0, 2 * kPi);
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t idx = 0; idx < t.grid.NumCells(); ++idx) {
    if (!t.valid[idx]) continue;
    Vec3 wi, wo;
    FromHalfDiff(t.grid.CellCentre(idx), phi(rng), &wi, &wo);
    const auto f = brdf.Eval(wi, wo);
    for (int c = 0; c < 3; ++c) {
      const double d = std::log(f[c] / t.Value(idx)[c]);
      sum += d * d;
      ++n;
    }
  }
  return std::sqrt(sum / n);
}

// Differences log(texture) - log(truth) at the texel centres of a disk texture (inside the
// disk), per channel: returns {mean, max |difference - mean|}.
struct GaugeFit {
  Rgb offset{};
  double max_dev = 0;
};

template <class Truth>
GaugeFit CompareDisk(const RgbImage& img, FactorMap map, Truth truth, double min_theta,
                     double max_theta) {
  const int n = img.width;
  GaugeFit g;
  std::vector<std::array<double, 3>> diffs;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double rho = std::hypot(DiskTexelCentre(i, n), DiskTexelCentre(j, n));
      if (rho > 1) continue;
      const double theta = DiskTheta(map, rho);
      if (theta < min_theta || theta > max_theta) continue;
      const Rgb tr = truth(theta);
      std::array<double, 3> d;
      for (int c = 0; c < 3; ++c) d[c] = std::log(img.At(i, j)[c]) - std::log(tr[c]);
      diffs.push_back(d);
    }
  }
  for (const auto& d : diffs)
    for (int c = 0; c < 3; ++c) g.offset[c] += d[c] / diffs.size();
  for (const auto& d : diffs)
    for (int c = 0; c < 3; ++c) g.max_dev = std::max(g.max_dev, std::abs(d[c] - g.offset[c]));
  return g;
}

// Noise-free products: a small lambda, so the bias of the smoothness term (O(lambda)) is far
// below the tolerances. What remains is the bilinear interpolation between texel centres of
// the float32 textures, O(texel^2): 128^2 textures put it below 1e-3 for these factors.
constexpr double kExactLambda = 1e-9;
// Coverage of testing::SmallGrid(): first theta_h cell centre, and the outermost ring that
// cell centres still reach.
constexpr double kFirstThetaH = 0.5 / 24 * kPi / 2;
constexpr double kLimit = 85 * kPi / 180;

TEST(FactorRecovery, McCoolProductIsRecovered) {
  const Table t = testing::McCoolProductTable(testing::SmallGrid());
  FactorOptions o;
  o.param = FactorParam::kMcCool;
  o.resolution = 128;
  o.lambda = kExactLambda;
  const Factorization r = Factor(t, o);
  EXPECT_EQ(r.stats.nonpositive_cells, 0u);
  EXPECT_EQ(r.stats.usable_cells, t.CountValid());
  EXPECT_LE(r.stats.solve_log_rms, 1e-4);  // the profiles themselves fit ~exactly

  const double rmse = LogRmseRandomPhiH(t, r.brdf, 1);
  EXPECT_LE(rmse, 1e-3);
  EXPECT_NEAR(FactorLnRatioRmse(t, r.brdf), rmse, 2e-4);  // the phi_h = 0 evaluation agrees

  // Textures equal to the truth up to the gauge (log p + c, log q - 2c) at texel centres
  // wherever cells reach: theta_h from the first bin centre (1.875 deg), theta up to 85 deg.
  const GaugeFit gp = CompareDisk(r.brdf.p(), FactorMap::kDiskParabolic, testing::TrueP, 0, kLimit);
  const GaugeFit gq =
      CompareDisk(r.brdf.q(), FactorMap::kDiskSqrtTheta, testing::TrueQh, kFirstThetaH, kLimit);
  EXPECT_LE(gp.max_dev, 1e-3);
  EXPECT_LE(gq.max_dev, 1e-3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(gq.offset[c], -2 * gp.offset[c], 1e-3) << "channel " << c;
    // The gauge pins p(normal) = 1, as the truth: the offset itself is ~0.
    EXPECT_NEAR(gp.offset[c], 0, 1e-3);
  }
}

TEST(FactorRecovery, RemainingErrorIsTextureInterpolation) {
  // Halving the texel size divides the error by ~4 (bilinear interpolation is second order):
  // the solver itself adds nothing measurable.
  const Table t = testing::McCoolProductTable(testing::SmallGrid());
  FactorOptions o;
  o.lambda = kExactLambda;
  o.resolution = 32;
  const double e32 = FactorLnRatioRmse(t, Factor(t, o).brdf);
  o.resolution = 64;
  const double e64 = FactorLnRatioRmse(t, Factor(t, o).brdf);
  EXPECT_GT(e32 / e64, 3.0);
  EXPECT_LT(e32 / e64, 5.0);
}

TEST(FactorRecovery, HalfDiffProductIsRecovered) {
  const Table t = testing::HalfDiffProductTable(testing::SmallGrid());
  FactorOptions o;
  o.param = FactorParam::kHalfDiff;
  o.resolution = 128;
  o.lambda = kExactLambda;
  const Factorization r = Factor(t, o);
  EXPECT_LE(r.stats.solve_log_rms, 1e-4);
  EXPECT_LE(LogRmseRandomPhiH(t, r.brdf, 2), 1e-3);

  const GaugeFit gp =
      CompareDisk(r.brdf.p(), FactorMap::kDiskSqrtTheta, testing::TrueQh, kFirstThetaH, kLimit);
  EXPECT_LE(gp.max_dev, 1e-3);
  // q texels: log q_texel - log q_true = -offset_p (gauge log p + c, log q - c).
  const RgbImage& q = r.brdf.q();
  double max_dev = 0;
  for (int j = 0; j < q.height; ++j) {
    for (int i = 0; i < q.width; ++i) {
      const double td = ThetaDOfColumn(i, q.width), pd = PhiDOfRow(j, q.height);
      if (td > kLimit) continue;
      const Rgb tr = testing::TrueQd(td, pd);
      for (int c = 0; c < 3; ++c) {
        max_dev =
            std::max(max_dev, std::abs(std::log(q.At(i, j)[c]) - std::log(tr[c]) + gp.offset[c]));
      }
    }
  }
  EXPECT_LE(max_dev, 1e-3);
}

TEST(FactorRecovery, PureGgxIsExactlyRankOneOnTheMerlGrid) {
  // Walter et al. 2007, eq. 20 with separable Smith G (eq. 34): without a diffuse term,
  //   f = ks D(h) G1(wi) G1(wo) / (4 cos_i cos_o) = p(wi) q(wh) p(wo),
  //   p(w) = G1(w) / cos(theta)  (p(normal) = 1: the gauge),  q(h) = ks D(h) / 4,
  // exactly McCool's form. On the full MERL grid the factors come back up to the texture
  // interpolation of the peak of D.
  const double alpha = 0.3;
  const double ks[3] = {0.5, 0.8, 1.2};
  const Table t =
      testing::Tabulate(Grid::Merl(), [&](const Vec3& wi, const Vec3& wo, const HalfDiffAngles&) {
        const double params[4] = {ks[0], ks[1], ks[2], alpha};
        double rgb[3];
        Ggx::Eval(params, MakeGeometry(wi, wo), rgb);
        return Rgb{rgb[0], rgb[1], rgb[2]};
      });
  FactorOptions o;
  o.resolution = 128;
  o.lambda = kExactLambda;
  const Factorization r = Factor(t, o);
  EXPECT_LE(r.stats.solve_log_rms, 2e-3);
  EXPECT_LE(FactorLnRatioRmse(t, r.brdf, 80 * kPi / 180), 5e-3);
  auto true_p = [&](double theta) {
    const double g = G1SmithGgx(alpha, FromSpherical(theta, 0)) / std::cos(theta);
    return Rgb{g, g, g};
  };
  auto true_q = [&](double theta_h) {
    const double d = DGgx(alpha, std::cos(theta_h), std::sin(theta_h) * std::sin(theta_h)) / 4;
    return Rgb{ks[0] * d, ks[1] * d, ks[2] * d};
  };
  const double lim = 80 * kPi / 180;
  const GaugeFit gp = CompareDisk(r.brdf.p(), FactorMap::kDiskParabolic, true_p, 0, lim);
  const GaugeFit gq = CompareDisk(r.brdf.q(), FactorMap::kDiskSqrtTheta, true_q, 0, lim);
  // Texel centres sample the piecewise linear profiles (128 knots): what remains is their
  // linear interpolation across the curvature of ln D (measured 3.6e-3 at the peak).
  EXPECT_LE(gp.max_dev, 5e-3);
  EXPECT_LE(gq.max_dev, 5e-3);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(gp.offset[c], 0, 1e-3);  // p(normal) = 1 already
}

TEST(FactorRecovery, HolesGiveFiniteSmoothTextures) {
  const Table full = testing::McCoolProductTable(testing::SmallGrid());
  Table t = full;
  // A band of theta_h with no data at all, plus 40 % random holes elsewhere.
  std::mt19937 rng(7);
  std::bernoulli_distribution drop(0.4);
  std::size_t dropped = 0;
  for (std::size_t idx = 0; idx < t.grid.NumCells(); ++idx) {
    int ih, id, ip;
    t.grid.Unindex(idx, &ih, &id, &ip);
    if (t.valid[idx] && ((ih >= 6 && ih <= 9) || drop(rng))) {
      t.valid[idx] = 0;
      t.Value(idx)[0] = std::nan("");  // masked values are never read
      ++dropped;
    }
  }
  ASSERT_GT(dropped, 0u);
  FactorOptions o;
  o.resolution = 64;
  o.lambda = kExactLambda;
  const Factorization r = Factor(t, o);
  for (const RgbImage* img : {&r.brdf.p(), &r.brdf.q()}) {
    for (float v : img->rgb) ASSERT_TRUE(std::isfinite(v) && v > 0);
  }
  // theta_h bins 6..9 of 24 (22.5..37.5 deg) are empty: their texels are filled by the
  // smoothness term (a cubic spline through the neighbouring data). The truth is smooth, so
  // the fill stays close to it...
  const GaugeFit gq =
      CompareDisk(r.brdf.q(), FactorMap::kDiskSqrtTheta, testing::TrueQh, kFirstThetaH, kLimit);
  EXPECT_LE(gq.max_dev, 5e-3);
  // ...and predicts the cells that were removed about as well as the full-data factorization.
  const double e_full = FactorLnRatioRmse(full, Factor(full, o).brdf);
  EXPECT_LE(FactorLnRatioRmse(full, r.brdf), e_full + 1e-3);
}

TEST(FactorRecovery, HalfDiffHolesAreFilledSmoothly) {
  Table t = testing::HalfDiffProductTable(testing::SmallGrid());
  // No data above theta_d = 60 deg: a third of the q texture is extrapolated.
  for (std::size_t idx = 0; idx < t.grid.NumCells(); ++idx) {
    if (t.grid.CellCentre(idx).theta_d > kPi / 3) t.valid[idx] = 0;
  }
  FactorOptions o;
  o.param = FactorParam::kHalfDiff;
  o.resolution = 32;
  o.lambda = kExactLambda;
  const Factorization r = Factor(t, o);
  const RgbImage& q = r.brdf.q();
  for (float v : q.rgb) ASSERT_TRUE(std::isfinite(v) && v > 0);
  // Smooth fill: second differences along theta_d in the empty region are no larger than in
  // the data region (the thin-plate fill continues the data linearly in theta_d).
  double max_data = 0, max_fill = 0;
  for (int j = 0; j < q.height; ++j) {
    for (int i = 1; i + 1 < q.width; ++i) {
      for (int c = 0; c < 3; ++c) {
        const double d2 = std::abs(std::log(q.At(i - 1, j)[c]) - 2 * std::log(q.At(i, j)[c]) +
                                   std::log(q.At(i + 1, j)[c]));
        double& m = ThetaDOfColumn(i, q.width) > kPi / 3 + 0.1 ? max_fill : max_data;
        m = std::max(m, d2);
      }
    }
  }
  EXPECT_LE(max_fill, max_data);
}

TEST(FactorRecovery, ResultDoesNotDependOnBinning) {
  // Solid-angle weights make the data term a mean over (wi, wo): the same product tabulated on
  // a linear and on a MERL-style sqrt theta_h grid factors to the same textures (where both
  // grids have cells).
  Grid a = testing::SmallGrid();
  Grid b = a;
  b.theta_h_mapping = ThetaHMapping::kSqrt;
  b.n_theta_h = 32;
  FactorOptions o;
  o.resolution = 64;
  o.lambda = kExactLambda;
  const Factorization ra = Factor(testing::McCoolProductTable(a), o);
  const Factorization rb = Factor(testing::McCoolProductTable(b), o);
  // Texel against texel over the common coverage, up to a constant (the gauge pins p at the
  // normal, which both grids only reach by extrapolation).
  const RgbImage& qa = ra.brdf.q();
  const RgbImage& qb = rb.brdf.q();
  std::vector<double> d;
  for (int j = 0; j < qa.height; ++j) {
    for (int i = 0; i < qa.width; ++i) {
      const double rho = std::hypot(DiskTexelCentre(i, qa.width), DiskTexelCentre(j, qa.width));
      const double theta = DiskTheta(FactorMap::kDiskSqrtTheta, rho);
      if (rho > 1 || theta < kFirstThetaH || theta > kLimit) continue;
      for (int c = 0; c < 3; ++c) d.push_back(std::log(double{qa.At(i, j)[c]} / qb.At(i, j)[c]));
    }
  }
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  EXPECT_LE(*hi - *lo, 4e-3);
}

}  // namespace
}  // namespace brdfit
