// The rendered-image metric of a factorization (factor/factor_metrics.h, docs/accuracy.md,
// docs/factorization.md "Rendered error"): what `brdfit factor` writes into the sidecar
// (metrics.rendered) and prints equals the metric of an independent reconstruction of f from the
// two EXR files as written, with the formulas of docs/formats.md ("Factorization files") and
// OpenGL's GL_LINEAR texture filtering; and the metric orders factorizations sensibly (a coarser
// texture of a smooth product does not score better).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/rgb_image.h"
#include "factor/factor.h"
#include "factor/factor_metrics.h"
#include "fit/rendered_error.h"
#include "io/exr_texture.h"
#include "io/hdf5_table.h"
#include "models/geometry.h"
#include "tests/factor/factor_test_util.h"
#include "tests/io/io_test_util.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing::Rgb;

std::string Slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// OpenGL 4.6 core profile, section 8.14.2 (GL_LINEAR): normalized coordinates (u, v) in texel
// units x = u W - 1/2, i0 = floor(x), weights from the fraction; CLAMP_TO_EDGE clamps the
// texel indices into [0, W - 1], REPEAT takes them modulo the size.
Rgb GlLinear(const RgbImage& img, double u, double v, bool repeat_v) {
  const double x = u * img.width - 0.5, y = v * img.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double a = x - fx, b = y - fy;
  auto col = [&](long long i) { return static_cast<int>(std::clamp<long long>(i, 0, img.width - 1)); };
  auto row = [&](long long j) {
    if (repeat_v) return static_cast<int>(((j % img.height) + img.height) % img.height);
    return static_cast<int>(std::clamp<long long>(j, 0, img.height - 1));
  };
  const long long i0 = static_cast<long long>(fx), j0 = static_cast<long long>(fy);
  Rgb out{0, 0, 0};
  const double w[4] = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
  const int ii[4] = {col(i0), col(i0 + 1), col(i0), col(i0 + 1)};
  const int jj[4] = {row(j0), row(j0), row(j0 + 1), row(j0 + 1)};
  for (int k = 0; k < 4; ++k) {
    const float* t = img.At(ii[k], jj[k]);  // column i, row j (row 0 = first scan line)
    for (int c = 0; c < 3; ++c) out[c] += w[k] * t[c];
  }
  return out;
}

// disk-parabolic: (s, t) = (x, y) / (1 + z) (Heidrich & Seidel 1998, eq. 1).
Rgb DiskParabolic(const RgbImage& img, const Vec3& w) {
  const double s = w.x / (1 + w.z), t = w.y / (1 + w.z);
  return GlLinear(img, 0.5 * (s + 1), 0.5 * (t + 1), false);
}

// disk-sqrt-theta: (s, t) = sqrt(theta / (pi/2)) (cos phi, sin phi).
Rgb DiskSqrtTheta(const RgbImage& img, const Vec3& w) {
  const double r = std::hypot(w.x, w.y);
  double s = 0, t = 0;
  if (r > 0) {
    const double rho = std::sqrt(std::atan2(r, w.z) / (kPi / 2));
    s = rho * w.x / r;
    t = rho * w.y / r;
  }
  return GlLinear(img, 0.5 * (s + 1), 0.5 * (t + 1), false);
}

Vec3 Unit(const Vec3& v) {
  const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / n, v.y / n, v.z / n};
}

// f of the documented formulas (docs/formats.md) from the textures read back from the files.
BrdfFunction Reconstruction(const std::string& param, const RgbImage& p, const RgbImage& q) {
  if (param == "mccool") {
    // f(wi, wo) = p(wi) q(wh) p(wo).
    return [&p, &q](const Vec3& wi, const Vec3& wo) {
      const Rgb a = DiskParabolic(p, wi), b = DiskSqrtTheta(q, Unit(wi + wo)),
                c = DiskParabolic(p, wo);
      return Rgb{a[0] * b[0] * c[0], a[1] * b[1] * c[1], a[2] * b[2] * c[2]};
    };
  }
  // f(wi, wo) = p(wh) q(theta_d, phi_d); Rusinkiewicz's difference angles (docs/conventions.md)
  // by models/geometry.h: at retro-reflection (the 0-degree light) phi_d is rounding noise that
  // a second implementation would not reproduce bit for bit, and q's first column is not quite
  // constant in phi_d.
  return [&p, &q](const Vec3& wi, const Vec3& wo) {
    const HalfDiffAngles d = ToHalfDiff(wi, wo);
    const Rgb a = DiskSqrtTheta(p, Unit(wi + wo));
    const Rgb b = GlLinear(q, d.theta_d / (kPi / 2), d.phi_d / kPi, true);
    return Rgb{a[0] * b[0], a[1] * b[1], a[2] * b[2]};
  };
}

void ExpectClose(double got, double want, double rel, const char* what) {
  EXPECT_NEAR(got, want, rel * std::max(1.0, std::abs(want))) << what;
}

class FactorRenderedCli : public ::testing::TestWithParam<const char*> {};

