// Factorization files of rank K with a diffuse value (format version 2): a hand-built
// factorization written and read back evaluates bit for bit alike; version 1 still loads;
// inconsistent sidecars are InputErrors naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/factor_io.h"
#include "pipeline/factor_export.h"
#include "tests/factor/factor_test_util.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::array<double, 3> kDiffuse{0.011, 0.0234567, 0.037};

Factorization HandBuilt(FactorParam param, int rank, std::array<double, 3> diffuse) {
  Factorization r;
  r.options.param = param;
  r.options.rank = rank;
  r.options.diffuse = diffuse[0] > 0;
  r.brdf = testing::HandBuiltFactoredBrdf(param, rank, diffuse);
  return r;
}

json ReadJsonFile(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}
void WriteJsonFile(const fs::path& p, const json& j) {
  std::ofstream(p) << j.dump(2);
}

// Random directions of the upper hemisphere, some near the horizon.
std::vector<Vec3> Directions(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> out;
  for (int k = 0; k < n; ++k) out.push_back(FromSpherical(u(rng) * 1.55, u(rng) * 2 * kPi));
  return out;
}

TEST(FactorIoRank, FileNamesOfEveryTerm) {
  const FactorPaths p = FactorFilePaths("d", "m", 3);
  ASSERT_EQ(p.terms.size(), 3u);
  EXPECT_EQ(p.terms[0].p, fs::path("d/m.p.exr"));
  EXPECT_EQ(p.terms[0].q, fs::path("d/m.q.exr"));
  EXPECT_EQ(p.terms[1].p, fs::path("d/m.p2.exr"));
  EXPECT_EQ(p.terms[2].q, fs::path("d/m.q3.exr"));
  EXPECT_EQ(p.All().size(), 7u);
  EXPECT_EQ(p.All().back(), fs::path("d/m.factor.json"));  // written last
  EXPECT_EQ(FactorTextureName(3, true), "q4");
  EXPECT_THROW(FactorFilePaths("d", "m", 0), OutputError);
  EXPECT_THROW(FactorFilePaths("d", "m", kFactorFileMaxRank + 1), OutputError);
}

TEST(FactorIoRank, RankTwoWithDiffuseEvaluatesBitForBitAfterReading) {
  const ScratchDir dir;
  for (FactorParam param : {FactorParam::kMcCool, FactorParam::kHalfDiff}) {
    SCOPED_TRACE(ToString(param));
    const Factorization r = HandBuilt(param, 2, kDiffuse);
    const FactorPaths paths = SaveFactorization(r, dir.path(), ToString(param));
    ASSERT_EQ(paths.terms.size(), 2u);
    for (const fs::path& f : paths.All()) EXPECT_TRUE(fs::exists(f)) << f;
    EXPECT_EQ(paths.terms[1].p.filename(), ToString(param) + std::string(".p2.exr"));

    const json j = ReadJsonFile(paths.json);
    EXPECT_EQ(j["format_version"], 2);
    EXPECT_EQ(j["rank"], 2);
    EXPECT_EQ(j["diffuse"].get<std::vector<double>>(),
              std::vector<double>(kDiffuse.begin(), kDiffuse.end()));
    EXPECT_DOUBLE_EQ(j["kd"][1].get<double>(), kPi * kDiffuse[1]);
    EXPECT_EQ(j["textures"]["p2"]["file"], paths.terms[1].p.filename().string());
    EXPECT_EQ(j["textures"]["q2"]["width"], r.brdf.terms()[1].q.width);
    EXPECT_EQ(j["textures"]["q2"]["height"], r.brdf.terms()[1].q.height);
    EXPECT_EQ(j["textures"]["q2"]["map"], ToString(GetFactorParamSpec(param).q.map));
    EXPECT_NE(j["formula"].get<std::string>().find("d + "), std::string::npos) << j["formula"];
    EXPECT_NE(j["formula"].get<std::string>().find(" + p2("), std::string::npos) << j["formula"];
    EXPECT_EQ(j["solver"]["rank"], 2);
    EXPECT_EQ(j["solver"]["diffuse"], true);
    ExrAttributes a;
    ReadRgbExr(paths.terms[1].q, &a);
    EXPECT_EQ(a.at(kExrAttrFactor), "q2");
    EXPECT_EQ(a.at(kExrAttrFormat), "brdfit-factorization 2");

    const FactoredBrdf back = LoadFactoredBrdf(paths.json);
    ASSERT_EQ(back.rank(), 2);
    EXPECT_EQ(back.diffuse(), r.brdf.diffuse());  // doubles through JSON, bit for bit
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(back.terms()[k].p, r.brdf.terms()[k].p);
      EXPECT_EQ(back.terms()[k].q, r.brdf.terms()[k].q);
    }
    // The second term and the diffuse value both count: the first term alone is well away.
    const FactoredBrdf first_only(param, r.brdf.p(), r.brdf.q());
    int differ = 0;
    const auto dirs = Directions(600, 11);
    for (std::size_t k = 0; k + 1 < dirs.size(); k += 2) {
      const auto f = back.Eval(dirs[k], dirs[k + 1]);
      EXPECT_EQ(f, r.brdf.Eval(dirs[k], dirs[k + 1]));
      const auto f1 = first_only.Eval(dirs[k], dirs[k + 1]);
      differ += f[0] - f1[0] > kDiffuse[0] && f[2] - f1[2] > kDiffuse[2];
    }
    EXPECT_GT(differ, 250);  // of 300
  }
}

