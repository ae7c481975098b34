// `brdfit render` end to end: only the materials a render uses are loaded or computed; a
// computed fit is cached on disk and reused by the next render (read from --explain); bad
// input exits 2 with the file named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include <cmath>

#include "core/synth.h"
#include "fit/options.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/inputs.h"
#include "pipeline/material_loader.h"
#include "io/image_io.h"

namespace brdfit::preview {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string out;
};

// Runs a shell command line; its exit code and its stdout + stderr.
CliRun RunShell(const std::string& command_line) {
  const std::string cmd = command_line + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p.get())) out += buf.data();
  const int status = pclose(p.release());
  return {WEXITSTATUS(status), out};
}

CliRun RunCli(const std::string& args) {
  return RunShell(std::string(BRDFIT_EXE) + " " + args);
}

int Count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1))
    ++n;
  return n;
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfit_render_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Three small synthetic tables (lambert+ggx with different roughness).
    const ModelInfo* m = FindModel("lambert+ggx");
    Grid grid;
    grid.n_theta_h = 16;
    grid.n_theta_d = 16;
    grid.n_phi_d = 32;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> p = m->DefaultParams();
      p.back() = 0.1 + 0.1 * k;
      Table t = SynthesizeTable(
          grid, [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); }, {});
      std::string name = "t";  // (not "t" + to_string: GCC 12 -Wrestrict false positive)
      name += std::to_string(k);
      name += ".h5";
      SaveTable(t, dir_ / name);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  // `render t0.h5 --compare` at 64x32 with --explain, caching in dir_/cache.
  std::string CompareT0Args() const {
    return (dir_ / "t0.h5").string() + " -o " + (dir_ / "out.png").string() +
           " --compare --size 64x32 --explain --cache " + (dir_ / "cache").string();
  }
  void WriteScene(const std::string& json) { std::ofstream(dir_ / "scene.json") << json; }
  fs::path dir_;
};

TEST_F(RenderCli, LoadsOnlyWhatTheSceneUsesAndReusesTheCache) {
  WriteScene(R"({
    "image": {"width": 48, "height": 48},
    "lights": [{"type": "directional", "direction": [1, 1, 1]}],
    "materials": {
      "a": {"type": "analytic", "model": "lambert+ggx", "fit_table": "t0.h5"},
      "b": {"type": "analytic", "model": "lambert+ggx", "fit_table": "t1.h5"},
      "c": {"type": "measured", "table": "t2.h5"}
    },
    "objects": [{"material": "b"}]
  })");
  const std::string args = (dir_ / "scene.json").string() + " -o " + (dir_ / "out.png").string() +
                           " --explain --cache " + (dir_ / "cache").string();
  const CliRun first = RunCli("render " + args);
  ASSERT_EQ(first.code, 0) << first.out;
  EXPECT_EQ(Count(first.out, "compute: fit lambert+ggx of"), 1) << first.out;
  EXPECT_NE(first.out.find("t1.h5"), std::string::npos) << first.out;
  EXPECT_EQ(Count(first.out, "skip: material 'a'"), 1) << first.out;
  EXPECT_EQ(Count(first.out, "skip: material 'c'"), 1) << first.out;
  EXPECT_EQ(first.out.find("t0.h5"), std::string::npos) << first.out;
  EXPECT_EQ(first.out.find("t2.h5"), std::string::npos) << first.out;

  const CliRun second = RunCli("render " + args);
  ASSERT_EQ(second.code, 0) << second.out;
  EXPECT_EQ(Count(second.out, "compute: fit"), 0) << second.out;
  EXPECT_EQ(Count(second.out, "reuse: fit lambert+ggx of"), 1) << second.out;
  // Both renders show the same image.
  EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

