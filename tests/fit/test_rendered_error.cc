// The rendered-image metric (fit/rendered_error.h, docs/accuracy.md "Rendered-image metric")
// against an independent per-pixel evaluation written here: its own sphere geometry (normal
// from spherical angles), its own local frame (a rotation taking n to the pole, not the Duff
// frame of the metric: the BRDFs are isotropic, so the values agree to rounding), its own
// statistics (full sorts). Plus the metric's exact properties: identical images, a scaled
// approximation, masked cells, failures.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/model_choice.h"
#include "fit/fitter.h"
#include "fit/rendered_error.h"
#include "fit_test_util.h"
#include "io/fit_params_json.h"
#include "io/fit_report.h"
#include "io/hdf5_util.h"
#include "io/metrics_json.h"
#include "models/registry.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

using Rgb = std::array<double, 3>;
using LocalBrdf = std::function<Rgb(const Vec3& wi, const Vec3& wo)>;

struct RefLight {
  double psnr = 0, median = 0, p95 = 0;
  std::size_t lit = 0, masked = 0, compared = 0;
  std::vector<double> lm, la;  // lit pixels' radiances, RGB
};
struct RefRegion {  // docs/accuracy.md "Every light": its lights' images pooled
  int lights = 0;
  double psnr = 0, median = 0, peak = 0, se = 0;
  std::size_t values = 0;
  std::vector<double> errors;
  struct Body {
    double ym;
    Rgb m, a;
  };
  std::vector<Body> compared;  // for the body's colour
};
struct Ref {
  double psnr = 0, psnr_srgb = 0, median = 0, p95 = 0, peak = 0, body = 0;
  std::size_t lit = 0, masked = 0, compared = 0;
  std::vector<RefLight> lights;
  std::array<RefRegion, 3> regions;  // front (<= 80 deg), side (<= 125), rim
};

double Y(const double* c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

double SortedAt(std::vector<double> v, std::size_t percent) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, v.size() * percent / 100)];
}

double PsnrDb(double peak, double mse) {
  return mse == 0 ? kRenderedPsnrCapDb : 10 * std::log10(peak * peak / mse);
}