TEST(FactorIoRank, RankFourRoundTrips) {
  const ScratchDir dir;
  const Factorization r = HandBuilt(FactorParam::kHalfDiff, kFactorFileMaxRank, {0, 0, 0});
  const FactorPaths paths = SaveFactorization(r, dir.path(), "h4");
  EXPECT_EQ(paths.All().size(), 2u * kFactorFileMaxRank + 1);
  const FactoredBrdf back = LoadFactoredBrdf(paths.json);
  EXPECT_EQ(back.rank(), kFactorFileMaxRank);
  EXPECT_FALSE(back.has_diffuse());
  const auto dirs = Directions(200, 3);
  for (std::size_t k = 0; k + 1 < dirs.size(); k += 2) {
    EXPECT_EQ(back.Eval(dirs[k], dirs[k + 1]), r.brdf.Eval(dirs[k], dirs[k + 1]));
  }
  // The sidecar names no texture beyond the rank, and the pure form's formula is a plain sum.
  const json j = ReadJsonFile(paths.json);
  EXPECT_FALSE(j["textures"].contains("p5"));
  EXPECT_EQ(j["formula"].get<std::string>().find("d + "), std::string::npos) << j["formula"];
}

TEST(FactorIoRank, VersionOneSidecarStillLoadsAsRankOneWithoutDiffuse) {
  const ScratchDir dir;
  const Factorization r = HandBuilt(FactorParam::kMcCool, 1, {0, 0, 0});
  const FactorPaths paths = SaveFactorization(r, dir.path(), "old");
  json j = ReadJsonFile(paths.json);
  // What version 1 wrote: no rank, no diffuse. A stray "rank" does not make it rank 3.
  j["format_version"] = 1;
  j.erase("diffuse");
  j.erase("kd");
  j["rank"] = 3;
  WriteJsonFile(paths.json, j);
  const FactoredBrdf back = LoadFactoredBrdf(paths.json);
  EXPECT_EQ(back.rank(), 1);
  EXPECT_FALSE(back.has_diffuse());
  const auto dirs = Directions(100, 5);
  for (std::size_t k = 0; k + 1 < dirs.size(); k += 2) {
    EXPECT_EQ(back.Eval(dirs[k], dirs[k + 1]), r.brdf.Eval(dirs[k], dirs[k + 1]));
  }
}

// LoadFactoredBrdf(json) throws an InputError naming `named` and saying `what`.
void ExpectRejected(const fs::path& json_path, const fs::path& named, const std::string& what) {
  try {
    LoadFactoredBrdf(json_path);
    ADD_FAILURE() << "accepted; expected an error about " << what;
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(named.string()), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
  }
}

