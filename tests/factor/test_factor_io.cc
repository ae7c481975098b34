// Factorization files: EXR pair + JSON sidecar written, read back, evaluated identically.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "pipeline/factor_export.h"
#include "core/error.h"
#include "tests/factor/factor_test_util.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

Factorization Small(FactorParam param) {
  FactorOptions o;
  o.param = param;
  o.resolution = 16;
  const Table t = param == FactorParam::kMcCool
                      ? testing::McCoolProductTable(testing::SmallGrid())
                      : testing::HalfDiffProductTable(testing::SmallGrid());
  return Factor(t, o);
}

TEST(FactorIo, SaveLoadEvaluatesIdentically) {
  const ScratchDir scratch("roundtrip");
  const fs::path& dir = scratch.path();
  for (FactorParam param : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    const Factorization r = Small(param);
    const FactorPaths paths =
        SaveFactorization(r, dir, ToString(param), {{"source", {{"file", "x.binary"}}}});
    ASSERT_EQ(paths.terms.size(), 1u);
    EXPECT_TRUE(fs::exists(paths.terms[0].p));
    EXPECT_TRUE(fs::exists(paths.terms[0].q));
    nlohmann::json sidecar;
    const FactoredBrdf back = LoadFactoredBrdf(paths.json, &sidecar);
    EXPECT_EQ(back.param(), param);
    EXPECT_EQ(back.p(), r.brdf.p());  // float32 textures, bit for bit
    EXPECT_EQ(back.q(), r.brdf.q());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 200; ++k) {
      const Vec3 wi = FromSpherical(u(rng) * 1.5, u(rng) * 6.28);
      const Vec3 wo = FromSpherical(u(rng) * 1.5, u(rng) * 6.28);
      EXPECT_EQ(back.Eval(wi, wo), r.brdf.Eval(wi, wo));
    }
    EXPECT_EQ(sidecar["format"], kFactorFormat);
    EXPECT_EQ(sidecar["parameterization"], ToString(param));
    EXPECT_EQ(sidecar["formula"], GetFactorParamSpec(param).formula);
    EXPECT_EQ(sidecar["source"]["file"], "x.binary");
    EXPECT_EQ(sidecar["textures"]["p"]["file"], paths.terms[0].p.filename().string());
    EXPECT_EQ(sidecar["format_version"], 2);
    EXPECT_EQ(sidecar["rank"], 1);
    EXPECT_EQ(sidecar["diffuse"], nlohmann::json::array({0.0, 0.0, 0.0}));
    EXPECT_EQ(sidecar["textures"]["q"]["units"], GetFactorParamSpec(param).q.units);
    EXPECT_EQ(sidecar["solver"]["resolution"], 16);

    // Each EXR describes itself.
    ExrAttributes a;
    ReadRgbExr(paths.terms[0].q, &a);
    EXPECT_EQ(a.at("brdfit:parameterization"), ToString(param));
    EXPECT_EQ(a.at("brdfit:factor"), "q");
    EXPECT_EQ(a.at("brdfit:formula"), GetFactorParamSpec(param).formula);
    EXPECT_EQ(a.at("brdfit:map"), ToString(GetFactorParamSpec(param).q.map));
    EXPECT_FALSE(a.at("brdfit:map_formula").empty());
    EXPECT_FALSE(a.at("brdfit:units").empty());
    EXPECT_FALSE(a.at("brdfit:gauge").empty());
  }
  fs::remove_all(dir);
}

void ExpectInputError(const fs::path& json, const fs::path& named, const std::string& what) {
  try {
    LoadFactoredBrdf(json);
    FAIL() << "no error";
  } catch (const InputError& e) {
    SCOPED_TRACE(e.what());
    EXPECT_NE(std::string(e.what()).find(named.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(FactorIo, InconsistentFilesAreInputErrors) {
  const ScratchDir scratch("bad");
  const fs::path& dir = scratch.path();
  const FactorPaths m = SaveFactorization(Small(FactorParam::kMcCool), dir, "m");
  const FactorPaths hd = SaveFactorization(Small(FactorParam::kHalfDiff), dir, "h");
  const FactorTermPaths& paths = m.terms[0];

  // p and q swapped on disk.
  fs::rename(paths.p, dir / "tmp.exr");
  fs::rename(paths.q, paths.p);
  fs::rename(dir / "tmp.exr", paths.q);
  ExpectInputError(m.json, paths.p, "brdfit:factor");

  // A q texture of another parameterization.
  fs::copy_file(hd.terms[0].q, paths.q, fs::copy_options::overwrite_existing);
  fs::copy_file(hd.terms[0].p, paths.p, fs::copy_options::overwrite_existing);
  ExpectInputError(m.json, paths.p, "brdfit:parameterization");

  // Missing texture.
  SaveFactorization(Small(FactorParam::kMcCool), dir, "m");
  fs::remove(paths.q);
  ExpectInputError(m.json, paths.q, "no such file");

  // Not a sidecar.
  std::ofstream(dir / "x.factor.json") << R"({"format": "brdfit-table"})";
  ExpectInputError(dir / "x.factor.json", dir / "x.factor.json", "format");
  std::ofstream(dir / "y.factor.json") << "{ not json";
  ExpectInputError(dir / "y.factor.json", dir / "y.factor.json", "JSON");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace brdfit