// Straight from the definitions in docs/accuracy.md.
Ref Reference(const Table& t, const LocalBrdf& approx, int n,
              const std::vector<double>& angles_deg) {
  Ref r;
  std::vector<double> all_e, all_y, all_m, all_a;
  for (double deg : angles_deg) {
    const double a = deg * kPi / 180;
    const double lx = std::sin(a), lz = std::cos(a);
    RefLight rl;
    for (int row = 0; row < n; ++row) {
      for (int col = 0; col < n; ++col) {
        const double sx = (col + 0.5) / n * 2 - 1, sy = 1 - (row + 0.5) / n * 2;
        const double rho = std::hypot(sx, sy);
        if (rho >= 1) continue;
        // Normal n = (sin th cos ph, sin th sin ph, cos th); the rotation R = R_y(-th) R_z(-ph)
        // takes it to +z: local coordinates are R applied to world vectors.
        const double th = std::asin(rho), ph = std::atan2(sy, sx);
        auto local = [&](double x, double y, double z) {
          const double c = std::cos(-ph), s = std::sin(-ph);
          const double x1 = c * x - s * y, y1 = s * x + c * y;
          const double ct = std::cos(-th), st = std::sin(-th);
          return Vec3{ct * x1 + st * z, y1, -st * x1 + ct * z};
        };
        const Vec3 wo = local(0, 0, 1), wi = local(lx, 0, lz);
        if (!(wo.z > 1e-3) || !(wi.z > 1e-3)) continue;
        // phi_d is undefined at theta_d = 0 (the 0-degree light): the metric takes 0.
        HalfDiffAngles hd = ToHalfDiff(wi, wo);
        if (hd.theta_d < 1e-6) hd.phi_d = 0;
        const auto m = t.LookupTrilinear(hd);
        if (!m) {
          ++rl.masked;
          continue;
        }
        const Rgb f = approx(wi, wo);
        for (int c = 0; c < 3; ++c) {
          rl.lm.push_back((*m)[c] * wi.z);
          rl.la.push_back(f[c] * wi.z);
        }
        ++rl.lit;
      }
    }
    double peak = 0, peak_y = 0, se = 0;
    for (std::size_t i = 0; i < rl.lm.size(); ++i) {
      peak = std::max(peak, rl.lm[i]);
      se += (rl.la[i] - rl.lm[i]) * (rl.la[i] - rl.lm[i]);
    }
    for (std::size_t p = 0; p < rl.lit; ++p) peak_y = std::max(peak_y, Y(&rl.lm[3 * p]));
    std::vector<double> e;
    RefRegion& g = r.regions[deg <= 80 ? 0 : deg <= 125 ? 1 : 2];
    for (std::size_t p = 0; p < rl.lit; ++p) {
      const double ym = Y(&rl.lm[3 * p]);
      all_y.push_back(ym);
      if (ym > 1e-4 * peak_y) {
        e.push_back(std::abs(Y(&rl.la[3 * p]) - ym) / ym);
        g.compared.push_back({ym,
                              {rl.lm[3 * p], rl.lm[3 * p + 1], rl.lm[3 * p + 2]},
                              {rl.la[3 * p], rl.la[3 * p + 1], rl.la[3 * p + 2]}});
      }
    }
    ++g.lights;
    g.peak = std::max(g.peak, peak);
    g.se += se;
    g.values += rl.lm.size();
    g.errors.insert(g.errors.end(), e.begin(), e.end());
    rl.psnr = PsnrDb(peak, se / static_cast<double>(rl.lm.size()));
    rl.median = SortedAt(e, 50);
    rl.p95 = SortedAt(e, 95);
    rl.compared = e.size();
    r.peak = std::max(r.peak, peak);
    r.lit += rl.lit;
    r.masked += rl.masked;
    r.compared += rl.compared;
    all_e.insert(all_e.end(), e.begin(), e.end());
    all_m.insert(all_m.end(), rl.lm.begin(), rl.lm.end());
    all_a.insert(all_a.end(), rl.la.begin(), rl.la.end());
    r.lights.push_back(std::move(rl));
  }
  for (RefRegion& g : r.regions) {
    if (g.lights == 0) continue;
    g.psnr = PsnrDb(g.peak, g.se / static_cast<double>(g.values));
    g.median = SortedAt(g.errors, 50);
    // The body's colour (front and side): the compared pixels at or below the median measured
    // luminance, summed per channel and divided by the sums' luminance; the largest relative
    // channel error, a channel under 10 % of the brightest measured against that 10 %.
    if (&g == &r.regions[2]) continue;
    std::vector<double> ys;
    for (const RefRegion::Body& b : g.compared) ys.push_back(b.ym);
    const double median_y = SortedAt(ys, 50);
    Rgb sm{}, sa{};
    for (const RefRegion::Body& b : g.compared) {
      if (b.ym > median_y) continue;
      for (int c = 0; c < 3; ++c) sm[c] += b.m[c], sa[c] += b.a[c];
    }
    const double ym = Y(sm.data()), ya = Y(sa.data());
    if (!(ym > 0) || !(ya > 0)) continue;
    for (int c = 0; c < 3; ++c) sm[c] /= ym, sa[c] /= ya;
    const double floor = 0.1 * std::max({sm[0], sm[1], sm[2]});
    for (int c = 0; c < 3; ++c) {
      r.body = std::max(r.body, std::abs(sa[c] - sm[c]) / std::max(sm[c], floor));
    }
  }
  double se = 0;
  for (std::size_t i = 0; i < all_m.size(); ++i) se += std::pow(all_a[i] - all_m[i], 2);
  r.psnr = PsnrDb(r.peak, se / static_cast<double>(all_m.size()));
  r.median = SortedAt(all_e, 50);
  r.p95 = SortedAt(all_e, 95);
  const double k = 1 / SortedAt(all_y, 99);
  auto srgb = [k](double x) {
    x = std::min(1.0, std::max(0.0, k * x));
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
  };
  double st = 0;
  for (std::size_t i = 0; i < all_m.size(); ++i) st += std::pow(srgb(all_a[i]) - srgb(all_m[i]), 2);
  r.psnr_srgb = PsnrDb(1, st / static_cast<double>(all_m.size()));
  return r;
}

LocalBrdf Model(const std::string& name, const std::vector<double>& p) {
  const ModelInfo* m = FindModel(name);
  return [m, p](const Vec3& wi, const Vec3& wo) {
    Rgb v;
    m->eval(p.data(), MakeGeometry(wi, wo), v.data());
    return v;
  };
}

// The metric's own lights: front, side and rim (light behind the sphere).
const std::vector<double> kAngles = RenderedErrorOptions{}.light_angles_deg;

