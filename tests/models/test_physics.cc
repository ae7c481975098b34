// Physical properties of every catalog model: reciprocity, non-negativity, NDF normalization,
// the Smith masking identity, and the white furnace (directional albedo <= 1 for the models
// documented as energy conserving; > 1 somewhere for those documented as not).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "models/microfacet/ndf.h"
#include "models/registry.h"
#include "models/sgd.h"
#include "tests/models/catalog_types.h"
#include "tests/models/oracles.h"
#include "tests/models/param_sets.h"
#include "tests/models/quadrature.h"
#include "tests/models/variant_terms.h"

namespace brdfit {
namespace {

using test::Integrate;
using test::IntegrateSplit;
using test::PolarBreakpoints;

constexpr double kMaxTheta = 89.9 * kPi / 180.0;

double Sample(const ParamSpec& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (s.log_scale) return std::exp(std::log(s.lower) + u(rng) * std::log(s.upper / s.lower));
  return s.lower + u(rng) * (s.upper - s.lower);
}

Vec3 RandomDirection(std::mt19937& rng) {
  std::uniform_real_distribution<double> t(0.0, kMaxTheta), p(0.0, 2 * kPi);
  return FromSpherical(t(rng), p(rng));
}

TEST(Physics, ReciprocityAndNonNegativity) {
  std::mt19937 rng(7);
  for (const ModelInfo& m : AllModels()) {
    double worst = 0;
    for (int k = 0; k < 300; ++k) {
      std::vector<double> p;
      for (const auto& s : m.params) p.push_back(Sample(s, rng));
      const Vec3 wi = RandomDirection(rng), wo = RandomDirection(rng);
      double a[3], b[3];
      m.eval(p.data(), MakeGeometry(wi, wo), a);
      m.eval(p.data(), MakeGeometry(wo, wi), b);
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(a[c]) && a[c] >= 0.0) << m.name << " f = " << a[c];
        const double scale = std::max(a[c], b[c]);
        if (scale > 1e-300) worst = std::max(worst, std::abs(a[c] - b[c]) / scale);
      }
    }
    // wi.h and wo.h are computed separately: reciprocal up to rounding.
    EXPECT_LE(worst, 1e-12) << m.name;
  }
}

// Walter et al. 2007 eq. 4: the projected microfacet area is one.
double NdfNormalization(const std::function<double(double cos, double sin2)>& d) {
  auto integrand = [&](double th) {
    const double s = std::sin(th), c = std::cos(th);
    return 2 * kPi * d(c, s * s) * c * s;
  };
  return IntegrateSplit(integrand, PolarBreakpoints(), 1e-10);
}

TEST(Physics, NdfNormalization) {
  for (double alpha : {0.01, 0.02, 0.05, 0.1, 0.3, 0.6, 1.0}) {
    const double ggx = NdfNormalization([&](double c, double s2) { return DGgx(alpha, c, s2); });
    const double beckmann =
        NdfNormalization([&](double c, double s2) { return DBeckmann(alpha, c, s2); });
    EXPECT_NEAR(ggx, 1.0, 1e-3) << "GGX alpha " << alpha;
    EXPECT_NEAR(beckmann, 1.0, 1e-3) << "Beckmann alpha " << alpha;
  }
  for (double n : {1.0, 10.0, 1e3, 1e5}) {
    const double bp = NdfNormalization([&](double c, double s2) { return DBlinnPhong(n, c, s2); });
    EXPECT_NEAR(bp, 1.0, 1e-3) << "Blinn-Phong n " << n;
  }
}

// Bagher et al. 2012's SGD (models/sgd.h) over its parameter box, and the Taylor polynomial of
// Gamma(s, 1) it is normalized with against the oracle's quadrature.
TEST(Physics, SgdNdfNormalization) {
  for (double s = -1.0; s <= 1.0; s += 0.125) {
    EXPECT_NEAR(UpperGammaAt1(s) / oracle::UpperGammaAt1(s), 1.0, 1e-12) << "s " << s;
  }
  for (double alpha : {1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0})
    for (double p : {0.0, 0.3, 0.8, 1.0, 1.5, 2.0}) {
      const double n = NdfNormalization([&](double c, double s2) { return DSgd(alpha, p, c, s2); });
      EXPECT_NEAR(n, 1.0, 1e-3) << "SGD alpha " << alpha << " p " << p;
    }
}