// A fit cached by a build of another engine revision (fit/options.h kFitEngineRevision: a
// default inside the engine changed what fits return) is not reused: the key says so.
TEST_F(RenderCli, FitCachedByAnotherEngineRevisionIsNotReused) {
  const std::string args = CompareT0Args();
  const CliRun first = RunCli("render " + args);
  ASSERT_EQ(first.code, 0) << first.out;
  const std::string content = pipeline::InputContentKey((dir_ / "t0.h5").string());
  const fs::path current =
      dir_ / "cache" /
      ("fit-" + pipeline::FitCacheKey(content, "lambert+ggx", kFitEngineRevision) + ".json");
  ASSERT_TRUE(fs::exists(current)) << first.out;
  // The entry as an older build would have left it: under the previous revision's key.
  const fs::path older =
      dir_ / "cache" /
      ("fit-" + pipeline::FitCacheKey(content, "lambert+ggx", kFitEngineRevision - 1) + ".json");
  ASSERT_NE(older, current);
  fs::rename(current, older);
  const CliRun second = RunCli("render " + args);
  ASSERT_EQ(second.code, 0) << second.out;
  EXPECT_EQ(Count(second.out, "reuse: fit"), 0) << second.out;
  EXPECT_EQ(Count(second.out, "compute: fit lambert+ggx of"), 1) << second.out;
  EXPECT_TRUE(fs::exists(current)) << second.out;
  // And the current entry is reused by the next render.
  const CliRun third = RunCli("render " + args);
  ASSERT_EQ(third.code, 0) << third.out;
  EXPECT_EQ(Count(third.out, "reuse: fit lambert+ggx of"), 1) << third.out;
}

// Issue 14 item 5: a cache entry with parameters of 1e300 crashed `render --compare --cache`.
// An entry whose parameters are out of the model's bounds is recomputed, with a note naming it.
TEST_F(RenderCli, OutOfRangeCacheEntryIsRecomputed) {
  const std::string args = CompareT0Args();
  const CliRun first = RunCli("render " + args);
  ASSERT_EQ(first.code, 0) << first.out;
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(dir_ / "cache")) {
    if (e.path().filename().string().starts_with("fit-")) entries.push_back(e.path());
  }
  ASSERT_EQ(entries.size(), 1u) << first.out;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(entries[0]));
  for (auto& p : j["params"]) p = 1e300;
  std::ofstream(entries[0]) << j.dump();

  const CliRun second = RunCli("render " + args);
  ASSERT_EQ(second.code, 0) << second.out;
  EXPECT_EQ(Count(second.out, "cache entry " + entries[0].string() + " unreadable"), 1)
      << second.out;
  EXPECT_NE(second.out.find("outside the model's bounds"), std::string::npos) << second.out;
  EXPECT_EQ(Count(second.out, "compute: fit"), 1) << second.out;
  // The recomputed entry replaced the bad one.
  const nlohmann::json fixed = nlohmann::json::parse(std::ifstream(entries[0]));
  for (const auto& p : fixed["params"]) EXPECT_LT(std::abs(p.get<double>()), 1e3) << fixed.dump();
}

TEST_F(RenderCli, CullsLightsThatReachNothing) {
  WriteScene(R"({
    "image": {"width": 32, "height": 32},
    "lights": [{"name": "near", "type": "point", "position": [0, 0, 3], "distance": 10},
               {"name": "far", "type": "point", "position": [0, 0, 30], "distance": 5},
               {"name": "aside", "type": "spot", "position": [0, 0, 5], "target": [20, 0, 0],
                "angle_deg": 10}],
    "materials": {"m": {"type": "analytic", "model": "ggx"}},
    "objects": [{"name": "ball", "material": "m"}]
  })");
  const CliRun r = RunCli("render " + (dir_ / "scene.json").string() + " -o " +
                          (dir_ / "out.exr").string() + " --explain");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("skip: light 'far' for object 'ball': out of range"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("skip: light 'aside' for object 'ball': outside the cone"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("analytic:ggx dir=0 point=1 spot=0"), std::string::npos) << r.out;
  const Image img = ReadExr(dir_ / "out.exr");
  EXPECT_EQ(img.width, 32);
  EXPECT_GT(img.At(16, 16)[0], 0.0f);  // lit by 'near'
  EXPECT_NE(r.out.find("wrote "), std::string::npos) << r.out;
  // -q: the image, and no 'wrote' line.
  const CliRun q = RunCli("render " + (dir_ / "scene.json").string() + " -o " +
                          (dir_ / "q.png").string() + " -q");
  ASSERT_EQ(q.code, 0) << q.out;
  EXPECT_EQ(q.out.find("wrote"), std::string::npos) << q.out;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "q.png"));
}