void ExpectMatches(const RenderedError& got, const Ref& ref) {
  ASSERT_TRUE(got.ok) << got.problem;
  EXPECT_NEAR(got.psnr_db, ref.psnr, 1e-9);
  EXPECT_NEAR(got.psnr_srgb_db, ref.psnr_srgb, 1e-9);
  EXPECT_NEAR(got.median_rel_error, ref.median, 1e-9);
  EXPECT_NEAR(got.p95_rel_error, ref.p95, 1e-9);
  // The body's pixels are those at or below the median luminance: mirror pixels tie there, and
  // rounding (the reference rotates by its own frame) can move one of a pair across; one pixel
  // of the ~1000 of a body moves its colour by far less than this.
  EXPECT_NEAR(got.body_color_error, ref.body, 1e-4 + 1e-3 * ref.body);
  EXPECT_NEAR(got.peak, ref.peak, 1e-12 * ref.peak);
  EXPECT_EQ(got.lit_pixels, ref.lit);
  EXPECT_EQ(got.masked_pixels, ref.masked);
  EXPECT_EQ(got.compared_pixels, ref.compared);
  EXPECT_EQ(got.below_floor_pixels, ref.lit - ref.compared);
  ASSERT_EQ(got.num_lights, static_cast<int>(ref.lights.size()));
  for (std::size_t k = 0; k < ref.lights.size(); ++k) {
    SCOPED_TRACE("light " + std::to_string(k));
    const RenderedLightError& g = got.lights[k];
    EXPECT_NEAR(g.psnr_db, ref.lights[k].psnr, 1e-9);
    EXPECT_NEAR(g.median_rel_error, ref.lights[k].median, 1e-9);
    EXPECT_NEAR(g.p95_rel_error, ref.lights[k].p95, 1e-9);
    EXPECT_EQ(g.lit_pixels, ref.lights[k].lit);
    EXPECT_EQ(g.masked_pixels, ref.lights[k].masked);
    EXPECT_EQ(g.compared_pixels, ref.lights[k].compared);
  }
  for (std::size_t r = 0; r < ref.regions.size(); ++r) {
    SCOPED_TRACE("region " + std::to_string(r));
    EXPECT_EQ(got.regions[r].lights, ref.regions[r].lights);
    if (ref.regions[r].lights == 0) continue;
    EXPECT_NEAR(got.regions[r].psnr_db, ref.regions[r].psnr, 1e-9);
    EXPECT_NEAR(got.regions[r].median_rel_error, ref.regions[r].median, 1e-9);
  }
}

// (a) Three (table, approximation, resolution) cases against the independent evaluation.
TEST(RenderedError, MatchesIndependentPerPixelEvaluation) {
  struct Case {
    std::string table_model;
    std::vector<std::string> table_params;
    std::string approx_model;
    std::vector<std::string> approx_params;
    int n;
  };
  const std::vector<Case> cases = {
      {"lambert+ggx",
       {"ggx.alpha=0.1"},
       "lambert+beckmann",
       {"beckmann.alpha=0.15", "lambert.kd_g=0.3"},
       16},
      {"lambert+ggx", {"ggx.alpha=0.3", "lambert.kd_g=0.2"}, "lambert+ggx", {"ggx.alpha=0.2"}, 33},
      {"lambert+cook-torrance", {"lambert.kd_b=0.2"}, "lambert+ward", {"ward.alpha=0.2"}, 64},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.table_model + " vs " + c.approx_model + " N=" + std::to_string(c.n));
    const Table t = SynthModel(c.table_model, Params(c.table_model, c.table_params), SmallGrid());
    const std::vector<double> p = Params(c.approx_model, c.approx_params);
    RenderedErrorOptions o;
    o.resolution = c.n;
    const RenderedError got = ComputeRenderedError(t, ModelBrdf(*FindModel(c.approx_model), p), o);
    ExpectMatches(got, Reference(t, Model(c.approx_model, p), c.n, kAngles));
    std::printf("%s vs %s, N=%d: PSNR %.3f dB, sRGB %.3f dB, median %.4f, p95 %.4f, %zu lit\n",
                c.table_model.c_str(), c.approx_model.c_str(), c.n, got.psnr_db, got.psnr_srgb_db,
                got.median_rel_error, got.p95_rel_error, got.lit_pixels);
    EXPECT_EQ(got.resolution, c.n);
    EXPECT_GT(got.median_rel_error, 0.01);  // a real difference is being measured
    EXPECT_LT(got.psnr_db, 60);
  }
}

// Other lights than the default six (one of them beyond 80 degrees).
TEST(RenderedError, CustomLights) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid());
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.3"});
  RenderedErrorOptions o;
  o.resolution = 24;
  o.light_angles_deg = {10, 85};
  const RenderedError got = ComputeRenderedError(t, ModelBrdf(*FindModel("lambert+ggx"), p), o);
  ExpectMatches(got, Reference(t, Model("lambert+ggx", p), 24, o.light_angles_deg));
  EXPECT_EQ(got.lights[1].light_deg, 85);
}

