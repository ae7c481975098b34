// The promise on the surfaces added since the first adversarial pass (docs/reliability.md,
// "The new surfaces"): bad input to merge, report, factor, fit -q and render is refused with
// the file and the problem named and a non-zero exit, before any work and with nothing written.
// Resume of a changed table and merges of different runs: tests/pipeline/test_shard_merge.cc;
// names in exported files: tests/export/check_hostile_names.py; scene ranges:
// tests/preview/test_scene.cc.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_process.h"
#include "core/synth.h"
#include "io/hdf5_table.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing_cli::CliRun;
using testing_cli::ReadAll;

CliRun Brdfit(const std::vector<std::string>& args, const fs::path& log) {
  return testing_cli::Run(args, log);
}

class NewSurfaces : public ::testing::Test {
 protected:
  void SetUp() override {
    table_ = dir_ / "t.h5";
    const CliRun r =
        Brdfit({"synth", "--model", "lambert+ggx", "--grid", "16,16,32", "-o", table_.string()},
               dir_ / "synth.log");
    ASSERT_EQ(r.code, 0) << r.log;
  }
  // A factorization of the table into `folder` (mccool, 8 x 8 texels).
  void Factor(const fs::path& folder) {
    const CliRun r = Brdfit(
        {"factor", table_.string(), "--param", "mccool", "--res", "8", "-o", folder.string()},
        dir_ / "factor.log");
    ASSERT_EQ(r.code, 0) << r.log;
  }
  void EditSidecar(const fs::path& sidecar, const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(ReadAll(sidecar));
    edit(j);
    std::ofstream(sidecar) << j.dump();
  }

  ScratchDir dir_;
  fs::path table_;
};

// `factor --res 1024` was refused only after the whole mccool solve (minutes), when the
// halfdiff candidate of the automatic form came; now with the options, before any solve.
TEST_F(NewSurfaces, FactorResolutionIsCheckedBeforeAnySolve) {
  const fs::path out = dir_ / "f";
  CliRun r =
      Brdfit({"factor", table_.string(), "--res", "1024", "-o", out.string()}, dir_ / "a.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("--res 1024 is too large for halfdiff, one of the "
                               "parameterizations --auto tries (at most 256"));
  EXPECT_THAT(r.log, HasSubstr("give --param mccool"));
  EXPECT_THAT(r.log, ::testing::Not(HasSubstr("table ")));  // no table line: nothing solved
  r = Brdfit({"factor", table_.string(), "--res", "512", "--param", "halfdiff", "-o", out.string()},
             dir_ / "b.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("--res 512 is too large for halfdiff (at most 256"));
  EXPECT_FALSE(fs::exists(out));
  // The same limit in a scene's factored material of form auto.
  std::ofstream(dir_ / "scene.json")
      << R"({"materials": {"f": {"type": "factored", "table": "t.h5", "form": "auto",
                                 "resolution": 512}},
             "objects": [{"material": "f"}]})";
  r = Brdfit({"render", (dir_ / "scene.json").string(), "-o", (dir_ / "x.png").string()},
             dir_ / "c.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("'resolution' must be at most 256 with \"form\": \"auto\""));
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

