// The environment region of the rendered-image metric (fit/rendered_environment.h): its
// estimator against an independent quadrature of the same integral (the sky over a dense grid of
// world directions, the sun added in closed form), for a Lambertian and a glossy table; the
// region judged apart from the pooled numbers; masked directions; options.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/rendered_regions.h"
#include "fit/rendered_environment.h"
#include "fit/rendered_error.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

constexpr std::size_t kEnv = static_cast<std::size_t>(LightRegion::kEnvironment);

// The pixel (x, y)'s normal, as docs/accuracy.md places pixel centres (row 0 at the top).
Vec3 Normal(int x, int y, int n) {
  const double px = 2.0 * (x + 0.5) / n - 1, py = 1 - 2.0 * (y + 0.5) / n;
  return {px, py, std::sqrt(std::max(0.0, 1 - px * px - py * py))};
}

// Any tangent frame of n (the BRDFs are isotropic: the frame's rotation about n is immaterial).
void Frame(const Vec3& n, Vec3* t, Vec3* b) {
  const Vec3 a = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  *t = Cross(a, n);
  *t = (1 / std::sqrt(Dot(*t, *t))) * *t;
  *b = Cross(n, *t);
}

// The pixel's radiance by quadrature: the sky over a midpoint grid of world directions (polar
// angle from +y, where the sky's gradient runs), the sun in closed form.
std::array<double, 3> Quadrature(const BrdfFunction& f, const Vec3& n,
                                 const EnvironmentOptions& env, int n_theta, int n_phi) {
  Vec3 t, b;
  Frame(n, &t, &b);
  const Vec3 v{0, 0, 1};
  const Vec3 wo{Dot(v, t), Dot(v, b), Dot(v, n)};
  std::array<double, 3> sum{};
  const double dth = kPi / n_theta, dph = 2 * kPi / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double th = (i + 0.5) * dth;
    for (int j = 0; j < n_phi; ++j) {
      const double ph = (j + 0.5) * dph;
      const Vec3 w{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)};
      const double c = Dot(w, n);
      if (!(c > 1e-3)) continue;
      const std::array<double, 3> fr = f({Dot(w, t), Dot(w, b), c}, wo);
      const double k = SkyRadiance(w) * c * std::sin(th) * dth * dph;
      for (int ch = 0; ch < 3; ++ch) sum[ch] += fr[ch] * k;
    }
  }
  const Vec3 l = SunDirection(env);
  const double c = Dot(l, n);
  if (c > 1e-3) {
    const std::array<double, 3> fr = f({Dot(l, t), Dot(l, b), c}, wo);
    for (int ch = 0; ch < 3; ++ch) sum[ch] += fr[ch] * env.sun_irradiance * c;
  }
  return sum;
}

double Luma(const std::array<double, 3>& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// The estimator is unbiased: with many directions every pixel is the integral, and with the
// default K the image's mean is.
TEST(RenderedEnvironment, LambertianPixelsAreTheIrradianceIntegral) {
  const Table t =
      SynthModel("lambert+ggx",
                 Params("lambert+ggx", {"lambert.kd_r=0.5", "lambert.kd_g=0.4", "lambert.kd_b=0.3",
                                        "ggx.ks_r=0", "ggx.ks_g=0", "ggx.ks_b=0"}),
                 SmallGrid());
  const BrdfFunction lookup = TableBrdf(t);
  for (const int k : {3000, 18}) {
    SCOPED_TRACE("K = " + std::to_string(k));
    RenderedErrorOptions o;
    o.resolution = 8;
    o.environment.samples = k;
    o.environment.resolution = k == 3000 ? 10 : 32;
    const RenderedReference ref = PrepareRenderedReference(t, o);
    ASSERT_FALSE(ref.env_pixels.empty());
    double sum_ratio = 0, worst = 0;
    for (const RenderedReference::EnvPixel& p : ref.env_pixels) {
      const Vec3 n = Normal(p.x, p.y, o.environment.resolution);
      const double want =
          Luma(Quadrature(lookup, n, o.environment, k == 3000 ? 180 : 90, k == 3000 ? 360 : 180));
      const double ratio = Luma(p.measured) / want;
      sum_ratio += ratio;
      worst = std::max(worst, std::abs(ratio - 1));
    }
    const double mean = sum_ratio / static_cast<double>(ref.env_pixels.size());
    std::printf("K=%d: %zu pixels, mean ratio %.4f, worst %.4f\n", k, ref.env_pixels.size(), mean,
                worst);
    EXPECT_NEAR(mean, 1.0, k == 3000 ? 0.002 : 0.015);
    if (k == 3000) {
      EXPECT_LT(worst, 0.01);
    }
  }
}

// A glossy lobe: the half-vector techniques find it (cosine-weighted directions alone would
// miss most of an alpha = 0.1 highlight at this K).
TEST(RenderedEnvironment, GlossyPixelsAreTheIntegral) {
  const Table t = SynthModel("lambert+ggx",
                             Params("lambert+ggx", {"ggx.alpha=0.1", "lambert.kd_r=0",
                                                    "lambert.kd_g=0", "lambert.kd_b=0"}),
                             SmallGrid());
  const BrdfFunction lookup = TableBrdf(t);
  RenderedErrorOptions o;
  o.resolution = 8;
  o.environment.samples = 3000;
  o.environment.resolution = 5;
  const RenderedReference ref = PrepareRenderedReference(t, o);
  ASSERT_FALSE(ref.env_pixels.empty());
  double worst = 0;
  for (const RenderedReference::EnvPixel& p : ref.env_pixels) {
    const Vec3 n = Normal(p.x, p.y, o.environment.resolution);
    const double want = Luma(Quadrature(lookup, n, o.environment, 720, 1440));
    worst = std::max(worst, std::abs(Luma(p.measured) / want - 1));
  }
  std::printf("glossy: %zu pixels, worst ratio error %.4f\n", ref.env_pixels.size(), worst);
  EXPECT_LT(worst, 0.04);
}

// Judged as a region of its own, out of the pooled numbers, which are the lights' alone.
TEST(RenderedEnvironment, ARegionOfItsOwnOutsideThePooledNumbers) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.15"}), SmallGrid());
  RenderedErrorOptions on, off;
  on.resolution = off.resolution = 32;
  off.environment.samples = 0;
  const RenderedError same = ComputeRenderedError(t, TableBrdf(t), on);
  ASSERT_TRUE(same.ok) << same.problem;
  EXPECT_EQ(same.regions[kEnv].lights, 1);
  EXPECT_EQ(same.regions[kEnv].psnr_db, kRenderedPsnrCapDb);
  EXPECT_EQ(same.regions[kEnv].median_rel_error, 0.0);

  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.15"});
  const BrdfFunction model = ModelBrdf(*FindModel("lambert+ggx"), p);
  const BrdfFunction brighter = [&](const Vec3& wi, const Vec3& wo) {
    std::array<double, 3> f = model(wi, wo);
    for (double& c : f) c *= 1.1;
    return f;
  };
  const RenderedError a = ComputeRenderedError(t, brighter, on);
  const RenderedError b = ComputeRenderedError(t, brighter, off);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_EQ(b.regions[kEnv].lights, 0);
  // The model's values against the table's trilinear lookups: 10 % brighter, to a few 0.1 %.
  EXPECT_NEAR(a.regions[kEnv].median_rel_error, 0.1, 0.01);
  EXPECT_LT(a.regions[kEnv].psnr_db, 40);
  EXPECT_EQ(a.psnr_db, b.psnr_db);
  EXPECT_EQ(a.median_rel_error, b.median_rel_error);
  EXPECT_EQ(a.psnr_srgb_db, b.psnr_srgb_db);
  EXPECT_EQ(a.lit_pixels, b.lit_pixels);
  for (int g = 0; g < kRenderedRegions - 1; ++g) {
    EXPECT_EQ(a.regions[g].psnr_db, b.regions[g].psnr_db);
  }
  // The environment enters the score (core/model_choice.h) as a region.
  const auto regions = RenderedRegions(a);
  EXPECT_EQ(regions[kEnv].lights, 1);
  EXPECT_NEAR(regions[kEnv].score_db,
              std::min(a.regions[kEnv].psnr_db, 60.0) - 20 * a.regions[kEnv].median_rel_error,
              1e-12);
}

