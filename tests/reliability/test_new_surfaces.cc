// The promise on the surfaces added since the first adversarial pass (docs/reliability.md,
// "The new surfaces"): bad input to merge, report, factor, fit -q and render is refused with
// the file and the problem named and a non-zero exit, before any work and with nothing written.
// Resume of a changed table and merges of different runs: tests/pipeline/test_shard_merge.cc;
// names in exported files: tests/export/check_hostile_names.py; scene ranges:
// tests/preview/test_scene.cc.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
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
#include "tmpfs_mount.h"

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
  // The fitted parameters of the table as `brdfit fit --json` writes them (ggx on the table).
  fs::path FitParamsJson() {
    const fs::path json = dir_ / "fits.json";
    const CliRun r = Brdfit({"fit", table_.string(), "--model", "ggx", "-q", "--json",
                             json.string(), "-o", (dir_ / "fits.h5").string()},
                            dir_ / "fit.log");
    EXPECT_EQ(r.code, 0) << r.log;
    return json;
  }
  void EditSidecar(const fs::path& sidecar,
                   const std::function<void(nlohmann::ordered_json&)>& edit) {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(ReadAll(sidecar));
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
  {  // A factor folder and a fit report: both parts named with their kinds.
    const CliRun r =
        Brdfit({"merge", (dir_ / "mixed").string(), good.string(), table_.string()},
               dir_ / "mixed.log");
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr(good.string() + " is a factor folder but " + table_.string() +
                                 " is a fit report"));
    EXPECT_FALSE(fs::exists(dir_ / "mixed"));
  }
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
         EditSidecar(d / "t.factor.json",
                     [](nlohmann::ordered_json& j) { j["format_version"] = 99; });
       },
       "t.factor.json", "unsupported format_version 99"},
      {"self-reference",
       [&](const fs::path& d) {
         EditSidecar(d / "t.factor.json", [](nlohmann::ordered_json& j) {
           j["textures"]["p"]["file"] = "t.factor.json";
         });
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
                     [](nlohmann::ordered_json& j) { j["textures"]["q"]["width"] = 9; });
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
  // A part that holds no factorization, and an output inside a part, are refused too.
  fs::create_directories(dir_ / "empty");
  CliRun e =
      Brdfit({"merge", (dir_ / "m-empty").string(), (dir_ / "empty").string()}, dir_ / "empty.log");
  EXPECT_EQ(e.code, 2) << e.log;
  EXPECT_THAT(e.log, HasSubstr("holds no factorization"));
  EXPECT_FALSE(fs::exists(dir_ / "m-empty"));
  e = Brdfit({"merge", (good / "sub").string(), good.string()}, dir_ / "inside.log");
  EXPECT_EQ(e.code, 2) << e.log;
  EXPECT_THAT(e.log, HasSubstr("inside it: merge into a folder outside every part"));
  EXPECT_FALSE(fs::exists(good / "sub"));
  // A sidecar naming a texture outside its folder is refused by every reader (export too).
  const fs::path outside = dir_ / "outside";
  fs::copy(good, outside);
  fs::create_directories(dir_ / "elsewhere");
  fs::copy_file(good / "t.p.exr", dir_ / "elsewhere" / "t.p.exr");
  EditSidecar(outside / "t.factor.json", [](nlohmann::ordered_json& j) {
    j["textures"]["p"]["file"] = "../elsewhere/t.p.exr";
  });
  e = Brdfit({"export", (outside / "t.factor.json").string(), "--format", "threejs", "-o",
              (dir_ / "o.mjs").string()},
             dir_ / "outside.log");
  EXPECT_EQ(e.code, 2) << e.log;
  EXPECT_THAT(e.log, HasSubstr("textures.p.file '../elsewhere/t.p.exr' is not a file name in the "
                               "sidecar's folder"));
  EXPECT_FALSE(fs::exists(dir_ / "o.mjs"));
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
  EditSidecar(sidecar, [&](nlohmann::ordered_json& j) {
    j["source"]["file"] = (dir_ / "gone.h5").string();
  });
  CliRun r = Brdfit({"report", sidecar.string(), "-o", (dir_ / "r.html").string()}, dir_ / "r.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_THAT(r.log,
              HasSubstr("brdfit: warning: material 't': its table " + (dir_ / "gone.h5").string() +
                        " (named by the results) is missing: no slices or renders"));
  EXPECT_THAT(ReadAll(dir_ / "r.html"), HasSubstr("(named by the results) is missing"));

  for (const char* device : {"/dev/zero", "/dev/null"}) {
    SCOPED_TRACE(device);
    EditSidecar(sidecar, [&](nlohmann::ordered_json& j) { j["source"]["file"] = device; });
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

// A fits JSON's text with its first fit edited (ordered: the parameters keep the model's order).
std::string FirstFitEdited(const std::string& text,
                           const std::function<void(nlohmann::ordered_json&)>& edit) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(text);
  edit(j["fits"][0]);
  return j.dump();
}

// A fits JSON whose member has another type than the reader expects is refused naming the file
// and the fit (it was the JSON library's bare type_error); control characters in a name are
// escaped in the message, never sent to the terminal.
TEST_F(NewSurfaces, FitsJsonOfTheWrongTypeNamesTheFileAndMessagesEscapeControls) {
  const fs::path json = FitParamsJson();
  // ordered_json: the parameters' order is the model's.
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(ReadAll(json));
  j["fits"][0]["chosen"] = "yes";
  std::ofstream(dir_ / "typed.json") << j.dump();
  CliRun r = Brdfit({"export", (dir_ / "typed.json").string(), "--format", "gltf", "-o",
                     (dir_ / "x.gltf").string()},
                    dir_ / "typed.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr((dir_ / "typed.json").string() +
                               ": fits[0].chosen is string, not true or false"));
  EXPECT_FALSE(fs::exists(dir_ / "x.gltf"));
  // A model name with an escape sequence and a newline: one line, the bytes escaped.
  j = nlohmann::ordered_json::parse(ReadAll(json));
  j["fits"][0]["model"] = "\x1b]0;pwn\x07\nforged line";
  std::ofstream(dir_ / "esc.json") << j.dump();
  r = Brdfit({"export", (dir_ / "esc.json").string(), "--format", "gltf", "-o",
              (dir_ / "y.gltf").string()},
             dir_ / "esc.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("\\x1b]0;pwn\\x07\\x0aforged line"));
  EXPECT_EQ(r.log.find('\x1b'), std::string::npos);
  EXPECT_EQ(std::count(r.log.begin(), r.log.end(), '\n'), 1) << r.log;
}