// (b) The approximation is the measured lookup itself: PSNR at the documented cap, no error.
TEST(RenderedError, IdenticalImagesGiveThePsnrCapAndZeroError) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.1"}), SmallGrid());
  const RenderedError r = ComputeRenderedError(t, TableBrdf(t));
  ASSERT_TRUE(r.ok) << r.problem;
  EXPECT_EQ(r.psnr_db, kRenderedPsnrCapDb);
  EXPECT_EQ(r.psnr_srgb_db, kRenderedPsnrCapDb);
  EXPECT_EQ(r.median_rel_error, 0.0);
  EXPECT_EQ(r.p95_rel_error, 0.0);
  EXPECT_EQ(r.body_color_error, 0.0);
  for (int k = 0; k < r.num_lights; ++k) {
    EXPECT_EQ(r.lights[k].psnr_db, kRenderedPsnrCapDb);
    EXPECT_EQ(r.lights[k].median_rel_error, 0.0);
  }
  EXPECT_EQ(r.num_lights, static_cast<int>(RenderedErrorOptions{}.light_angles_deg.size()));
  for (const RenderedRegionError& g : r.regions) {
    EXPECT_EQ(g.psnr_db, kRenderedPsnrCapDb);
    EXPECT_EQ(g.median_rel_error, 0.0);
  }
  EXPECT_EQ(r.resolution, 64);
  EXPECT_EQ(r.masked_pixels, 0u);
  EXPECT_GT(r.lit_pixels, 6u * 64 * 64 / 4);
}

// (c) (1 + s) times the measurement: every relative luminance error is exactly s (the doubling
// is exact in floating point for s = 1), and the PSNR is 20 log10(peak / rms(L_m)) - 20 log10 s.
TEST(RenderedError, ScaledApproximationHasPredictableErrors) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.15"}), SmallGrid());
  auto scaled = [&](double s) {
    const BrdfFunction same = TableBrdf(t);
    return BrdfFunction([same, s](const Vec3& wi, const Vec3& wo) {
      Rgb v = same(wi, wo);
      for (double& c : v) c *= 1 + s;
      return v;
    });
  };
  const RenderedError twice = ComputeRenderedError(t, scaled(1.0));
  ASSERT_TRUE(twice.ok) << twice.problem;
  EXPECT_EQ(twice.median_rel_error, 1.0);
  EXPECT_EQ(twice.p95_rel_error, 1.0);
  EXPECT_EQ(twice.body_color_error, 0.0);  // twice as bright, the same colour
  for (int k = 0; k < twice.num_lights; ++k) EXPECT_EQ(twice.lights[k].median_rel_error, 1.0);
  // PSNR of 2x: MSE = mean(L_m^2).
  const Ref ref = Reference(t, TableBrdf(t), 64, kAngles);
  double sum2 = 0, count = 0;
  for (const RefLight& l : ref.lights) {
    for (double v : l.lm) sum2 += v * v;
    count += static_cast<double>(l.lm.size());
  }
  EXPECT_NEAR(twice.psnr_db, 20 * std::log10(ref.peak / std::sqrt(sum2 / count)), 1e-9);
  const RenderedError tenth = ComputeRenderedError(t, scaled(0.1));
  ASSERT_TRUE(tenth.ok);
  EXPECT_NEAR(tenth.psnr_db - twice.psnr_db, 20.0, 1e-9);  // -20 log10(0.1)
  for (int k = 0; k < twice.num_lights; ++k) {
    EXPECT_NEAR(tenth.lights[k].psnr_db - twice.lights[k].psnr_db, 20.0, 1e-9);
  }
  EXPECT_NEAR(tenth.median_rel_error, 0.1, 1e-12);
  EXPECT_NEAR(tenth.body_color_error, 0.0, 1e-12);
  // A colour cast: red 1.1 times, green and blue as measured.
  const BrdfFunction same = TableBrdf(t);
  const BrdfFunction red = [same](const Vec3& wi, const Vec3& wo) {
    Rgb v = same(wi, wo);
    v[0] *= 1.1;
    return v;
  };
  const RenderedError redder = ComputeRenderedError(t, red);
  ASSERT_TRUE(redder.ok);
  EXPECT_GT(redder.body_color_error, 0.05);
  EXPECT_LT(redder.body_color_error, 0.1);
  ExpectMatches(redder, Reference(t, red, 64, kAngles));
  // Too dark by the same factor gives the same relative error.
  EXPECT_NEAR(ComputeRenderedError(t, scaled(-0.1)).median_rel_error, 0.1, 1e-12);
}

