// The images behind the rendered-image metric (fit/rendered_error.h RenderImages, docs/accuracy.md
// "Images"): their pixels, read back with the definitions of docs/accuracy.md written here,
// reproduce every number of the metric; the pixel states follow the scene's geometry (computed
// here from the pixel centres, not by the code under test); the approximation's pixels are the
// model evaluated in an independent frame; masked cells show as masked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fit/rendered_error.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;
using State = RenderedImage::State;

double Y(const double* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

double SortedAt(std::vector<double> v, std::size_t percent) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, v.size() * percent / 100)];
}

double PsnrDb(double peak, double mse) {
  return mse == 0 ? kRenderedPsnrCapDb : std::min(kRenderedPsnrCapDb, 10 * std::log10(peak * peak / mse));
}

bool Lit(State s) { return s == State::kCompared || s == State::kBelowFloor; }

// The metric recomputed from the images alone (docs/accuracy.md, "Metrics").
RenderedError FromImages(const std::vector<RenderedImage>& images) {
  RenderedError r;
  std::vector<double> all_e, all_y, all_m, all_a;
  for (std::size_t k = 0; k < images.size(); ++k) {
    const RenderedImage& img = images[k];
    RenderedLightError& le = r.lights[k];
    double peak = 0, peak_y = 0, se = 0;
    std::size_t lit = 0;
    for (std::size_t p = 0; p < img.state.size(); ++p) {
      if (!Lit(img.state[p])) continue;
      ++lit;
      for (int c = 0; c < 3; ++c) {
        peak = std::max(peak, img.measured[3 * p + c]);
        se += std::pow(img.approx[3 * p + c] - img.measured[3 * p + c], 2);
        all_m.push_back(img.measured[3 * p + c]);
        all_a.push_back(img.approx[3 * p + c]);
      }
      peak_y = std::max(peak_y, Y(&img.measured[3 * p]));
      all_y.push_back(Y(&img.measured[3 * p]));
    }
    std::vector<double> e;
    for (std::size_t p = 0; p < img.state.size(); ++p) {
      if (img.state[p] != State::kCompared) continue;
      e.push_back(std::abs(img.rel_error[p]));
    }
    le.psnr_db = PsnrDb(peak, se / (3.0 * static_cast<double>(lit)));
    le.median_rel_error = SortedAt(e, 50);
    le.p95_rel_error = SortedAt(e, 95);
    le.lit_pixels = lit;
    le.compared_pixels = e.size();
    r.peak = std::max(r.peak, peak);
    r.lit_pixels += lit;
    r.compared_pixels += e.size();
    all_e.insert(all_e.end(), e.begin(), e.end());
    (void)peak_y;
  }
  double se = 0;
  for (std::size_t i = 0; i < all_m.size(); ++i) se += std::pow(all_a[i] - all_m[i], 2);
  r.psnr_db = PsnrDb(r.peak, se / static_cast<double>(all_m.size()));
  r.median_rel_error = SortedAt(all_e, 50);
  r.p95_rel_error = SortedAt(all_e, 95);
  r.exposure = 1 / SortedAt(all_y, 99);
  auto srgb = [&](double x) {
    x = std::clamp(r.exposure * x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
  };
  double st = 0;
  for (std::size_t i = 0; i < all_m.size(); ++i) st += std::pow(srgb(all_a[i]) - srgb(all_m[i]), 2);
  r.psnr_srgb_db = PsnrDb(1, st / static_cast<double>(all_m.size()));
  return r;
}

TEST(RenderedImages, PixelsReproduceTheMetric) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.2"}), SmallGrid());
  const ModelInfo& approx_model = *FindModel("lambert+beckmann");
  const std::vector<double> p =
      Params("lambert+beckmann", {"beckmann.alpha=0.3", "lambert.kd_g=0.3"});
  RenderedErrorOptions o;
  o.resolution = 40;
  const BrdfFunction approx = ModelBrdf(approx_model, p);
  const RenderedImages images = RenderImages(PrepareRenderedReference(t, o), approx);
  const RenderedError metric = ComputeRenderedError(t, approx, o);
  ASSERT_TRUE(metric.ok) << metric.problem;
  ASSERT_EQ(images.lights.size(), o.light_angles_deg.size());
  // The metric returned with the images is the metric.
  EXPECT_EQ(images.metric.psnr_db, metric.psnr_db);
  EXPECT_EQ(images.metric.median_rel_error, metric.median_rel_error);
  EXPECT_EQ(images.metric.psnr_srgb_db, metric.psnr_srgb_db);

  const RenderedError back = FromImages(images.lights);
  EXPECT_NEAR(back.psnr_db, metric.psnr_db, 1e-9);
  EXPECT_NEAR(back.psnr_srgb_db, metric.psnr_srgb_db, 1e-9);
  EXPECT_EQ(back.median_rel_error, metric.median_rel_error);
  EXPECT_EQ(back.p95_rel_error, metric.p95_rel_error);
  EXPECT_EQ(back.exposure, metric.exposure);
  EXPECT_EQ(back.peak, metric.peak);
  EXPECT_EQ(back.lit_pixels, metric.lit_pixels);
  EXPECT_EQ(back.compared_pixels, metric.compared_pixels);
  for (std::size_t k = 0; k < images.lights.size(); ++k) {
    SCOPED_TRACE("light " + std::to_string(k));
    EXPECT_EQ(images.lights[k].light_deg, o.light_angles_deg[k]);
    EXPECT_NEAR(back.lights[k].psnr_db, metric.lights[k].psnr_db, 1e-9);
    EXPECT_EQ(back.lights[k].median_rel_error, metric.lights[k].median_rel_error);
    EXPECT_EQ(back.lights[k].p95_rel_error, metric.lights[k].p95_rel_error);
    EXPECT_EQ(back.lights[k].lit_pixels, metric.lights[k].lit_pixels);
    EXPECT_EQ(back.lights[k].compared_pixels, metric.lights[k].compared_pixels);
  }
}

