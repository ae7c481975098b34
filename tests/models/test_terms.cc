// Microfacet term families (models/microfacet/) against the papers' and tutorials' printed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "models/microfacet/fresnel.h"
#include "models/microfacet/masking.h"
#include "models/microfacet/ndf.h"
#include "tests/models/oracles.h"
#include "tests/models/variant_terms.h"

namespace brdfit {
namespace {

double RelDiff(double a, double b) {
  const double s = std::max(std::abs(a), std::abs(b));
  return s == 0 ? 0 : std::abs(a - b) / s;
}

std::vector<Geometry> Geometries() {
  std::vector<Geometry> out;
  for (double ti : {0.0, 0.1, 0.6, 1.2, 89.9 * kPi / 180})
    for (double to : {0.05, 0.6, 1.4})
      for (double dphi : {0.0, 1.0, kPi}) {
        out.push_back(MakeGeometry(FromSpherical(ti, 0.3), FromSpherical(to, 0.3 + dphi)));
      }
  return out;
}

TEST(Ndf, GgxAndBeckmannMatchTanForms) {
  for (double alpha : {1e-4, 0.01, 0.3, 1.0})
    for (double th : {0.0, 1e-5, 0.01, 0.5, 1.5}) {
      const Vec3 h = FromSpherical(th, 0.7);
      const double s2 = h.x * h.x + h.y * h.y;
      EXPECT_LE(RelDiff(DGgx(alpha, h.z, s2), oracle::DGgx(alpha, th)), 1e-13)
          << alpha << " " << th;
      const double want = oracle::DBeckmann(alpha, th);
      if (want > 1e-280) {
        EXPECT_LE(RelDiff(DBeckmann(alpha, h.z, s2), want), 1e-12) << alpha << " " << th;
      }
    }
}

TEST(Ndf, BlinnPhongNdfIsWalterPhongDistribution) {
  for (double n : {1.0, 20.0, 1e4})
    for (double th : {0.0, 0.003, 0.2, 1.0}) {
      const double s = std::sin(th);
      EXPECT_LE(RelDiff(DBlinnPhong(n, std::cos(th), s * s),
                        (n + 2) / (2 * kPi) * std::pow(std::cos(th), n)),
                1e-12);
    }
}

TEST(Masking, SmithLambdaMatchesWalterG1) {
  for (double alpha : {1e-4, 0.05, 0.5, 1.0})
    for (double t : {0.0, 0.01, 0.5, 1.2, 1.5, 89.9 * kPi / 180}) {
      const Vec3 v = FromSpherical(t, 1.1);
      EXPECT_LE(RelDiff(1.0 / (1.0 + GgxNdf::Lambda(alpha, v)), oracle::G1Ggx(alpha, t)), 1e-14);
      EXPECT_LE(RelDiff(G1SmithGgx(alpha, v), oracle::G1Ggx(alpha, t)), 1e-14);
      EXPECT_LE(RelDiff(1.0 / (1.0 + BeckmannNdf::Lambda(alpha, v)), oracle::G1Beckmann(alpha, t)),
                1e-13)
          << alpha << " " << t;
    }
}

// Frostbite's V_SmithGGXCorrelated (Lagarde & de Rousiers 2014, Listing 2, code form) is
// G2_hc / (4 cos_i cos_o).
TEST(Masking, HeightCorrelatedMatchesFrostbiteVisibility) {
  for (double alpha : {0.01, 0.2, 1.0})
    for (const Geometry& g : Geometries()) {
      const double a2 = alpha * alpha, nl = g.cos_i, nv = g.cos_o;
      const double lv = nl * std::sqrt((-nv * a2 + nv) * nv + a2);
      const double ll = nv * std::sqrt((-nl * a2 + nl) * nl + a2);
      const double vis = 0.5 / (lv + ll);
      const double got = SmithHeightCorrelated::G<GgxNdf>(alpha, g) / (4 * nl * nv);
      EXPECT_LE(RelDiff(got, vis), 1e-12);
    }
}

// The printed forms of the Schlick k choices, written with the sources' "roughness" r
// (alpha = r^2; docs/models.md).
TEST(Masking, SchlickKChoicesMatchSeeds) {
  for (double r : {0.01, 0.3, 0.7, 1.0}) {
    const double alpha = r * r;
    const double a = r * r;  // mebiusbox 2018 code: a = roughness * roughness; k = a * a * 0.5
    EXPECT_DOUBLE_EQ(SchlickKValue(SchlickK::kAlphaSqHalf, alpha), a * a * 0.5);
    EXPECT_DOUBLE_EQ(SchlickKValue(SchlickK::kAlphaHalf, alpha), alpha / 2);  // Karis 2013
    EXPECT_NEAR(SchlickKValue(SchlickK::kUe4, alpha), (r + 1) * (r + 1) * 0.125, 1e-15);
    const double m = alpha;  // Schlick 1994: k = sqrt(2 m^2 / pi), m = Beckmann RMS slope
    EXPECT_NEAR(SchlickKValue(SchlickK::kBeckmannFit, alpha), std::sqrt(2 * m * m / kPi), 1e-15);
  }
  const Geometry g = MakeGeometry(FromSpherical(0.4, 0), FromSpherical(1.0, 2.0));
  const double k = (std::sqrt(0.3) + 1) * (std::sqrt(0.3) + 1) / 8;
  const double want = g.cos_i / (g.cos_i * (1 - k) + k) * g.cos_o / (g.cos_o * (1 - k) + k);
  EXPECT_NEAR((SchlickSmith<SchlickK::kUe4>::G<GgxNdf>(0.3, g)), want, 1e-15);
}

// The visibility family of course notes (Tokoi) and the URP workshop 2025's V-groove code.
TEST(Masking, VisibilityTermsMatchSeedForms) {
  for (const Geometry& g : Geometries()) {
    const double cc = g.cos_i * g.cos_o;
    const double ldotv = Dot(g.wi, g.wo);
    EXPECT_LE(RelDiff(KelemenG::G<GgxNdf>(0.1, g) / cc, 2 / (1 + ldotv)), 1e-12);
    EXPECT_LE(RelDiff(NeumannG::G<GgxNdf>(0.1, g) / cc, 1 / std::max(g.cos_i, g.cos_o)), 1e-15);
    EXPECT_LE(RelDiff(AshikhminPremozeG::G<GgxNdf>(0.1, g) / cc,
                      1 / (g.cos_i + g.cos_o - g.cos_i * g.cos_o)),
              1e-15);
    EXPECT_DOUBLE_EQ(ImplicitG::G<GgxNdf>(0.1, g), cc);
    EXPECT_DOUBLE_EQ(NoMasking::G<GgxNdf>(0.1, g), 1.0);
    const double hn = g.cos_h, vn = g.cos_o, ln = g.cos_i;
    const double vh = Dot(g.wo, g.h), lh = Dot(g.wi, g.h);
    const double urp = std::min(1.0, 2 * std::min(hn * vn / vh, hn * ln / lh));
    EXPECT_LE(RelDiff(VGroove::G<GgxNdf>(0.1, g), urp), 1e-14);
  }
}

TEST(Fresnel, SchlickEndpointsAndF90) {
  for (double f0 : {0.0, 0.04, 0.9}) {
    EXPECT_DOUBLE_EQ(FSchlick(f0, 1.0), f0);
    EXPECT_DOUBLE_EQ(FSchlick(f0, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(FFarCry3(f0, 0.0), 1.0);
    EXPECT_NEAR(FSchlickF90(f0, 1.0, 0.37), FSchlick(f0, 0.37), 1e-16);
    EXPECT_DOUBLE_EQ(FSchlickF90(f0, 0.5, 0.0), 0.5);
  }
}

TEST(Fresnel, DielectricMatchesSnellForm) {
  for (double eta : {1.01, 1.33, 1.5, 2.4, 4.0})
    for (double theta : {0.0, 0.2, 0.8, 1.3, 1.57}) {
      EXPECT_LE(RelDiff(FDielectric(eta, std::cos(theta)), oracle::FDielectricSnell(eta, theta)),
                1e-12)
          << eta << " " << theta;
    }
  // F(0) = ((eta - 1) / (eta + 1))^2 and the F0 <-> IOR round trip.
  for (double eta : {1.2, 1.5, 3.0}) {
    EXPECT_NEAR(FDielectric(eta, 1.0), F0FromIor(eta), 1e-15);
    EXPECT_NEAR(IorFromF0(F0FromIor(eta)), eta, 1e-12);
  }
}

TEST(Fresnel, ConductorMatchesComplexFresnel) {
  // (eta, k) of gold, aluminium and copper at ~550 nm, and a dielectric (k = 0).
  const std::vector<std::pair<double, double>> nk = {
      {0.47, 2.40}, {0.96, 6.69}, {1.02, 2.58}, {1.5, 0.0}};
  for (auto [eta, k] : nk)
    for (double theta : {0.0, 0.3, 0.9, 1.4, 1.5707}) {
      EXPECT_LE(
          RelDiff(FConductor(eta, k, std::cos(theta)), oracle::FConductorComplex(eta, k, theta)),
          1e-12)
          << eta << " " << k << " " << theta;
    }
}

}  // namespace
}  // namespace brdfit