// Every reader of a fits JSON is one reader (io/fit_params_json.h with io/result_json.h): export
// and report refuse the same damage with the same words, where export read an absent error of
// a usable fit as 0 and an unknown status as "failed".
TEST_F(NewSurfaces, ExportAndReportReadAFitsJsonWithOneStrictness) {
  const fs::path json = FitParamsJson();
  const std::string text = ReadAll(json);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {FirstFitEdited(text, [](auto& f) { f["metrics"].erase("log_rmse"); }),
       "fits[0].metrics.log_rmse is missing"},
      {FirstFitEdited(text, [](auto& f) { f.erase("metrics"); }), "fits[0].metrics is missing"},
      {FirstFitEdited(text, [](auto& f) { f["status"] = "great"; }),
       "fits[0].status is 'great', not"},
      {FirstFitEdited(text, [](auto& f) { f["metrics"]["rendered"]["psnr_db"] = nullptr; }),
       "fits[0].metrics.rendered.psnr_db is null, not a number"},
  };
  for (const auto& [bad, problem] : cases) {
    SCOPED_TRACE(problem);
    std::ofstream(dir_ / "bad.json") << bad;
    const CliRun exported = Brdfit({"export", (dir_ / "bad.json").string(), "--format", "gltf",
                                    "-o", (dir_ / "x.gltf").string()},
                                   dir_ / "export.log");
    const CliRun reported =
        Brdfit({"report", (dir_ / "bad.json").string(), "-q", "-o", (dir_ / "r.html").string()},
               dir_ / "report.log");
    for (const CliRun* r : {&exported, &reported}) {
      EXPECT_EQ(r->code, 2) << r->log;
      EXPECT_THAT(r->log, HasSubstr((dir_ / "bad.json").string() + ": " + problem));
    }
    EXPECT_FALSE(fs::exists(dir_ / "x.gltf"));
    EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  }
}