// States from the pixel centres and cosines; radiances from an independent frame (a rotation
// taking the normal to the pole); the signed error from the two radiances and the floor.
TEST(RenderedImages, PixelsFollowTheScene) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.15"}), SmallGrid());
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.25", "lambert.kd_r=0.5"});
  RenderedErrorOptions o;
  o.resolution = 24;
  o.light_angles_deg = {45, 80};
  const RenderedImages images = RenderImages(PrepareRenderedReference(t, o), ModelBrdf(m, p));
  ASSERT_TRUE(images.metric.ok) << images.metric.problem;
  const int n = o.resolution;
  int brighter = 0, darker = 0;
  for (std::size_t k = 0; k < images.lights.size(); ++k) {
    const RenderedImage& img = images.lights[k];
    ASSERT_EQ(img.resolution, n);
    ASSERT_EQ(img.state.size(), static_cast<std::size_t>(n * n));
    const double a = o.light_angles_deg[k] * kPi / 180;
    double peak_y = 0;
    for (std::size_t i = 0; i < img.state.size(); ++i) {
      if (Lit(img.state[i])) peak_y = std::max(peak_y, Y(&img.measured[3 * i]));
    }
    for (int row = 0; row < n; ++row) {
      for (int col = 0; col < n; ++col) {
        const std::size_t i = static_cast<std::size_t>(row) * n + col;
        const double sx = (col + 0.5) / n * 2 - 1, sy = 1 - (row + 0.5) / n * 2;
        const double rho = std::hypot(sx, sy);
        if (rho >= 1) {
          EXPECT_EQ(img.state[i], State::kOff) << col << "," << row;
          continue;
        }
        const double th = std::asin(rho), ph = std::atan2(sy, sx);
        auto local = [&](double x, double y, double z) {
          const double c = std::cos(-ph), s = std::sin(-ph);
          const double x1 = c * x - s * y, y1 = s * x + c * y;
          const double ct = std::cos(-th), st = std::sin(-th);
          return Vec3{ct * x1 + st * z, y1, -st * x1 + ct * z};
        };
        const Vec3 wo = local(0, 0, 1), wi = local(std::sin(a), 0, std::cos(a));
        if (!(wo.z > 1e-3) || !(wi.z > 1e-3)) {
          EXPECT_EQ(img.state[i], State::kUnlit) << col << "," << row;
          continue;
        }
        ASSERT_TRUE(Lit(img.state[i])) << col << "," << row;
        std::array<double, 3> f{};
        m.eval(p.data(), MakeGeometry(wi, wo), f.data());
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(img.approx[3 * i + c], f[c] * wi.z, 1e-9 * (1 + f[c])) << col << "," << row;
        }
        const double ym = Y(&img.measured[3 * i]), ya = Y(&img.approx[3 * i]);
        if (ym > o.luminance_floor * peak_y) {
          ASSERT_EQ(img.state[i], State::kCompared);
          EXPECT_NEAR(img.rel_error[i], (ya - ym) / ym, 1e-12 * (1 + std::abs(ya / ym)));
          (img.rel_error[i] > 0 ? brighter : darker)++;
        } else {
          EXPECT_EQ(img.state[i], State::kBelowFloor);
          EXPECT_TRUE(std::isnan(img.rel_error[i]));
        }
      }
    }
  }
  // A brighter body (kd_r) and a wider lobe: both signs occur.
  EXPECT_GT(brighter, 0);
  EXPECT_GT(darker, 0);
}