// `merge` of factorization folders read every part as report, render and export will, before
// copying anything: a damaged part is refused naming the file.
TEST_F(NewSurfaces, MergeRefusesDamagedFactorFoldersNamingTheFile) {
  const fs::path good = dir_ / "good";
  Factor(good);
  struct Case {
    const char* name;
    std::function<void(const fs::path&)> damage;
    const char* file;     // the file the message names
    const char* problem;  // and the problem
  };
  const std::vector<Case> cases = {
      {"truncated-exr",
       [](const fs::path& d) {
         const std::string b = ReadAll(d / "t.p.exr");
         std::ofstream(d / "t.p.exr", std::ios::binary) << b.substr(0, b.size() / 2);
       },
       "t.p.exr", "OpenEXR"},
      {"garbage-exr", [](const fs::path& d) { std::ofstream(d / "t.q.exr") << "not an image"; },
       "t.q.exr", "not an OpenEXR file"},
      {"wrong-version",
       [&](const fs::path& d) {
         EditSidecar(d / "t.factor.json", [](nlohmann::json& j) { j["format_version"] = 99; });
       },
       "t.factor.json", "unsupported format_version 99"},
      {"self-reference",
       [&](const fs::path& d) {
         EditSidecar(d / "t.factor.json",
                     [](nlohmann::json& j) { j["textures"]["p"]["file"] = "t.factor.json"; });
       },
       "t.factor.json", "not an OpenEXR file"},
      {"swapped-textures",
       [](const fs::path& d) {
         fs::rename(d / "t.p.exr", d / "x");
         fs::rename(d / "t.q.exr", d / "t.p.exr");
         fs::rename(d / "x", d / "t.q.exr");
       },
       "t.p.exr", "attribute brdfit:factor is 'q'"},
      {"oversized-texture",
       [&](const fs::path& d) {
         EditSidecar(d / "t.factor.json",
                     [](nlohmann::json& j) { j["textures"]["q"]["width"] = 9; });
       },
       "t.q.exr", "image is 8 x 8, the sidecar t.factor.json says 9 x 8"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path part = dir_ / c.name, out = dir_ / (std::string("merged-") + c.name);
    fs::copy(good, part);
    c.damage(part);
    const CliRun r =
        Brdfit({"merge", out.string(), good.string(), part.string()}, dir_ / "merge.log");
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr((part / c.file).string())) << r.log;
    EXPECT_THAT(r.log, HasSubstr(c.problem)) << r.log;
    EXPECT_FALSE(fs::exists(out)) << "a damaged part was merged";
  }
  // The undamaged folder merges.
  const CliRun r = Brdfit({"merge", (dir_ / "m").string(), good.string()}, dir_ / "ok.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_TRUE(ReadAll(dir_ / "m" / "t.p.exr") == ReadAll(good / "t.p.exr"));
}

// `report` on a sidecar whose table is gone says so on stderr (the page still reports the
// numbers: results travel without their tables); one whose table is a device is refused.
TEST_F(NewSurfaces, ReportSaysWhenTheNamedTableIsMissingOrNotAFile) {
  Factor(dir_ / "f");
  const fs::path sidecar = dir_ / "f" / "t.factor.json";
  EditSidecar(sidecar,
              [&](nlohmann::json& j) { j["source"]["file"] = (dir_ / "gone.h5").string(); });
  CliRun r = Brdfit({"report", sidecar.string(), "-o", (dir_ / "r.html").string()}, dir_ / "r.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_THAT(r.log,
              HasSubstr("brdfit: warning: material 't': its table " + (dir_ / "gone.h5").string() +
                        " (named by the results) is missing: no slices or renders"));
  EXPECT_THAT(ReadAll(dir_ / "r.html"), HasSubstr("(named by the results) is missing"));

  for (const char* device : {"/dev/zero", "/dev/null"}) {
    SCOPED_TRACE(device);
    EditSidecar(sidecar, [&](nlohmann::json& j) { j["source"]["file"] = device; });
    const fs::path html = dir_ / "d.html";
    r = Brdfit({"report", sidecar.string(), "-o", html.string()}, dir_ / "d.log");
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr(std::string(device) +
                                 ": named as the table of material 't' but not a regular file"));
    EXPECT_FALSE(fs::exists(html));
  }
}

// `fit -q` keeps a success silent, not a failure: an all-negative table's failed fit is named
// on stderr with its reason, and the exit code says so.
TEST_F(NewSurfaces, QuietFitStillNamesItsFailure) {
  Grid g;
  g.n_theta_h = 8;
  g.n_theta_d = 8;
  g.n_phi_d = 16;
  // Every value negative: the writer masks them, the fit has no cell to use.
  const Table neg = SynthesizeTable(
      g, [](const Geometry&, double rgb[3]) { rgb[0] = rgb[1] = rgb[2] = -1.0; }, SynthOptions{});
  WriteHdf5Table(neg, dir_ / "neg.h5");
  const CliRun r = Brdfit({"fit", (dir_ / "neg.h5").string(), "--model", "ggx", "-q", "-o",
                           (dir_ / "neg-fits.h5").string()},
                          dir_ / "neg.log");
  EXPECT_NE(r.code, 0) << r.log;
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: " + (dir_ / "neg.h5").string() +
                               " lambert+ggx: fit failed: no usable cells"));
}

// A camera far outside the documented ranges rendered an all-black image with exit 0.
TEST_F(NewSurfaces, RenderRefusesACameraOutsideItsRange) {
  std::ofstream(dir_ / "far.json") << R"({"materials": {"m": {"type": "analytic", "model": "ggx"}},
             "camera": {"position": [0, 0, 1e308]}, "objects": [{"material": "m"}]})";
  const CliRun r =
      Brdfit({"render", (dir_ / "far.json").string(), "-o", (dir_ / "far.png").string()},
             dir_ / "far.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("far.json: camera: 'position' must be within 1e+06"));
  EXPECT_FALSE(fs::exists(dir_ / "far.png"));
}

}  // namespace
}  // namespace brdfit
