// `brdfit factor`: outputs on success, exit 2 naming the file on bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "io/hdf5_table.h"
#include "pipeline/factor_export.h"
#include "tests/factor/factor_test_util.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out, err;
};

std::string Slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CliRun Brdfit(const std::vector<std::string>& args, const fs::path& dir) {
  std::string cmd = std::string("'") + BRDFIT_EXE + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  cmd += " >'" + (dir / "out.txt").string() + "' 2>'" + (dir / "err.txt").string() + "'";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, Slurp(dir / "out.txt"),
          Slurp(dir / "err.txt")};
}

class FactorCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfit_test_factor_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    table_ = (dir_ / "product.h5").string();
    WriteHdf5Table(testing::McCoolProductTable(testing::SmallGrid()), table_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string table_;
};

TEST_F(FactorCli, WritesTexturesAndSidecar) {
  const CliRun r = Brdfit({"factor", table_, "--res", "16", "-o", (dir_ / "out").string()}, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path json = dir_ / "out" / "product.factor.json";
  EXPECT_TRUE(fs::exists(dir_ / "out" / "product.p.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "product.q.exr"));
  nlohmann::json sidecar;
  const FactoredBrdf b = LoadFactoredBrdf(json, &sidecar);
  EXPECT_EQ(b.p().width, 16);
  EXPECT_EQ(sidecar["source"]["file"], fs::absolute(table_).string());
  EXPECT_TRUE(sidecar["metrics"]["fit_metrics"]["ok"].get<bool>());
  EXPECT_LT(sidecar["metrics"]["ln_ratio_rmse"].get<double>(), 0.05);  // 16^2 texels
  EXPECT_NE(r.out.find("product"), std::string::npos) << r.out;
}

// The sidecar names the table as it was given: a relative input stays relative (an absolute
// path of the machine that wrote it was a known defect, issue 16).
TEST_F(FactorCli, SidecarKeepsARelativeSourceAsGiven) {
  const std::string cmd = "cd '" + dir_.string() + "' && '" + BRDFIT_EXE +
                          "' factor product.h5 --res 8 --param halfdiff -o out -q >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  nlohmann::json sidecar;
  LoadFactoredBrdf(dir_ / "out" / "product.factor.json", &sidecar);
  EXPECT_EQ(sidecar["source"]["file"], "product.h5");
}

// The default tries every candidate of factor/factor_choice.h and keeps the one the rule picks
// (checked here from the recorded scores, independently of ChooseFactorization); an option that
// names the form turns the choice off.
TEST_F(FactorCli, DefaultKeepsTheCandidateWithTheBestRenderedScore) {
  // A bright Lambert body under a separable lobe: one product cannot hold it.
  const Table t = testing::Tabulate(
      testing::SmallGrid(), [](const Vec3& wi, const Vec3& wo, const HalfDiffAngles& a) {
        const testing::Rgb pi = testing::TrueP(testing::ThetaOf(wi));
        const testing::Rgb po = testing::TrueP(testing::ThetaOf(wo));
        const testing::Rgb q = testing::TrueQh(a.theta_h);
        return testing::Rgb{0.5 + pi[0] * q[0] * po[0], 0.6 + pi[1] * q[1] * po[1],
                            0.7 + pi[2] * q[2] * po[2]};
      });
  const std::string table = (dir_ / "body.h5").string();
  WriteHdf5Table(t, table);
  const CliRun r = Brdfit({"factor", table, "--res", "16", "-o", (dir_ / "out").string()}, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json sidecar;
  const FactoredBrdf b = LoadFactoredBrdf(dir_ / "out" / "body.factor.json", &sidecar);
  const nlohmann::json& choice = sidecar.at("choice");
  ASSERT_EQ(choice.at("candidates").size(), 4u);
  double best = -1e300;
  for (const auto& c : choice["candidates"]) best = std::max(best, c["score_db"].get<double>());
  // The rule (factor/factor_choice.h): within 0.5 dB of the best S, the least texture memory,
  // then the fewest fetches per light, then the higher S.
  std::string expect;
  std::tuple<std::size_t, double, double> least{SIZE_MAX, 0, 0};
  for (const auto& c : choice["candidates"]) {
    const std::tuple<std::size_t, double, double> key{c["texture_bytes"].get<std::size_t>(),
                                                      c["fetches_per_light"].get<double>(),
                                                      -c["score_db"].get<double>()};
    if (c["score_db"].get<double>() >= best - 0.5 && key < least) {
      least = key;
      expect = c["form"].get<std::string>();
    }
  }
  EXPECT_EQ(choice["chosen"], expect);
  // The body needs more than one product: a diffuse value, or a second product that holds it.
  EXPECT_TRUE(b.has_diffuse() || b.rank() >= 2) << choice.dump(1);
  EXPECT_NE(r.out.find("<- chosen"), std::string::npos) << r.out;
  // The chosen form is what was written: its rendered metric is the candidate's.
  for (const auto& c : choice["candidates"]) {
    if (c["form"] == expect) {
      EXPECT_DOUBLE_EQ(c["psnr_db"].get<double>(),
                       sidecar["metrics"]["rendered"]["psnr_db"].get<double>());
    }
  }

  const CliRun e = Brdfit(
      {"factor", table, "--res", "16", "--rank", "1", "-o", (dir_ / "explicit").string()}, dir_);
  ASSERT_EQ(e.code, 0) << e.err;
  nlohmann::json explicit_sidecar;
  const FactoredBrdf one =
      LoadFactoredBrdf(dir_ / "explicit" / "body.factor.json", &explicit_sidecar);
  EXPECT_FALSE(explicit_sidecar.contains("choice"));
  EXPECT_EQ(one.rank(), 1);
  EXPECT_FALSE(one.has_diffuse());
}

// A refined halfdiff factorization is the slow sparse path: the command says so up front (on
// stderr), a mccool one does not.
TEST_F(FactorCli, RefinedHalfDiffSaysItIsSlow) {
  const CliRun h = Brdfit({"factor", table_, "--param", "halfdiff", "--res", "32", "--refine",
                           "-q", "-o", (dir_ / "h").string()},
                          dir_);
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_NE(h.err.find("sparse factorization per step"), std::string::npos) << h.err;
  EXPECT_NE(h.err.find("1056 unknowns"), std::string::npos) << h.err;  // 32 + 32^2
  const CliRun m = Brdfit(
      {"factor", table_, "--res", "32", "--refine", "-q", "-o", (dir_ / "m").string()}, dir_);
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(m.err.find("sparse factorization"), std::string::npos) << m.err;
}

// --rank K shows what each product buys: every rank 1..K scored like the result, its texture
// memory and fetches growing by one product each.
TEST_F(FactorCli, RankKReportsEveryLowerRank) {
  const CliRun r = Brdfit(
      {"factor", table_, "--res", "16", "--diffuse", "--rank", "3", "-o", (dir_ / "out").string()},
      dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json sidecar;
  const FactoredBrdf b = LoadFactoredBrdf(dir_ / "out" / "product.factor.json", &sidecar);
  ASSERT_EQ(b.rank(), 3);
  const nlohmann::json& ranks = sidecar.at("ranks");
  ASSERT_EQ(ranks.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(ranks[k]["rank"], k + 1);
    EXPECT_EQ(ranks[k]["fetches_per_light"], 2 * (k + 1));
    EXPECT_TRUE(ranks[k]["psnr_db"].is_number()) << ranks.dump(1);
    if (k > 0) {
      // One product more (two 16^2 float32 RGB textures); 12 B of d where one of them has d = 0.
      const double more =
          ranks[k]["texture_bytes"].get<double>() - ranks[k - 1]["texture_bytes"].get<double>();
      EXPECT_NEAR(more, 2 * 16 * 16 * 12, 12);
    }
  }
  EXPECT_DOUBLE_EQ(ranks[2]["psnr_db"].get<double>(),
                   sidecar["metrics"]["rendered"]["psnr_db"].get<double>());
  EXPECT_NE(r.out.find("rank 2: S"), std::string::npos) << r.out;
}

TEST_F(FactorCli, SecondTableReusesTheSystem) {
  fs::copy_file(table_, dir_ / "copy.h5");
  const CliRun r = Brdfit({"factor", table_, (dir_ / "copy.h5").string(), "--param", "halfdiff",
                           "--res", "8", "-o", (dir_ / "out").string()},
                          dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto a = nlohmann::json::parse(Slurp(dir_ / "out" / "product.factor.json"));
  const auto b = nlohmann::json::parse(Slurp(dir_ / "out" / "copy.factor.json"));
  EXPECT_FALSE(a["stats"]["system_reused"].get<bool>());
  EXPECT_TRUE(b["stats"]["system_reused"].get<bool>());
  EXPECT_EQ(b["parameterization"], "halfdiff");
}

TEST_F(FactorCli, BadInputsExitTwoNamingTheFile) {
  const std::string out = (dir_ / "out").string();
  const std::string missing = (dir_ / "missing.binary").string();
  CliRun r = Brdfit({"factor", missing, "-o", out}, dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;

  // A file that is no table: reported by name; the good table is still factored.
  const fs::path junk = dir_ / "junk.binary";
  std::ofstream(junk) << "not a table";
  r = Brdfit({"factor", junk.string(), table_, "--res", "8", "-o", out}, dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(junk.string()), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "product.factor.json"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "junk.factor.json"));

  for (const std::vector<std::string>& opts : {std::vector<std::string>{"--param", "svd"},
                                               {"--res", "2"},
                                               {"--lambda", "0"},
                                               {"--weighting", "none"},
                                               {"--max-theta", "95"}}) {
    std::vector<std::string> args = {"factor", table_, "-o", out};
    args.insert(args.end(), opts.begin(), opts.end());
    r = Brdfit(args, dir_);
    EXPECT_EQ(r.code, 2) << opts[0];
    EXPECT_NE(r.err.find("brdfit: error:"), std::string::npos) << r.err;
  }

  // Two inputs that would write the same outputs: the material keys a_b/product and
  // a/b/product (pipeline/material_keys.h) are both the file stem a_b_product. (One stem in two
  // folders is two materials with two stems: tests/pipeline/test_shard_factor_bench.cc.)
  fs::create_directories(dir_ / "a_b");
  fs::create_directories(dir_ / "a" / "b");
  fs::copy_file(table_, dir_ / "a_b" / "product.h5");
  fs::copy_file(table_, dir_ / "a" / "b" / "product.h5");
  r = Brdfit({"factor", (dir_ / "a_b" / "product.h5").string(),
              (dir_ / "a" / "b" / "product.h5").string(), "-o", out},
             dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("same outputs (a_b_product.*)"), std::string::npos) << r.err;
}

// The factored form's options: validated before any work, recorded in the sidecar's solver
// section, every texture of the rank written and the form shown in the table.
TEST_F(FactorCli, FormOptionsAreValidatedRecordedAndShown) {
  const std::string out = (dir_ / "out").string();
  for (const std::vector<std::string>& opts : {std::vector<std::string>{"--rank", "0"},
                                               {"--rank", "5"},
                                               {"--rank", "two"},
                                               {"--refine-iterations", "0"}}) {
    std::vector<std::string> args = {"factor", table_, "-o", out};
    args.insert(args.end(), opts.begin(), opts.end());
    const CliRun r = Brdfit(args, dir_);
    EXPECT_EQ(r.code, 2) << opts[0] << " " << opts[1];
    EXPECT_NE(r.err.find(opts[0]), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "product.factor.json"));
  }
  const std::string out_of_range = Brdfit({"factor", table_, "-o", out, "--rank", "5"}, dir_).err;
  EXPECT_NE(out_of_range.find("brdfit: error: --rank 5 outside [1, 4]"), std::string::npos)
      << out_of_range;

  const CliRun r = Brdfit({"factor", table_, "--res", "8", "--rank", "2", "--diffuse", "--refine",
                           "--refine-iterations", "7", "-o", out},
                          dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json sidecar;
  const FactoredBrdf b = LoadFactoredBrdf(dir_ / "out" / "product.factor.json", &sidecar);
  EXPECT_EQ(sidecar["solver"]["rank"], 2);
  EXPECT_EQ(sidecar["solver"]["diffuse"], true);
  EXPECT_EQ(sidecar["solver"]["refine"], true);
  EXPECT_EQ(sidecar["solver"]["refine_iterations"], 7);
  EXPECT_TRUE(sidecar["stats"].contains("refine_rel_rms"));
  // Whatever rank the solver returned, the sidecar says it and every texture of it is there.
  EXPECT_EQ(sidecar["rank"], b.rank());
  for (int k = 0; k < b.rank(); ++k) {
    const std::string n = k == 0 ? "" : std::to_string(k + 1);
    EXPECT_TRUE(fs::exists(dir_ / "out" / ("product.p" + n + ".exr"))) << k;
    EXPECT_TRUE(fs::exists(dir_ / "out" / ("product.q" + n + ".exr"))) << k;
  }
  EXPECT_NE(r.out.find("form"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("diffuse d = kd/pi = ("), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("rank 1 of the 2 asked for") != std::string::npos, b.rank() != 2) << r.out;

  const CliRun plain =
      Brdfit({"factor", table_, "--res", "8", "--diffuse", "--no-diffuse", "-o", out}, dir_);
  ASSERT_EQ(plain.code, 0) << plain.err;
  const auto j = nlohmann::json::parse(Slurp(dir_ / "out" / "product.factor.json"));
  EXPECT_EQ(j["solver"]["diffuse"], false);
  EXPECT_EQ(j["solver"]["rank"], 1);
  EXPECT_EQ(plain.out.find("diffuse d ="), std::string::npos) << plain.out;
}

// NBRDF inputs, as `brdfit fit` takes them: named by material, sidecar naming the input.
TEST_F(FactorCli, FactorsNbrdfInputsByName) {
  const fs::path zip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  if (!fs::exists(zip)) GTEST_SKIP() << zip << " not found: NBRDF inputs not tested";
  const fs::path out = dir_ / "out";
  const CliRun r = Brdfit({"factor", "nbrdf:pink-felt", "--res", "8", "-o", out.string()}, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "pink-felt.p.exr"));
  EXPECT_TRUE(fs::exists(out / "pink-felt.q.exr"));
  const std::string sidecar = Slurp(out / "pink-felt.factor.json");
  EXPECT_NE(sidecar.find("\"file\": \"nbrdf:pink-felt\""), std::string::npos) << sidecar;
  const CliRun bad = Brdfit({"factor", "nbrdf:no-such-material", "-o", out.string()}, dir_);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("no-such-material"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace brdfit