TEST(RenderedImages, MaskedPixelsAndFailures) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.2"});
  Table holed = SynthModel("lambert+ggx", truth, SmallGrid());
  const Grid& g = holed.grid;
  for (int ih = 10; ih < 16; ++ih) {
    for (int id = 0; id < g.n_theta_d; ++id) {
      for (int ip = 0; ip < g.n_phi_d; ++ip) holed.valid[g.Index(ih, id, ip)] = 0;
    }
  }
  const BrdfFunction model = ModelBrdf(*FindModel("lambert+ggx"), truth);
  const RenderedImages images = RenderImages(PrepareRenderedReference(holed), model);
  ASSERT_TRUE(images.metric.ok) << images.metric.problem;
  std::size_t masked = 0;
  for (std::size_t k = 0; k < images.lights.size(); ++k) {
    const auto c = static_cast<std::size_t>(
        std::count(images.lights[k].state.begin(), images.lights[k].state.end(), State::kMasked));
    EXPECT_EQ(c, images.metric.lights[k].masked_pixels);
    masked += c;
  }
  EXPECT_GT(masked, 1000u);
  EXPECT_EQ(masked, images.metric.masked_pixels);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const RenderedImages bad = RenderImages(
      PrepareRenderedReference(holed),
      [&](const Vec3&, const Vec3&) { return std::array<double, 3>{nan, 0, 0}; });
  EXPECT_FALSE(bad.metric.ok);
  EXPECT_NE(bad.metric.problem.find("not finite"), std::string::npos);
  EXPECT_TRUE(bad.lights.empty());
}

// IEC 61966-2-1: the linear segment, the power segment, the clamp.
TEST(RenderedImages, ToneMapIsTheSrgbOetfOfTheExposedValue) {
  EXPECT_EQ(RenderedToneMap(0, 2), 0);
  EXPECT_EQ(RenderedToneMap(-1, 2), 0);
  EXPECT_DOUBLE_EQ(RenderedToneMap(0.001, 2), 12.92 * 0.002);
  EXPECT_DOUBLE_EQ(RenderedToneMap(0.5, 2), 1);
  EXPECT_DOUBLE_EQ(RenderedToneMap(100, 2), 1);
  EXPECT_NEAR(RenderedToneMap(0.1, 2), 1.055 * std::pow(0.2, 1 / 2.4) - 0.055, 1e-15);
}

}  // namespace
}  // namespace brdfit
