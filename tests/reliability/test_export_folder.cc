// `brdfit export FITS --format X -o DIR/`: every material of the fits, one file each, named
// after the material (export/write_export.h MaterialFileNames): hostile names stay inside the
// folder and collide with nothing; a material with nothing to export stops the command before
// anything is written; --material still selects.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cli_process.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing_cli::CliRun;
using testing_cli::ReadAll;

std::set<std::string> FilesIn(const fs::path& dir) {
  std::set<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// tests/export/data/fits.json (two materials, four fits each) with its second material's fits
// copied under each of `names`.
fs::path FitsWithMaterials(const fs::path& dir, const std::vector<std::string>& names) {
  std::ifstream in(fs::path(BRDFIT_SOURCE_DIR) / "tests/export/data/fits.json");
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(in);
  nlohmann::ordered_json fits = j["fits"];
  for (const std::string& n : names) {
    for (const auto& f : j["fits"]) {
      if (f["material"] != "red-phenolic") continue;
      nlohmann::ordered_json c = f;
      c["material"] = n;
      fits.push_back(c);
    }
  }
  j["fits"] = fits;
  const fs::path out = dir / "fits.json";
  std::ofstream(out) << j.dump(2);
  return out;
}

TEST(ExportFolder, EveryMaterialOneFileNamedSafely) {
  ScratchDir dir;
  const fs::path fits = FitsWithMaterials(
      dir.path(),
      {"../evil", "Gold-Metallic-Paint", "a b<x>\"'$(id)", ".hidden", "-rf", "a/b", "a:b"});
  const fs::path out = dir.path() / "scenes";
  CliRun r = testing_cli::Run(
      {"export", fits.string(), "--format", "pbrt", "-o", out.string() + "/"}, dir / "a.log");
  ASSERT_EQ(r.code, 0) << r.log;
  // Two materials of the file, then the copies: "Gold-Metallic-Paint" folds onto
  // gold-metallic-paint's name on case-insensitive file systems and gets "-2"; "a/b" and "a:b"
  // both become "a_b", the second "a_b-2".
  EXPECT_EQ(FilesIn(out),
            (std::set<std::string>{"gold-metallic-paint.pbrt", "red-phenolic.pbrt", "_._evil.pbrt",
                                   "Gold-Metallic-Paint-2.pbrt", "a_b_x_____id_.pbrt",
                                   "_hidden.pbrt", "_rf.pbrt", "a_b.pbrt", "a_b-2.pbrt"}));
  // Nothing outside the folder but the inputs and logs.
  EXPECT_EQ(FilesIn(dir.path()), (std::set<std::string>{"fits.json", "scenes", "a.log"}));
  // Each file is its material's scene: the source and material are named inside.
  EXPECT_THAT(ReadAll(out / "red-phenolic.pbrt"), HasSubstr("red-phenolic"));
  EXPECT_THAT(ReadAll(out / "gold-metallic-paint.pbrt"), HasSubstr("gold-metallic-paint"));
  EXPECT_THAT(r.log, HasSubstr("-> " + (out / "_rf.pbrt").string()));

  // glTF: each .gltf with its own .bin; an existing folder needs no trailing '/'.
  const fs::path gl = dir.path() / "gl";
  fs::create_directory(gl);
  r = testing_cli::Run({"export", fits.string(), "--format", "gltf", "-o", gl.string(), "-q"},
                       dir / "b.log");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(FilesIn(gl).size(), 18u);
  EXPECT_TRUE(fs::exists(gl / "_rf.gltf"));
  EXPECT_TRUE(fs::exists(gl / "_rf.bin"));

  // --material selects one.
  const fs::path one = dir.path() / "one";
  r = testing_cli::Run({"export", fits.string(), "--format", "mitsuba", "--material",
                        "red-phenolic", "-o", one.string() + "/"},
                       dir / "c.log");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_EQ(FilesIn(one), (std::set<std::string>{"red-phenolic.xml"}));
}

TEST(ExportFolder, AMaterialWithNothingToExportStopsBeforeAnythingIsWritten) {
  ScratchDir dir;
  fs::path fits = FitsWithMaterials(dir.path(), {"broken"});
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(ReadAll(fits));
  for (auto& f : j["fits"]) {
    if (f["material"] == "broken") f["status"] = "failed";
  }
  std::ofstream(fits) << j.dump(2);
  const fs::path out = dir.path() / "out";
  const CliRun r = testing_cli::Run(
      {"export", fits.string(), "--format", "glb", "-o", out.string() + "/"}, dir / "a.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("fits.json"));
  EXPECT_THAT(r.log, HasSubstr("broken"));
  EXPECT_TRUE(FilesIn(out).empty()) << "something was written";
}

}  // namespace
}  // namespace brdfit