// The body's colour (RenderedError::body_color_error) on a dark, saturated table: a red body
// (kd = 0.05, 0.02, 0.008) under a white, sharp lobe. The exact model scores ~0; one whose blue
// body is zeroed (the lobe keeps the highlight) loses most of the body's blue and scores 0.75
// (the lobe's tail gives the body's dimmer half a quarter of its blue), though its luminance
// errors are small: blue is 7 % of luminance. One whose blue body is 3 times too bright scores
// 1.4 (2 less the tail's share).
TEST(RenderedError, BodyColourCatchesAZeroedChannelOfADarkSaturatedBody) {
  const std::string model = "lambert+ggx";
  const std::vector<double> truth = Params(
      model,
      {"kd_r=0.05", "kd_g=0.02", "kd_b=0.008", "ks_r=0.3", "ks_g=0.3", "ks_b=0.3", "alpha=0.05"});
  const Table t = SynthModel(model, truth, SmallGrid());
  const ModelInfo* info = FindModel(model);
  ASSERT_NE(info, nullptr);
  const RenderedError exact = ComputeRenderedError(t, ModelBrdf(*info, truth));
  ASSERT_TRUE(exact.ok) << exact.problem;
  // The table's trilinear lookup against the model itself: near 0, not exactly.
  EXPECT_LT(exact.body_color_error, 0.02);
  std::vector<double> no_blue = truth, blue3 = truth;
  no_blue[2] = 0;
  blue3[2] = 3 * truth[2];
  const RenderedError zeroed = ComputeRenderedError(t, ModelBrdf(*info, no_blue));
  ASSERT_TRUE(zeroed.ok);
  EXPECT_GT(zeroed.body_color_error, 0.6);
  EXPECT_LE(zeroed.body_color_error, 1.0);
  // Its luminance hardly moves: blue weighs 0.0722 in Y, and the body is dark beside the lobe.
  EXPECT_LT(zeroed.median_rel_error, 0.1);
  const RenderedError bright = ComputeRenderedError(t, ModelBrdf(*info, blue3));
  ASSERT_TRUE(bright.ok);
  EXPECT_GT(bright.body_color_error, 1.2);
  EXPECT_LE(bright.body_color_error, 2.0 + exact.body_color_error);
  // The independent evaluation agrees on every number of all three.
  for (const auto& p : {truth, no_blue, blue3}) {
    ExpectMatches(ComputeRenderedError(t, ModelBrdf(*info, p)),
                  Reference(t, Model(model, p), 64, kAngles));
  }
}

// (d) Masked cells: a band of theta_h bins is masked (values set to NaN, which must never be
// read). Pixels whose trilinear lookup has no valid neighbour are excluded and counted; the
// metric over the rest equals the independent evaluation that skips them. Were the holes read
// as zero, the lit pixels would be black there and the PSNR against the full table would drop.
TEST(RenderedError, MaskedCellsAreExcludedNotZero) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Table full = SynthModel("lambert+ggx", truth, SmallGrid());
  Table holed = full;
  const Grid& g = holed.grid;
  for (int ih = 10; ih < 16; ++ih) {
    for (int id = 0; id < g.n_theta_d; ++id) {
      for (int ip = 0; ip < g.n_phi_d; ++ip) {
        const std::size_t idx = g.Index(ih, id, ip);
        holed.valid[idx] = 0;
        for (int c = 0; c < 3; ++c) holed.Value(idx)[c] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  const BrdfFunction full_lookup = TableBrdf(full);
  const RenderedError r = ComputeRenderedError(holed, full_lookup);
  const Ref ref = Reference(holed, full_lookup, 64, kAngles);
  ExpectMatches(r, ref);
  EXPECT_GT(r.masked_pixels, 1000u);
  // Lit + masked is the geometrically lit set of the full table.
  const RenderedError rf = ComputeRenderedError(full, full_lookup);
  EXPECT_EQ(r.lit_pixels + r.masked_pixels, rf.lit_pixels);
  EXPECT_EQ(rf.masked_pixels, 0u);
  // The holes' neighbours are renormalized trilinear values, close to the full table's.
  EXPECT_GT(r.psnr_db, 30);
  EXPECT_LT(r.median_rel_error, 1e-3);
  // Holes in the approximation (TableBrdf gives NaN there) fail the metric, never score black.
  const RenderedError bad = ComputeRenderedError(full, TableBrdf(holed));
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.problem.find("not finite"), std::string::npos) << bad.problem;
}

// The reference's per-light peak luminance, which the luminance floor scales wherever compared
// pixels are picked, is the brightest of that light's measured pixels (masked ones left out),
// recomputed here from the pixels; the environment's the same over its pixels.
TEST(RenderedError, EachLightsPeakIsItsBrightestMeasuredPixel) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.1"}), SmallGrid());
  Table holed = t;
  for (std::size_t i = 0; i < holed.grid.NumCells(); i += 7) {
    holed.valid[i] = 0;
    for (int c = 0; c < 3; ++c) holed.Value(i)[c] = std::numeric_limits<double>::quiet_NaN();
  }
  for (const Table* table : {&t, static_cast<const Table*>(&holed)}) {
    const RenderedReference ref = PrepareRenderedReference(*table);
    ASSERT_EQ(ref.peak_y.size(), static_cast<std::size_t>(ref.counts.num_lights));
    for (int k = 0; k < ref.counts.num_lights; ++k) {
      double y = 0;
      for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; ++i) {
        const auto& m = ref.pixels[i].measured;
        y = std::max(y, 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2]);
      }
      EXPECT_EQ(ref.peak_y[static_cast<std::size_t>(k)], y) << k;
      EXPECT_GT(y, 0) << k;
    }
    ASSERT_FALSE(ref.env_pixels.empty());
    double env = 0;
    for (const auto& p : ref.env_pixels) {
      env = std::max(env, 0.2126 * p.measured[0] + 0.7152 * p.measured[1] + 0.0722 * p.measured[2]);
    }
    EXPECT_EQ(ref.env_peak_y, env);
  }
}