TEST(FactorIoRank, InconsistentSidecarsAreInputErrorsNamingFileAndProblem) {
  const ScratchDir dir;
  const FactorPaths paths =
      SaveFactorization(HandBuilt(FactorParam::kMcCool, 2, kDiffuse), dir.path(), "m");
  const json good = ReadJsonFile(paths.json);
  const fs::path bad = dir / "bad.factor.json";  // beside the textures it names
  struct Case {
    const char* what;  // expected in the message
    std::function<void(json&)> edit;
  };
  const std::vector<Case> cases = {
      {"rank 5 is not an integer in [1, 4]", [](json& j) { j["rank"] = 5; }},
      {"rank 0", [](json& j) { j["rank"] = 0; }},
      {"rank -1", [](json& j) { j["rank"] = -1; }},
      {"rank \"2\"", [](json& j) { j["rank"] = "2"; }},
      {"rank 2.0", [](json& j) { j["rank"] = 2.0; }},
      // Would be 2 through a narrowing get<int>().
      {"rank 4294967298", [](json& j) { j["rank"] = 4294967298LL; }},
      {"rank 18446744073709551615", [](json& j) { j["rank"] = UINT64_MAX; }},
      {"missing 'rank'", [](json& j) { j.erase("rank"); }},
      {"missing textures.p3", [](json& j) { j["rank"] = 3; }},
      {"missing textures.q2", [](json& j) { j["textures"].erase("q2"); }},
      {"textures.p3: not a texture of a rank-2",
       [](json& j) { j["textures"]["p3"] = j["textures"]["p2"]; }},
      {"diffuse value -0.1 is negative", [](json& j) { j["diffuse"][1] = -0.1; }},
      {"diffuse [0.1,0.2] is not an array of three",
       [](json& j) {
         j["diffuse"] = {0.1, 0.2};
       }},
      {"diffuse null", [](json& j) { j["diffuse"] = nullptr; }},  // NaN is written as null
      {"not an array of three numbers", [](json& j) { j["diffuse"][2] = nullptr; }},
      {"missing 'diffuse'", [](json& j) { j.erase("diffuse"); }},
      {"unsupported format_version 3", [](json& j) { j["format_version"] = 3; }},
      {"unsupported format_version 4294967298",
       [](json& j) { j["format_version"] = 4294967298LL; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    json j = good;
    c.edit(j);
    WriteJsonFile(bad, j);
    ExpectRejected(bad, bad, c.what);
  }

  // Texture problems name the texture's file.
  json j = good;
  j["textures"]["p2"]["width"] = 7;
  WriteJsonFile(bad, j);
  ExpectRejected(bad, paths.terms[1].p, "the sidecar bad.factor.json says 7 x");
  j = good;
  j["textures"]["p2"]["file"] = "m.q2.exr";
  WriteJsonFile(bad, j);
  ExpectRejected(bad, paths.terms[1].q, "brdfit:factor is 'q2'");
  fs::remove(paths.terms[1].q);
  ExpectRejected(paths.json, paths.terms[1].q, "no such file");
}

TEST(FactorIoRank, WriterRefusesWhatTheReaderWouldRefuse) {
  const ScratchDir dir;
  FactorFiles f;
  f.sidecar = {{"parameterization", "mccool"}};
  f.terms.resize(1);
  f.terms[0].p.image = RgbImage::Filled(2, 2, 1.0f);
  f.terms[0].q.image = RgbImage::Filled(2, 2, 1.0f);
  f.diffuse = {0, -1e-3, 0};
  EXPECT_THROW(WriteFactorFiles(FactorFilePaths(dir.path(), "a", 1), f), InputError);
  f.diffuse = {0, NAN, 0};
  EXPECT_THROW(WriteFactorFiles(FactorFilePaths(dir.path(), "a", 1), f), InputError);
  f.diffuse = {0, 0, 0};
  EXPECT_THROW(WriteFactorFiles(FactorFilePaths(dir.path(), "a", 2), f), InputError);  // 1 term
  f.terms.resize(kFactorFileMaxRank + 1, f.terms[0]);
  FactorPaths many = FactorFilePaths(dir.path(), "a", kFactorFileMaxRank);
  many.terms.push_back(many.terms.back());
  EXPECT_THROW(WriteFactorFiles(many, f), InputError);
  EXPECT_FALSE(fs::exists(dir / "a.factor.json"));
}

}  // namespace
}  // namespace brdfit
