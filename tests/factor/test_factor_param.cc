// Texture maps and interpolation weights of the factorization (factor/factor_param.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "factor/factor_param.h"
#include "core/error.h"

namespace brdfit {
namespace {

Vec3 RandomUpper(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  // Uniform in theta and phi: covers the pole and the horizon.
  return FromSpherical(u(rng) * kPi / 2 * 0.999, u(rng) * 2 * kPi);
}

TEST(FactorParam, NamesRoundTripAndBadNamesThrow) {
  for (FactorParam p : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    EXPECT_EQ(FactorParamFromString(ToString(p)), p);
  }
  for (FactorMap m :
       {FactorMap::kDiskParabolic, FactorMap::kDiskSqrtTheta, FactorMap::kThetaDPhiD}) {
    EXPECT_EQ(FromString<FactorMap>(ToString(m)), m);
  }
  EXPECT_THROW(FactorParamFromString("svd"), InputError);
  EXPECT_THROW(FromString<FactorMap>("cube"), InputError);
}

TEST(FactorParam, ParabolicMapIsHeidrichSeidel) {
  // Oracle: the projective form (x, y) / (1 + z) (Heidrich & Seidel 1998), against the
  // polar form rho = tan(theta / 2) used for profiles.
  std::mt19937 rng(1);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 w = RandomUpper(rng);
    double s, t;
    DiskCoords(FactorMap::kDiskParabolic, w, &s, &t);
    EXPECT_NEAR(s, w.x / (1 + w.z), 1e-15);
    EXPECT_NEAR(t, w.y / (1 + w.z), 1e-15);
    const double theta = std::acos(w.z);
    EXPECT_NEAR(std::hypot(s, t), std::tan(theta / 2), 1e-12);
  }
  EXPECT_NEAR(DiskRadius(FactorMap::kDiskParabolic, kPi / 2), 1.0, 1e-15);
}

TEST(FactorParam, DiskMapsInvertAndKeepTheAzimuth) {
  std::mt19937 rng(2);
  for (FactorMap m : {FactorMap::kDiskParabolic, FactorMap::kDiskSqrtTheta}) {
    EXPECT_EQ(DiskRadius(m, 0), 0);
    EXPECT_NEAR(DiskRadius(m, kPi / 2), 1, 1e-15);
    for (int k = 0; k < 1000; ++k) {
      const Vec3 w = RandomUpper(rng);
      double s, t;
      DiskCoords(m, w, &s, &t);
      const double rho = std::hypot(s, t);
      EXPECT_LE(rho, 1 + 1e-15);
      EXPECT_NEAR(DiskTheta(m, rho), std::acos(w.z), 1e-9);
      EXPECT_NEAR(DiskRadius(m, DiskTheta(m, rho)), rho, 1e-12);
      if (rho > 1e-6) {
        EXPECT_NEAR(std::atan2(t, s), std::atan2(w.y, w.x), 1e-9);
      }
    }
  }
  // sqrt-theta: MERL's theta_h warp, theta = (pi/2) rho^2.
  EXPECT_NEAR(DiskTheta(FactorMap::kDiskSqrtTheta, 0.5), kPi / 8, 1e-15);
  double s, t;
  DiskCoords(FactorMap::kDiskSqrtTheta, Vec3{0, 0, 1}, &s, &t);  // pole: no NaN
  EXPECT_EQ(s, 0);
  EXPECT_EQ(t, 0);
}

TEST(FactorParam, BilinearWeightsReproduceBilinearFunctions) {
  // GL_LINEAR semantics: weights are non-negative, sum to 1, and reproduce any function
  // bilinear in the texel coordinates inside the texel-centre box (clamped outside).
  const int w = 7, h = 5;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, w), v(-1, h);
  auto f = [](double x, double y) { return 0.3 + 2 * x - y + 0.5 * x * y; };
  for (int k = 0; k < 500; ++k) {
    const double x = u(rng), y = v(rng);
    const Bilinear b = BilinearWeights(x, y, w, h, false);
    double sum = 0, val = 0;
    for (int c = 0; c < 4; ++c) {
      EXPECT_GE(b.weight[c], 0);
      sum += b.weight[c];
      val += b.weight[c] * f(b.index[c] % w, b.index[c] / w);
    }
    EXPECT_NEAR(sum, 1, 1e-15);
    EXPECT_NEAR(val, f(std::clamp(x, 0.0, w - 1.0), std::clamp(y, 0.0, h - 1.0)), 1e-12);
  }
}

TEST(FactorParam, PhiDWrapsWithPeriodPi) {
  // Row n - 1 and row 0 are neighbours; phi_d and phi_d + pi give the same weights.
  const int n = 8;
  const Bilinear a = ThetaDPhiDLookup(0.3, 0.01, n, n);
  const Bilinear b = ThetaDPhiDLookup(0.3, 0.01 + kPi, n, n);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(a.index[c], b.index[c]);
    EXPECT_NEAR(a.weight[c], b.weight[c], 1e-12);
  }
  // phi_d = 0.01 lies between the centre of row n - 1 (wrapped) and row 0.
  EXPECT_EQ(a.index[0] / n, n - 1);
  EXPECT_EQ(a.index[2] / n, 0);
  // Column centres: theta_d of column i is (i + 1/2)/n * pi/2.
  const Bilinear c = ThetaDPhiDLookup(ThetaDOfColumn(3, n), PhiDOfRow(5, n), n, n);
  double on_texel = 0;
  for (int k = 0; k < 4; ++k) on_texel += c.index[k] == 5 * n + 3 ? c.weight[k] : 0;
  EXPECT_NEAR(on_texel, 1, 1e-12);
}

TEST(FactorParam, ProfileWeightsInterpolateLinearly) {
  const int k = 9;
  for (double rho : {0.0, 0.1, 0.5, 0.999, 1.0, 1.5}) {
    const Linear2 l = ProfileWeights(rho, k);
    const double r = std::min(rho, 1.0);
    EXPECT_NEAR(l.weight[0] + l.weight[1], 1, 1e-15);
    EXPECT_NEAR(l.weight[0] * l.index[0] / (k - 1.0) + l.weight[1] * l.index[1] / (k - 1.0), r,
                1e-15);
  }
}

TEST(FactorParam, SpecsDescribeTheForms) {
  const auto& m = GetFactorParamSpec(FactorParam::kMcCool);
  EXPECT_EQ(m.p.map, FactorMap::kDiskParabolic);
  EXPECT_EQ(m.q.map, FactorMap::kDiskSqrtTheta);
  EXPECT_EQ(m.p_uses, 2);
  const auto& h = GetFactorParamSpec(FactorParam::kHalfDiff);
  EXPECT_EQ(h.q.map, FactorMap::kThetaDPhiD);
  EXPECT_STREQ(h.p.units, "1/sr");
}

}  // namespace
}  // namespace brdfit