TEST(RenderedError, FailuresAreReportedWithFiniteNumbers) {
  const Table t = SynthModel("lambert", Params("lambert", {}), SmallGrid());
  const BrdfFunction nan = [](const Vec3&, const Vec3& wo) {
    return Rgb{0.1, wo.z > 0.5 ? std::numeric_limits<double>::quiet_NaN() : 0.1, 0.1};
  };
  RenderedError r = ComputeRenderedError(t, nan);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.problem.find("not finite"), std::string::npos) << r.problem;
  EXPECT_EQ(r.psnr_db, 0);
  // Overflowing squared errors.
  r = ComputeRenderedError(t, [](const Vec3&, const Vec3&) { return Rgb{1e300, 1e300, 1e300}; });
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(std::isfinite(r.psnr_db) && std::isfinite(r.median_rel_error));
  // Every cell masked.
  Table empty = Table::Empty(t.grid);
  r = ComputeRenderedError(empty, ModelBrdf(*FindModel("lambert"), Params("lambert", {})));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.problem.find("masked"), std::string::npos) << r.problem;
  EXPECT_GT(r.masked_pixels, 0u);
  // A black measurement.
  Table black = t;
  std::fill(black.rgb.begin(), black.rgb.end(), 0.0);
  r = ComputeRenderedError(black, ModelBrdf(*FindModel("lambert"), Params("lambert", {})));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.problem.find("black"), std::string::npos) << r.problem;
  // Bad options throw.
  const BrdfFunction lambert = ModelBrdf(*FindModel("lambert"), Params("lambert", {}));
  RenderedErrorOptions o;
  o.resolution = 0;
  EXPECT_THROW(ComputeRenderedError(t, lambert, o), std::invalid_argument);
  o = {};
  o.light_angles_deg = std::vector<double>(kRenderedMaxLights + 1, 10.0);
  EXPECT_THROW(ComputeRenderedError(t, lambert, o), std::invalid_argument);
  o = {};
  o.light_angles_deg = {180};
  EXPECT_THROW(ComputeRenderedError(t, lambert, o), std::invalid_argument);
}

TEST(RenderedError, Deterministic) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid(), 0.05, 0.1);
  const BrdfFunction f =
      ModelBrdf(*FindModel("lambert+ggx"), Params("lambert+ggx", {"ggx.alpha=0.3"}));
  const RenderedError a = ComputeRenderedError(t, f), b = ComputeRenderedError(t, f);
  ASSERT_TRUE(a.ok);
  EXPECT_EQ(a.psnr_db, b.psnr_db);
  EXPECT_EQ(a.psnr_srgb_db, b.psnr_srgb_db);
  EXPECT_EQ(a.median_rel_error, b.median_rel_error);
  EXPECT_EQ(a.p95_rel_error, b.p95_rel_error);
  EXPECT_EQ(a.exposure, b.exposure);
}