// The fits JSON reader holds every member to what the writer makes: a key twice, a negative
// error measure, an at_bound, metrics or choice of another type, are refused naming the member.
// export -o - is refused (it writes files); one table under two names (a link) is one table.
TEST_F(NewSurfaces, FitsJsonMembersAndInputIdentityAreChecked) {
  const fs::path json = FitParamsJson();
  const std::string text = ReadAll(json);
  // Whole-file damage too: numbers JSON cannot hold, invalid UTF-8, two chosen fits of a
  // material.
  nlohmann::ordered_json two = nlohmann::ordered_json::parse(text);
  two["fits"][0]["chosen"] = true;
  two["fits"].push_back(two["fits"][0]);
  two["fits"][1]["params"]["ggx.alpha"] = 0.5;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {FirstFitEdited(text, [](auto& f) { f["metrics"]["log_rmse"] = -1; }),
       "fits[0].metrics.log_rmse is -1, below 0"},
      {FirstFitEdited(text, [](auto& f) { f["at_bound"] = "ggx.alpha"; }),
       "fits[0].at_bound is not an array"},
      {FirstFitEdited(text, [](auto& f) { f["at_bound"] = nlohmann::ordered_json::array({1}); }),
       "fits[0].at_bound holds a non-name"},
      {FirstFitEdited(text, [](auto& f) { f["metrics"] = "good"; }),
       "fits[0].metrics is not an object"},
      {FirstFitEdited(text, [](auto& f) { f["choice"] = 3; }),
       "fits[0].choice is number, not a string"},
      {FirstFitEdited(text, [](auto& f) { f["metrics"]["rendered"]["ok"] = "yes"; }),
       "fits[0].metrics.rendered.ok is string, not true or false"},
      // A key twice: the text itself, nlohmann would keep the last.
      {std::string(text).insert(text.find("\"model\""), "\"model\": \"ward\", "),
       "duplicate key 'model' in fits[0]"},
      {std::string(text).insert(text.find("\"log_rmse\""), "\"huge\": 1e999, "),
       "not valid JSON: "},
      {std::string(text).insert(text.find("\"log_rmse\""), "\"nan\": NaN, "), "not valid JSON: "},
      {std::string(text).insert(text.find("\"material\": \"") + 13, "\xff\xfe"),
       "not valid JSON: "},
      {two.dump(), "fits[0] and fits[1] are both chosen for material"},
  };
  for (const auto& [bad, problem] : cases) {
    SCOPED_TRACE(problem);
    std::ofstream(dir_ / "bad.json") << bad;
    CliRun r = Brdfit({"export", (dir_ / "bad.json").string(), "--format", "gltf", "-o",
                       (dir_ / "x.gltf").string()},
                      dir_ / "bad.log");
    EXPECT_EQ(r.code, 2) << r.log;
    EXPECT_THAT(r.log, HasSubstr((dir_ / "bad.json").string() + ": " + problem));
    EXPECT_FALSE(fs::exists(dir_ / "x.gltf"));
  }
  // A .gltf and its .bin are written together or not at all: a .bin that cannot be written
  // leaves the .gltf it would have replaced as it was.
  fs::create_directory(dir_ / "d.bin");
  std::ofstream(dir_ / "d.gltf") << "old";
  CliRun r = Brdfit({"export", json.string(), "--format", "gltf", "-o", (dir_ / "d.gltf").string()},
                    dir_ / "dir.log");
  EXPECT_NE(r.code, 0) << r.log;
  EXPECT_THAT(r.log, HasSubstr("d.bin"));
  EXPECT_EQ(ReadAll(dir_ / "d.gltf"), "old");
  r = Brdfit({"export", json.string(), "--format", "gltf", "-o", "-"}, dir_ / "dash.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("-o -: export writes files"));
  // The same table under two names.
  fs::create_symlink(table_, dir_ / "alias.h5");
  r = Brdfit({"fit", table_.string(), (dir_ / "alias.h5").string(), "--model", "ggx", "-q", "-o",
              (dir_ / "two.h5").string()},
             dir_ / "alias.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("are the same file (a link?)"));
  EXPECT_FALSE(fs::exists(dir_ / "two.h5"));
}

// Names with control characters (a file name, a scene's material) never reach the terminal
// raw: not in errors, the fit's table and progress lines, info, or render --explain.
TEST_F(NewSurfaces, ControlCharactersInNamesAreEscapedInEveryOutput) {
  const fs::path odd = dir_ / "x\x1b[31mRED.h5";
  fs::copy_file(table_, odd);
  CliRun r = Brdfit({"fit", odd.string(), "--model", "ggx", "-o", (dir_ / "f.h5").string()},
                    dir_ / "fit.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_THAT(r.log, HasSubstr("x\\x1b[31mRED"));
  EXPECT_EQ(r.log.find('\x1b'), std::string::npos) << r.log;
  r = Brdfit({"info", odd.string()}, dir_ / "info.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(r.log.find('\x1b'), std::string::npos) << r.log;
  std::ofstream(dir_ / "esc.json")
      << "{\"materials\": {\"m\\u001b]0;pwn\\u0007\\nX\": {\"type\": \"analytic\", "
         "\"model\": \"ggx\"}}, \"objects\": [{\"material\": \"m\\u001b]0;pwn\\u0007\\nX\"}]}";
  r = Brdfit({"render", (dir_ / "esc.json").string(), "-o", (dir_ / "e.png").string(), "--explain"},
             dir_ / "render.log");
  EXPECT_EQ(r.code, 0) << r.log;
  EXPECT_THAT(r.log, HasSubstr("m\\x1b]0;pwn\\x07\\x0aX"));
  EXPECT_EQ(r.log.find('\x1b'), std::string::npos) << r.log;
  EXPECT_EQ(r.log.find('\x07'), std::string::npos) << r.log;
}

// The report's lock file (".<report>.lock", its pid written into it) is never written through
// a link or onto an input: a planted symbolic link truncated the input it pointed to.
TEST_F(NewSurfaces, TheReportLockIsNeverWrittenThroughALinkOrOntoAnInput) {
  const std::string input = ReadAll(table_);
  const auto fit = [&](const fs::path& report, const std::string& tag) {
    return Brdfit({"fit", table_.string(), "--model", "ggx", "-q", "-o", report.string()},
                  dir_ / (tag + ".log"));
  };
  // A symbolic link to the input under the lock's name.
  fs::create_symlink(table_, dir_ / ".a.h5.lock");
  CliRun r = fit(dir_ / "a.h5", "a");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr(".a.h5.lock"));
  EXPECT_TRUE(ReadAll(table_) == input) << "the input was written through the lock's link";
  // A symbolic link to another file.
  std::ofstream(dir_ / "precious.txt") << "keep me";
  fs::create_symlink(dir_ / "precious.txt", dir_ / ".b.h5.lock");
  r = fit(dir_ / "b.h5", "b");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("symbolic link"));
  EXPECT_EQ(ReadAll(dir_ / "precious.txt"), "keep me");
  // A hard link to another file.
  fs::create_hard_link(dir_ / "precious.txt", dir_ / ".c.h5.lock");
  r = fit(dir_ / "c.h5", "c");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("not a regular file of its own"));
  EXPECT_EQ(ReadAll(dir_ / "precious.txt"), "keep me");
  // An input named like the report's lock.
  const fs::path odd = dir_ / ".d.h5.lock";
  fs::copy_file(table_, odd);
  r = Brdfit({"fit", odd.string(), "--model", "ggx", "-q", "-o", (dir_ / "d.h5").string()},
             dir_ / "d.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("the report's lock"));
  EXPECT_TRUE(ReadAll(odd) == input);
  for (const char* report : {"a.h5", "b.h5", "c.h5", "d.h5"})
    EXPECT_FALSE(fs::exists(dir_ / report));
}

// OpenEXR outputs on a full disk: exit 2 naming the file, nothing under the final name (the
// library's own file stream did not check its last writes: a 0-byte .exr with exit 0), and a
// factorization folder rewritten there keeps its previous textures whole.
TEST_F(NewSurfaces, OpenExrOutputsOnAFullDiskFailWithNothingWritten) {
  std::ofstream(dir_ / "s.json") << R"({"image": {"width": 16, "height": 16},
             "materials": {"m": {"type": "analytic", "model": "lambert+ggx"}},
             "objects": [{"material": "m"}]})";
  testing_cli::TmpfsMount disk(dir_ / "disk", 24);
  if (!disk.mounted()) GTEST_SKIP() << disk.why();
  // A full disk and a small file (16 x 16, unlit: it compresses to a few hundred bytes):
  // OpenEXR's file stream buffered all of it and lost it at close, unchecked.
  {
    std::ofstream fill(disk.path() / "filler", std::ios::binary);
    const std::string block(1024, '\0');
    for (int i = 0; i < 64 && fill; ++i) fill << block;
  }
  const fs::path exr = disk.path() / "r.exr";
  CliRun r = Brdfit({"render", (dir_ / "s.json").string(), "-o", exr.string()}, dir_ / "r.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr(exr.string()));
  EXPECT_FALSE(fs::exists(exr)) << "a cut EXR under the final name";
  // A factorization rewritten on the full disk: its previous files stay whole and readable.
  fs::remove(disk.path() / "filler");
  const fs::path fac = disk.path() / "fac";
  r = Brdfit(
      {"factor", table_.string(), "--param", "mccool", "--res", "8", "-q", "-o", fac.string()},
      dir_ / "f1.log");
  ASSERT_EQ(r.code, 0) << r.log;
  {
    std::ofstream fill(disk.path() / "filler", std::ios::binary);
    const std::string block(1024, '\0');
    for (int i = 0; i < 64 && fill; ++i) fill << block;
  }
  r = Brdfit({"factor", table_.string(), "--param", "mccool", "--res", "8", "--lambda", "1e-3",
              "-q", "-o", fac.string()},
             dir_ / "f2.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("write failed"));
  for (const auto& e : fs::directory_iterator(fac)) {
    EXPECT_GT(fs::file_size(e.path()), 0u) << e.path() << ": an empty file under a final name";
  }
  // The folder still reads as a factorization (every file whole): it exports.
  r = Brdfit({"export", (fac / "t.factor.json").string(), "--format", "threejs", "-o",
              (dir_ / "x.mjs").string()},
             dir_ / "x.log");
  EXPECT_EQ(r.code, 0) << r.log;
}

}  // namespace
}  // namespace brdfit