// What CI renders headless: a 512x512 four-panel comparison (measured | fit | factored |
// error), with the fit and the factorization computed on the way.
TEST_F(RenderCli, FourPanelComparison512) {
  WriteScene(R"({
    "lights": [{"type": "directional", "direction": [1, 1, 1.5]},
               {"type": "point", "position": [-3, 0.5, 3], "intensity": 0.4}],
    "materials": {
      "meas": {"type": "measured", "table": "t1.h5"},
      "fit": {"type": "analytic", "model": "ggx", "fit_table": "t1.h5"},
      "fac": {"type": "factored", "table": "t1.h5", "resolution": 16}
    },
    "objects": [{"material": "meas"}],
    "comparison": {"measured": "meas", "fitted": ["fit"], "factored": "fac"}
  })");
  const CliRun r =
      RunCli("render " + (dir_ / "scene.json").string() + " -o " + (dir_ / "cmp.png").string() +
             " --compare --size 512x512 --explain --cache " + (dir_ / "cache").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Count(r.out, "load: table"), 1) << r.out;  // one table file, loaded once
  EXPECT_EQ(Count(r.out, "compute: fit ggx"), 1) << r.out;
  EXPECT_EQ(Count(r.out, "compute: factorization mccool 16"), 1) << r.out;
  EXPECT_NE(r.out.find("comparison error of 'fit' vs 'meas': median"), std::string::npos) << r.out;
  const Image img = ReadPng(dir_ / "cmp.png");
  ASSERT_EQ(img.width, 512);
  ASSERT_EQ(img.height, 512);
  // Each 256 x 256 panel shows a lit sphere at its centre (not the "not available" grey).
  for (int k = 0; k < 4; ++k) {
    const float* c = img.At((k % 2) * 256 + 128, (k / 2) * 256 + 128);
    EXPECT_GT(c[0] + c[1] + c[2], 0.05f) << "panel " << k;
    EXPECT_FALSE(std::abs(c[0] - 0.18f) < 0.01f && std::abs(c[1] - 0.18f) < 0.01f) << "panel " << k;
  }
}

// `render TABLE --compare` draws the factorization `brdfit factor TABLE` writes: the same form
// chosen from the same candidates with the same rendered scores (pipeline/factor_with_choice.h).
TEST_F(RenderCli, TableComparisonDrawsTheFactorizationFactorChooses) {
  const std::string table = (dir_ / "t1.h5").string();
  const CliRun f = RunCli("factor " + table + " -q -o " + (dir_ / "fac").string());
  ASSERT_EQ(f.code, 0) << f.out;
  const CliRun r = RunCli("render " + table + " -o " + (dir_ / "cmp.png").string() +
                          " --compare --size 128x128 --explain --cache " +
                          (dir_ / "cache").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const auto read = [](const fs::path& p) { return nlohmann::json::parse(std::ifstream(p)); };
  const nlohmann::json factor = read(dir_ / "fac" / "t1.factor.json");
  std::vector<fs::path> cached;
  for (const auto& e : fs::directory_iterator(dir_ / "cache")) {
    if (e.path().string().find(".factor.json") != std::string::npos) cached.push_back(e.path());
  }
  ASSERT_EQ(cached.size(), 1u) << r.out;
  const nlohmann::json preview = read(cached[0]);
  ASSERT_TRUE(factor.contains("choice"));
  ASSERT_TRUE(preview.contains("choice")) << preview.dump(1);
  EXPECT_EQ(preview["choice"]["chosen"], factor["choice"]["chosen"]);
  ASSERT_EQ(preview["choice"]["candidates"].size(), factor["choice"]["candidates"].size());
  for (std::size_t k = 0; k < factor["choice"]["candidates"].size(); ++k) {
    EXPECT_EQ(preview["choice"]["candidates"][k]["score_db"],
              factor["choice"]["candidates"][k]["score_db"]);
  }
  EXPECT_EQ(preview["solver"], factor["solver"]);  // the same options, resolution included
  EXPECT_NE(r.out.find("chosen of 4 forms"), std::string::npos) << r.out;
}

TEST_F(RenderCli, BadInputExitsTwoNamingTheFile) {
  WriteScene(R"({"materials": {"m": {"type": "measured", "table": "missing.binary"}},
                 "objects": [{"material": "m"}]})");
  const CliRun r =
      RunCli("render " + (dir_ / "scene.json").string() + " -o " + (dir_ / "out.png").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("missing.binary"), std::string::npos) << r.out;
  const CliRun s = RunCli("render " + (dir_ / "scene.json").string() + " -o x.png --size 12");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.out.find("--size"), std::string::npos) << s.out;
}