// Heitz 2014's normalization constraint on the masking function ("the projected area of the
// visible microsurface equals the projected area of the geometric surface"): G1(v) * integral of
// max(0, v.m) D(m) d m = cos theta_v, which holds for the exact Smith Lambda only.
template <class Ndf>
double MaskingIdentity(double alpha, double theta_v) {
  const Vec3 v = FromSpherical(theta_v, 0.0);
  auto inner = [&](double phi) {
    return IntegrateSplit(
        [&](double th) {
          const Vec3 m = FromSpherical(th, phi);
          const double vm = Dot(v, m);
          if (vm <= 0) return 0.0;
          const double s = std::sin(th);
          Geometry g;
          g.h = m;
          g.cos_h = m.z;
          g.sin2_h = s * s;
          return vm * Ndf::D(alpha, g) * s;
        },
        PolarBreakpoints(), 1e-10);
  };
  const double projected = 2 * Integrate(inner, 0.0, kPi, 1e-9);  // symmetric in phi
  return projected / (1.0 + Ndf::Lambda(alpha, v));
}

TEST(Physics, SmithMaskingIdentity) {
  for (double alpha : {0.05, 0.3, 1.0})
    for (double theta : {0.1, 0.7, 1.3, 1.55}) {
      EXPECT_NEAR(MaskingIdentity<GgxNdf>(alpha, theta) / std::cos(theta), 1.0, 1e-5)
          << "GGX alpha " << alpha << " theta " << theta;
      EXPECT_NEAR(MaskingIdentity<BeckmannNdf>(alpha, theta) / std::cos(theta), 1.0, 1e-5)
          << "Beckmann alpha " << alpha << " theta " << theta;
    }
}

// Directional albedo of channel 0: integral of f(wi, wo) cos_o d wo, in half-vector
// coordinates (d wo = 4 (wi.h) d wh) so that every lobe, which peaks at h = n or spreads from
// there, is resolved by the polar breakpoints. With wi = (sin ti, 0, cos ti) and h at
// (th, ph): wo.z = 2 (wi.h) cos th - cos ti = R cos(2 th - b), b = atan2(sin ti cos ph, cos ti),
// and wi.h = R cos(th - b); both are positive exactly for th < (b + pi/2) / 2, so the inner
// integral ends there and has no discontinuity.
double Albedo(const ModelInfo& m, const std::vector<double>& p, double theta_i) {
  const Vec3 wi = FromSpherical(theta_i, 0.0);
  auto integrand = [&](double th, double ph) {
    const Vec3 h = FromSpherical(th, ph);
    const double c = Dot(wi, h);
    const Vec3 wo = 2 * c * h - wi;
    if (c <= 0 || wo.z <= 0) return 0.0;  // rounding at the end point only
    double f[3];
    m.eval(p.data(), MakeGeometry(wi, wo), f);
    return f[0] * wo.z * 4 * c * std::sin(th);
  };
  auto inner = [&](double ph) {
    const double b = std::atan2(std::sin(theta_i) * std::cos(ph), std::cos(theta_i));
    const double th_max = 0.5 * (b + kPi / 2);
    std::vector<double> points;
    for (double t : PolarBreakpoints())
      if (t < th_max) points.push_back(t);
    points.push_back(th_max);
    return IntegrateSplit([&](double th) { return integrand(th, ph); }, points, 1e-8);
  };
  return 2 * IntegrateSplit(inner, {0.0, kPi / 2, kPi}, 1e-7);  // symmetric in phi_h
}

// Shape-parameter grid of one lobe: lower bound, two interior points and the upper bound of
// each shape parameter (log-spaced when log_scale; bounds only for lobes with more than two
// shape parameters); colour weights at `weight`. `grid` overrides the values of named shape
// parameters.
using Grid = std::map<std::string, std::vector<double>>;
using test::ParamSets;
ParamSets LobeFurnaceParams(const std::vector<ParamSpec>& specs, const Grid& grid, double weight) {
  ParamSets sets = {{}};
  const auto shapes = std::count_if(specs.begin(), specs.end(),
                                    [](const ParamSpec& s) { return s.role == ParamRole::kShape; });
  const std::vector<double> steps =
      shapes > 2 ? std::vector<double>{0.0, 1.0} : std::vector<double>{0.0, 1.0 / 3, 2.0 / 3, 1.0};
  for (const ParamSpec& s : specs) {
    std::vector<double> values;
    if (grid.count(std::string(s.name))) {
      values = grid.at(std::string(s.name));
    } else if (s.role != ParamRole::kShape) {
      values = {weight};
    } else {
      for (double t : steps) {
        values.push_back(s.log_scale ? s.lower * std::pow(s.upper / s.lower, t)
                                     : s.lower + t * (s.upper - s.lower));
      }
    }
    ParamSets next;
    for (const auto& base : sets)
      for (double v : values) {
        next.push_back(base);
        next.back().push_back(v);
      }
    sets = next;
  }
  return sets;
}