// A masked direction is left out of both images: the table against itself stays identical.
TEST(RenderedEnvironment, MaskedDirectionsLeaveBothImages) {
  Table holed = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.2"}), SmallGrid());
  const Grid& g = holed.grid;
  for (int ih = 0; ih < g.n_theta_h; ++ih) {
    for (int id = 28; id < g.n_theta_d; ++id) {  // theta_d >= 84 deg, beyond every light
      for (int ip = 0; ip < g.n_phi_d; ++ip) {
        const std::size_t idx = g.Index(ih, id, ip);
        holed.valid[idx] = 0;
        for (int c = 0; c < 3; ++c) holed.Value(idx)[c] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  const RenderedReference ref = PrepareRenderedReference(holed, RenderedErrorOptions{});
  EXPECT_GT(ref.env_masked_samples, 0u);
  const RenderedError r = ScoreRendered(ref, TableBrdf(holed));
  ASSERT_TRUE(r.ok) << r.problem;
  EXPECT_EQ(r.regions[kEnv].psnr_db, kRenderedPsnrCapDb);
}

TEST(RenderedEnvironment, DeterministicAndSeeded) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.1"}), SmallGrid());
  const BrdfFunction f =
      ModelBrdf(*FindModel("lambert+ggx"), Params("lambert+ggx", {"ggx.alpha=0.2"}));
  RenderedErrorOptions o;
  const RenderedError a = ComputeRenderedError(t, f, o), b = ComputeRenderedError(t, f, o);
  EXPECT_EQ(a.regions[kEnv].psnr_db, b.regions[kEnv].psnr_db);
  o.environment.seed = 2;
  const RenderedError c = ComputeRenderedError(t, f, o);
  EXPECT_NE(a.regions[kEnv].psnr_db, c.regions[kEnv].psnr_db);
  // Another seed integrates the same images: the error moves by the noise, not more.
  EXPECT_NEAR(a.regions[kEnv].psnr_db, c.regions[kEnv].psnr_db, 1.5);
}

TEST(RenderedEnvironment, OptionsOutsideTheirRangesAreRefused) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid());
  for (const auto& edit : std::vector<std::function<void(EnvironmentOptions&)>>{
           [](EnvironmentOptions& e) { e.samples = 4; },
           [](EnvironmentOptions& e) { e.samples = 3003; },
           [](EnvironmentOptions& e) { e.resolution = 0; },
           [](EnvironmentOptions& e) { e.sun_polar_deg = 181; },
           [](EnvironmentOptions& e) { e.sun_irradiance = -1; },
           [](EnvironmentOptions& e) {
             e.sun_azimuth_deg = std::numeric_limits<double>::infinity();
           },
       }) {
    RenderedErrorOptions o;
    edit(o.environment);
    EXPECT_THROW(PrepareRenderedReference(t, o), std::invalid_argument);
  }
}

}  // namespace
}  // namespace brdfit
