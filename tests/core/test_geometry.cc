#include <gtest/gtest.h>

#include <random>

#include "models/geometry.h"

namespace brdfit {
namespace {

TEST(Geometry, HalfDiffRoundTripRandomDirections) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 wi = FromSpherical(std::acos(u(rng)), 2 * kPi * u(rng));
    const Vec3 wo = FromSpherical(std::acos(u(rng)), 2 * kPi * u(rng));
    const HalfDiffAngles a = ToHalfDiff(wi, wo);
    ASSERT_GE(a.phi_d, 0.0);
    ASSERT_LT(a.phi_d, kPi);
    const Vec3 h = Normalize(wi + wo);
    Vec3 wi2, wo2;
    FromHalfDiff(a, std::atan2(h.y, h.x), &wi2, &wo2);
    // The fold may swap wi and wo (reciprocity); either assignment must match.
    const double direct = Length(wi2 - wi) + Length(wo2 - wo);
    const double swapped = Length(wi2 - wo) + Length(wo2 - wi);
    EXPECT_LT(std::min(direct, swapped), 1e-9) << "k=" << k;
  }
}

TEST(Geometry, ThetaDIsAngleBetweenWiAndHalfVector) {
  const Vec3 wi = FromSpherical(0.7, 0.3), wo = FromSpherical(0.2, 2.9);
  const HalfDiffAngles a = ToHalfDiff(wi, wo);
  const Vec3 h = Normalize(wi + wo);
  EXPECT_NEAR(std::cos(a.theta_d), Dot(wi, h), 1e-12);
  EXPECT_NEAR(std::cos(a.theta_h), h.z, 1e-12);
}

TEST(Geometry, MakeGeometryAvoidsCancellationNearNormal) {
  // theta_h = 1e-9: 1 - cos^2 would lose every digit; the component form keeps them.
  const Geometry g = MakeGeometry(HalfDiffAngles{1e-9, 0.3, 0.5});
  EXPECT_NEAR(g.sin2_h / 1e-18, 1.0, 1e-6);
  EXPECT_NEAR(g.cos_d, std::cos(0.3), 1e-12);
}

TEST(Geometry, ReflectionCosineMatchesExplicitReflection) {
  const Vec3 wi = FromSpherical(0.5, 0.1), wo = FromSpherical(0.6, 3.0);
  const Geometry g = MakeGeometry(wi, wo);
  const Vec3 r = 2.0 * wi.z * Vec3{0, 0, 1} - wi;
  EXPECT_NEAR(g.cos_r, Dot(r, wo), 1e-14);
}

}  // namespace
}  // namespace brdfit