// Every fit carries the metric (fit/fitter.h), and it survives the HDF5 fit report and the JSON
// parameters (io/fit_report.h) unchanged. A perfect model scores the cap.
TEST(RenderedError, EveryFitCarriesItThroughReportAndJson) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Table t = SynthModel("lambert+ggx", truth, SmallGrid(), 0.05, 0.0);
  const FitResult r = FitTable("lambert+ggx", t, SampleOptions{}, LogLossUnpolished());
  ASSERT_FALSE(r.Failed()) << r.message;
  const RenderedError& e = r.metrics.rendered;
  ASSERT_TRUE(e.ok) << e.problem;
  EXPECT_EQ(e.num_lights, static_cast<int>(RenderedErrorOptions{}.light_angles_deg.size()));
  for (const RenderedRegionError& g : e.regions) EXPECT_GT(g.lights, 0);
  // 5 % noise on the table: the fit is close to the truth, far better than a 2x error.
  EXPECT_LT(e.median_rel_error, 0.05);
  EXPECT_GT(e.psnr_db, 25);

  ScratchDir dir;
  const std::filesystem::path report = dir / "fits.h5";
  WriteFitReport({{"t.h5", "t", "{}", r, false, {}, {}, false, std::nullopt}}, report, false);
  const auto back = ReadFitReport(report);
  ASSERT_EQ(back.size(), 1u);
  const RenderedError& b = back[0].result.metrics.rendered;
  EXPECT_TRUE(b.ok);
  EXPECT_EQ(b.psnr_db, e.psnr_db);
  EXPECT_EQ(b.psnr_srgb_db, e.psnr_srgb_db);
  EXPECT_EQ(b.median_rel_error, e.median_rel_error);
  EXPECT_EQ(b.p95_rel_error, e.p95_rel_error);
  EXPECT_EQ(b.lit_pixels, e.lit_pixels);
  ASSERT_EQ(b.num_lights, e.num_lights);
  for (int k = 0; k < e.num_lights; ++k) {
    EXPECT_EQ(b.lights[k].light_deg, e.lights[k].light_deg);
    EXPECT_EQ(b.lights[k].psnr_db, e.lights[k].psnr_db);
  }
  const auto j = nlohmann::json::parse(FitParamsJson(back));
  EXPECT_EQ(j["fits"][0]["metrics"]["rendered"]["psnr_db"].get<double>(), e.psnr_db);
  EXPECT_EQ(j["fits"][0]["metrics"]["rendered"]["median_rel_error"].get<double>(),
            e.median_rel_error);
  EXPECT_TRUE(j["fits"][0]["metrics"]["rendered"]["ok"].get<bool>());
  EXPECT_FALSE(j["fits"][0]["metrics"]["rendered"].contains("problem"));
  // The regions and S: in the HDF5 report, the JSON, and read back from the JSON.
  for (int g = 0; g < kRenderedRegions; ++g) {
    EXPECT_EQ(b.regions[g].lights, e.regions[g].lights);
    EXPECT_EQ(b.regions[g].psnr_db, e.regions[g].psnr_db);
    EXPECT_EQ(b.regions[g].median_rel_error, e.regions[g].median_rel_error);
    const auto& jr = j["fits"][0]["metrics"]["rendered"]["regions"][kRenderedRegionNames[g]];
    EXPECT_EQ(jr["psnr_db"].get<double>(), e.regions[g].psnr_db);
    EXPECT_EQ(jr["lights"].get<int>(), e.regions[g].lights);
  }
  EXPECT_EQ(j["fits"][0]["metrics"]["rendered"]["score_db"].get<double>(), RenderedScoreDb(e));
  const std::filesystem::path json = dir / "fits.json";
  std::ofstream(json) << FitParamsJson(back);
  const auto again = ReadFitParamsJson(json);
  ASSERT_EQ(again.size(), 1u);
  const RenderedError& a = again[0].result.metrics.rendered;
  EXPECT_EQ(a.num_lights, e.num_lights);
  for (int g = 0; g < kRenderedRegions; ++g) {
    EXPECT_EQ(a.regions[g].lights, e.regions[g].lights);
    EXPECT_EQ(a.regions[g].psnr_db, e.regions[g].psnr_db);
  }
  EXPECT_EQ(RenderedScoreDb(a), RenderedScoreDb(e));
  // The body's colour: through HDF5 and JSON; optional (core/metrics.h), so a result that does
  // not hold it (NaN: read from a file written before it) is written without it and read back
  // as not computed by both.
  EXPECT_EQ(b.body_color_error, e.body_color_error);
  EXPECT_EQ(a.body_color_error, e.body_color_error);
  EXPECT_EQ(j["fits"][0]["metrics"]["rendered"]["body_color_error"].get<double>(),
            e.body_color_error);
  auto old = back;
  old[0].result.metrics.rendered.body_color_error = std::nan("");
  WriteFitReport(old, dir / "old.h5", false);
  const auto old_back = ReadFitReport(dir / "old.h5");
  ASSERT_EQ(old_back.size(), 1u);
  EXPECT_TRUE(std::isnan(old_back[0].result.metrics.rendered.body_color_error));
  EXPECT_EQ(old_back[0].result.metrics.rendered.psnr_db, e.psnr_db);
  const auto old_json = nlohmann::json::parse(FitParamsJson(old));
  EXPECT_FALSE(old_json["fits"][0]["metrics"]["rendered"].contains("body_color_error"));
  std::ofstream(dir / "old.json") << FitParamsJson(old);
  const auto old_again = ReadFitParamsJson(dir / "old.json");
  ASSERT_EQ(old_again.size(), 1u);
  EXPECT_TRUE(std::isnan(old_again[0].result.metrics.rendered.body_color_error));
  // A report written before the environment region holds three regions: read with the
  // environment not judged, and S is the directional regions' as it was.
  {
    std::filesystem::copy_file(report, dir / "three.h5");
    H5::H5File f((dir / "three.h5").string(), H5F_ACC_RDWR);
    std::vector<std::string> groups;
    H5Lvisit(
        f.getId(), H5_INDEX_NAME, H5_ITER_NATIVE,
        [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
          const std::string n = name;
          const std::string tail = "metrics/rendered";
          if (n.size() >= tail.size() &&
              n.compare(n.size() - tail.size(), tail.size(), tail) == 0) {
            static_cast<std::vector<std::string>*>(out)->push_back(n);
          }
          return 0;
        },
        &groups);
    ASSERT_EQ(groups.size(), 1u);
    H5::Group rg = f.openGroup(groups[0]);
    for (const char* name : {"region_lights", "region_psnr_db", "region_median_rel_error"}) {
      std::vector<double> v(kRenderedRegions);
      rg.openDataSet(name).read(v.data(), H5::PredType::NATIVE_DOUBLE);
      v.pop_back();
      rg.unlink(name);
      hdf5::WriteDoubles(rg, name, v);
    }
  }
  const auto three = ReadFitReport(dir / "three.h5");
  ASSERT_EQ(three.size(), 1u);
  const RenderedError& t3 = three[0].result.metrics.rendered;
  EXPECT_EQ(t3.regions[kRenderedRegions - 1].lights, 0);
  for (int g = 0; g + 1 < kRenderedRegions; ++g)
    EXPECT_EQ(t3.regions[g].psnr_db, e.regions[g].psnr_db);
  RenderedError directional = e;
  directional.regions[kRenderedRegions - 1] = {};
  EXPECT_EQ(RenderedScoreDb(t3), RenderedScoreDb(directional));
  // A negative one is refused by name, as any number of the summary.
  ASSERT_GT(e.body_color_error, 0);  // so that "-" makes it negative
  std::string text = FitParamsJson(back);
  const std::string key = "\"body_color_error\": ";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + key.size(), "-");
  std::ofstream(dir / "neg.json") << text;
  try {
    ReadFitParamsJson(dir / "neg.json");
    ADD_FAILURE() << "a negative body_color_error was read";
  } catch (const std::exception& ex) {
    EXPECT_NE(std::string(ex.what()).find("body_color_error"), std::string::npos) << ex.what();
  }
}

// The JSON layout shared by fit parameters and factorization sidecars (io/metrics_json.h): a
// failed metric says so and why; a metric never computed (a failed fit) is left out.
TEST(RenderedError, JsonSaysWhenTheMetricFailedAndOmitsItWhenNotComputed) {
  RenderedError failed;
  failed.num_lights = 6;
  failed.problem = "the measured images are black";
  const auto j = nlohmann::json(RenderedErrorJson(failed));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["problem"], failed.problem);
  EXPECT_EQ(j["psnr_db"].get<double>(), 0.0);

  FitResult r;
  r.model = "lambert";
  const auto none = nlohmann::json::parse(FitParamsJson({{"t.h5", "t", "{}", r, false, {}, {}, false, std::nullopt}}));
  EXPECT_FALSE(none["fits"][0]["metrics"].contains("rendered"));
  r.metrics.rendered = failed;
  const auto some = nlohmann::json::parse(FitParamsJson({{"t.h5", "t", "{}", r, false, {}, {}, false, std::nullopt}}));
  EXPECT_EQ(some["fits"][0]["metrics"]["rendered"], j);
}

}  // namespace
}  // namespace brdfit