// The sidecar's metrics.rendered is the metric of the textures as written, evaluated without
// FactoredBrdf, factor_param.h or the EXR writer's in-memory images; the summary prints it.
TEST_P(FactorRenderedCli, SidecarEqualsIndependentReconstructionOfTheWrittenTextures) {
  const std::string param = GetParam();
  ScratchDir dir;
  const Table table = testing::McCoolProductTable(testing::SmallGrid());
  const fs::path table_path = dir / "product.h5";
  WriteHdf5Table(table, table_path);
  const fs::path out = dir / "out";
  const auto run = testing_io::RunCli(
      {"factor", table_path.string(), "--param", param, "--res", "12", "-o", out.string()},
      dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const auto sidecar = nlohmann::json::parse(Slurp(out / "product.factor.json"));
  const auto& written = sidecar["metrics"]["rendered"];
  ASSERT_TRUE(written["ok"].get<bool>()) << written.dump();
  EXPECT_FALSE(written.contains("problem"));
  const RgbImage p = ReadRgbExr(out / sidecar["textures"]["p"]["file"].get<std::string>());
  const RgbImage q = ReadRgbExr(out / sidecar["textures"]["q"]["file"].get<std::string>());
  ASSERT_EQ(p.width, 12);
  const RenderedError want = ComputeRenderedError(table, Reconstruction(param, p, q));
  ASSERT_TRUE(want.ok) << want.problem;
  // Different arithmetic for the same texels: agreement to rounding, far below any difference
  // of the textures (one texel off by 1e-6 moves the PSNR by more).
  ExpectClose(written["psnr_db"].get<double>(), want.psnr_db, 1e-9, "psnr_db");
  ExpectClose(written["psnr_srgb_db"].get<double>(), want.psnr_srgb_db, 1e-9, "psnr_srgb_db");
  ExpectClose(written["median_rel_error"].get<double>(), want.median_rel_error, 1e-9, "median");
  ExpectClose(written["p95_rel_error"].get<double>(), want.p95_rel_error, 1e-9, "p95");
  // Not trivially equal: a real error, and the textures matter (a 1 % brighter p changes it).
  EXPECT_LT(want.psnr_db, kRenderedPsnrCapDb);
  RgbImage brighter = p;
  for (float& v : brighter.rgb) v *= 1.01f;
  const RenderedError moved = ComputeRenderedError(table, Reconstruction(param, brighter, q));
  EXPECT_GT(std::abs(moved.median_rel_error - want.median_rel_error), 1e-3);

  // The summary line: psnr_dB and med_lum as brdfit fit prints them.
  EXPECT_NE(run.out.find("psnr_dB"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("med_lum"), std::string::npos) << run.out;
  char cells[64];
  std::snprintf(cells, sizeof cells, " %.1f %6.1f%% ", want.psnr_db, 100 * want.median_rel_error);
  EXPECT_NE(run.out.find(cells), std::string::npos) << cells << "\n" << run.out;
}

INSTANTIATE_TEST_SUITE_P(BothParameterizations, FactorRenderedCli,
                         ::testing::Values("mccool", "halfdiff"));

// An exact product of smooth factors: each parameterization's own form is reproduced up to the
// bilinear interpolation between texels and the table's trilinear lookup, so a coarser texture
// never scores better (PSNR and median luminance error), and the finest one is close.
TEST(FactorRendered, CoarserTexturesOfASmoothProductDoNotScoreBetter) {
  Grid g = testing::SmallGrid();
  g.n_theta_h = 45;
  g.n_theta_d = 45;
  g.n_phi_d = 90;
  struct Case {
    FactorParam param;
    Table table;
  };
  const Case cases[] = {{FactorParam::kMcCool, testing::McCoolProductTable(g)},
                        {FactorParam::kHalfDiff, testing::HalfDiffProductTable(g)}};
  for (const Case& c : cases) {
    const RenderedReference ref = PrepareRenderedReference(c.table);
    double last_psnr = 1e300, last_lum = -1;
    for (int res : {64, 16, 8, 4}) {
      FactorOptions o;
      o.param = c.param;
      o.resolution = res;
      const Factorization r = Factor(c.table, o);
      const RenderedError e = ScoreRendered(ref, FactoredBrdfFunction(r.brdf));
      ASSERT_TRUE(e.ok) << e.problem;
      // The score of the helper is the score of ScoreFactorizationRendered.
      const RenderedError direct = ScoreFactorizationRendered(c.table, r.brdf);
      EXPECT_EQ(direct.psnr_db, e.psnr_db);
      EXPECT_EQ(direct.median_rel_error, e.median_rel_error);
      SCOPED_TRACE(std::string(ToString(c.param)) + " res " + std::to_string(res));
      EXPECT_LE(e.psnr_db, last_psnr);
      EXPECT_GE(e.median_rel_error, last_lum);
      if (res == 64) {
        EXPECT_GT(e.psnr_db, 40);
        EXPECT_LT(e.median_rel_error, 0.01);
      }
      std::printf("%s %3d: %.2f dB, median %.3f %%\n", ToString(c.param), res, e.psnr_db,
                  100 * e.median_rel_error);
      last_psnr = e.psnr_db;
      last_lum = e.median_rel_error;
    }
  }
}

}  // namespace
}  // namespace brdfit