// Extra grid points where the generic bounds-and-thirds grid misses a lobe's maximum:
// Oren-Nayar's albedo peaks near sigma = 0.2 at grazing; Lafortune's sharpest lobes (n = 1e5)
// would only slow the test, so its n grid stops at 300.
Grid LobeGrid(std::string_view lobe) {
  if (lobe == "oren-nayar") return {{"sigma", {0.0, 0.2, 0.5, 1.0, kPi / 2}}};
  if (lobe == "lafortune") {
    return {{"cxy", {-20.0, -1.5, -1.02, -1.0, -0.5, 0.0, 1.0}}, {"n", {1, 10, 300}}};
  }
  return {};
}

template <class M>
struct FurnaceParams {
  static ParamSets Get(double weight = 1.0) {
    return LobeFurnaceParams({M::kParams.begin(), M::kParams.end()}, LobeGrid(M::kName), weight);
  }
};
// A sum: colour weights 1 / (number of lobes), the lobes' grids joined (JoinLobeSets; a full
// product of the lobes' grids would be slow); then each lobe alone at full weight, the others
// at 0, where a lobe that does not conserve energy shows it (oren-nayar+ggx: at weights 1/2
// the sum's albedo stays below 1).
template <class... L>
struct FurnaceParams<Sum<L...>> {
  static ParamSets Get() {
    ParamSets all = test::JoinLobeSets({FurnaceParams<L>::Get(1.0 / sizeof...(L))...});
    for (std::size_t alone = 0; alone < sizeof...(L); ++alone) {
      std::size_t i = 0;  // braced lists evaluate left to right
      const ParamSets one =
          test::JoinLobeSets({FurnaceParams<L>::Get(i++ == alone ? 1.0 : 0.0)...});
      all.insert(all.end(), one.begin(), one.end());
    }
    return all;
  }
};

// Every catalog model: albedo <= 1 if documented as energy conserving (ModelInfo), and > 1
// somewhere if documented as not.
void RunFurnace(const ModelInfo& m, const ParamSets& sets) {
  double max_albedo = 0;
  std::string at;
  for (const auto& p : sets) {
    for (double deg : {0.0, 45.0, 80.0, 89.0, 89.9}) {
      const double a = Albedo(m, p, deg * kPi / 180);
      ASSERT_TRUE(std::isfinite(a)) << m.name;
      if (a > max_albedo) {
        max_albedo = a;
        std::ostringstream os;
        os << "theta_i " << deg << " deg, params";
        for (double v : p) os << " " << v;
        at = os.str();
      }
    }
  }
  std::printf("  %-22s max albedo %.6f at %s\n", m.name.c_str(), max_albedo, at.c_str());
  if (m.energy_conserving) {
    EXPECT_LE(max_albedo, 1.0 + 1e-3) << m.name << " is documented as energy conserving; at " << at;
  } else {
    // The documentation says this model can reflect more than it receives: show it.
    EXPECT_GT(max_albedo, 1.0 + 1e-3) << m.name << " is documented as not energy conserving";
  }
}

// One test per catalog model (a model added to the catalog is in the furnace at once).
template <class M>
class WhiteFurnace : public ::testing::Test {};
TYPED_TEST_SUITE(WhiteFurnace, test::CatalogTypes, test::CatalogNames);

TYPED_TEST(WhiteFurnace, AlbedoAgreesWithEnergyClaim) {
  const ModelInfo* m = FindModel(ModelName<TypeParam>());
  ASSERT_NE(m, nullptr);
  RunFurnace(*m, FurnaceParams<TypeParam>::Get());
}

// Lambert's albedo is kd exactly (the integral of cos over the hemisphere is pi):
// a check of the furnace quadrature itself.
TEST(Physics, FurnaceQuadratureIsExactForLambert) {
  const ModelInfo* m = FindModel("lambert");
  for (double deg : {0.0, 60.0, 89.0}) {
    EXPECT_NEAR(Albedo(*m, {0.7, 0.7, 0.7}, deg * kPi / 180), 0.7, 1e-6);
  }
}

}  // namespace
}  // namespace brdfit