// A mesh object (`"shape": "mesh"`): the OBJ is loaded once for two objects, the image is
// written; a broken OBJ exits 2 naming it and writes nothing.
TEST_F(RenderCli, MeshObjectsRenderAndABrokenMeshIsNamed) {
  { std::ofstream(dir_ / "quad.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"; }
  WriteScene(R"({"materials": {"m": {"type": "analytic", "model": "lambert",
                                     "params": {"kd_r": 1, "kd_g": 1, "kd_b": 1}}},
                 "lights": [{"type": "directional", "direction": [0, 0, 1]}],
                 "objects": [{"name": "a", "shape": "mesh", "file": "quad.obj", "material": "m",
                              "centre": [-1, 0, 0], "radius": 0.8},
                             {"name": "b", "shape": "mesh", "file": "quad.obj", "material": "m",
                              "centre": [1, 0, 0], "radius": 0.8}]})");
  const CliRun r = RunCli("render " + (dir_ / "scene.json").string() + " --size 64x32 -o " +
                          (dir_ / "quads.exr").string() + " --explain");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(Count(r.out, "load: mesh"), 1) << r.out;
  EXPECT_NE(r.out.find("(2 triangles, 4 vertices, normals computed)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("reuse: mesh"), std::string::npos) << r.out;
  EXPECT_EQ(Count(r.out, "draw: object"), 2) << r.out;
  // A white Lambert quad facing a unit directional light along its normal shows the light
  // colour (pi convention): radiance 1 inside both quads.
  const Image img = ReadExr(dir_ / "quads.exr");
  const float* left = img.At(16, 16);
  const float* right = img.At(48, 16);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(left[c], 1.0f, 1e-5f);
    EXPECT_NEAR(right[c], 1.0f, 1e-5f);
  }

  { std::ofstream(dir_ / "quad.obj") << "v 0 0 0\nf 1 2 3\n"; }
  const CliRun bad =
      RunCli("render " + (dir_ / "scene.json").string() + " -o " + (dir_ / "bad.png").string());
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("quad.obj"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

// --window without a display: a clear error and exit 2, nothing written.
TEST_F(RenderCli, WindowWithoutDisplayExitsTwo) {
  const std::string scene = std::string(BRDFIT_SOURCE_DIR) + "/data/scenes/ggx_point.json";
  const CliRun n = RunCli("render " + scene + " --size 64x64");
  EXPECT_EQ(n.code, 2);
  EXPECT_NE(n.out.find("-o out.png (or --window)"), std::string::npos) << n.out;
  const CliRun w =
      RunShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(BRDFIT_EXE) + " render " + scene +
               " --window --frames 1 -o " + (dir_ / "w.png").string());
  EXPECT_EQ(w.code, 2) << w.out;
  EXPECT_NE(w.out.find("no window"), std::string::npos) << w.out;
  EXPECT_FALSE(fs::exists(dir_ / "w.png"));
}

// --window on a virtual X display (xvfb-run, installed by scripts/setup-deps.sh): the pixels
// read back from the window are the headless render of the same scene (same renderer, same
// Mesa llvmpipe; within one 8-bit step: the window's 8-bit conversion rounds on its own).
TEST_F(RenderCli, WindowFrameMatchesTheHeadlessRender) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "xvfb-run not installed: window mode not tested (scripts/setup-deps.sh)";
  }
  const std::string scene = std::string(BRDFIT_SOURCE_DIR) + "/data/scenes/ggx_spot.json";
  const CliRun h = RunCli("render " + scene + " --size 128x96 -o " + (dir_ / "h.png").string());
  ASSERT_EQ(h.code, 0) << h.out;
  const CliRun w = RunShell(
      "xvfb-run -a -s '-screen 0 640x480x24' " + std::string(BRDFIT_EXE) + " render " + scene +
      " --window --frames 3 --explain --size 128x96 -o " + (dir_ / "w.png").string());
  ASSERT_EQ(w.code, 0) << w.out;
  EXPECT_NE(w.out.find("window: 3 frames shown, 1 rendered"), std::string::npos) << w.out;
  const Image a = ReadPng(dir_ / "h.png"), b = ReadPng(dir_ / "w.png");
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  float worst = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
  EXPECT_LE(worst, 1.0f / 255.0f + 1e-6f);
  float sum = 0;
  for (float v : b.rgba) sum += v;
  EXPECT_GT(sum, 0.0f);  // something was drawn
}

}  // namespace
}  // namespace brdfit::preview
