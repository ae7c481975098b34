// `brdfit fit --model auto` (pipeline/batch_fit.h kAutoCandidates, core/model_choice.h): the
// candidates and their losses, and on a table one candidate expresses exactly, that candidate is
// the one marked chosen, in the JSON and the HDF5 report, and stays so on a resumed run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model_choice.h"
#include "io/fit_report.h"
#include "io/table_io.h"
#include "pipeline/batch_fit.h"
#include "tests/fit/fit_test_util.h"
#include "tests/io/io_test_util.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing_io::RunCli;

TEST(ModelAuto, CandidatesKeepTheirLossesUnlessALossIsGiven) {
  const auto runs = pipeline::ResolveModelRuns({"auto"}, "lambert", false);
  ASSERT_EQ(runs.size(), pipeline::kAutoCandidates.size());
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i], pipeline::kAutoCandidates[i]);
  // With --loss given, models fitted twice under two losses become one run.
  const auto given = pipeline::ResolveModelRuns({"auto", "ggx"}, "lambert", true);
  std::map<std::string, int> count;
  for (const auto& r : given) {
    EXPECT_FALSE(r.loss) << r.model;
    ++count[r.model];
  }
  for (const auto& [m, n] : count) EXPECT_EQ(n, 1) << m;
  EXPECT_EQ(count.count("lambert+ggx"), 1u);
  EXPECT_EQ(count.count("lambert+abc"), 1u);
  // Plain names resolve as before.
  const auto plain = pipeline::ResolveModelRuns({"ggx:2"}, "lambert", false);
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_EQ(plain[0].model, "lambert+ggx+ggx");
  EXPECT_FALSE(plain[0].loss);
}

TEST(ModelAuto, TheCandidateThatExpressesTheTableIsChosen) {
  ScratchDir dir;
  // An Oren-Nayar (Fujii) + GGX table: oren-nayar-fujii+ggx reproduces it exactly, the other
  // candidates (two GGX lobes, Burley + GGX, ABC) only approximately.
  const std::vector<double> truth = testing::Params(
      "oren-nayar-fujii+ggx", {"oren-nayar-fujii.kd_r=0.30", "oren-nayar-fujii.kd_g=0.18",
                               "oren-nayar-fujii.kd_b=0.08", "oren-nayar-fujii.sigma=0.8",
                               "ggx.ks_r=0.5", "ggx.ks_g=0.4", "ggx.ks_b=0.3", "ggx.alpha=0.15"});
  const Table t = testing::SynthModel("oren-nayar-fujii+ggx", truth, testing::SmallGrid());
  const fs::path table = dir.path() / "t.h5", report = dir.path() / "fits.h5",
                 json = dir.path() / "fits.json";
  SaveTable(t, table);
  auto r = RunCli({"fit", table.string(), "--model", "auto", "-o", report.string(), "--json",
                   json.string(), "-j", "2", "--no-progress"},
                  dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("chosen: "), std::string::npos) << r.out;

  nlohmann::json j;
  std::ifstream(json) >> j;
  ASSERT_EQ(j["fits"].size(), pipeline::kAutoCandidates.size());
  int chosen = 0;
  for (const auto& f : j["fits"]) {
    if (!f["chosen"].get<bool>()) {
      EXPECT_FALSE(f.contains("choice"));
      continue;
    }
    ++chosen;
    EXPECT_EQ(f["model"], "oren-nayar-fujii+ggx");
    EXPECT_EQ(f["options"]["loss"], "rel");
    EXPECT_FALSE(f["choice"].get<std::string>().empty());
    // Exact recovery; the PSNR is then limited by the measured side's trilinear lookup between
    // cell centres (about 65 dB on this 30 x 30 x 60 grid).
    EXPECT_GT(f["metrics"]["rendered"]["psnr_db"].get<double>(), 55.0);
    EXPECT_NEAR(f["params"]["oren-nayar-fujii.sigma"].get<double>(), 0.8, 1e-4);
    EXPECT_NEAR(f["params"]["ggx.alpha"].get<double>(), 0.15, 1e-4);
  }
  EXPECT_EQ(chosen, 1);

  // The HDF5 report marks the same entry; the rule, applied to what it holds, agrees.
  const auto entries = ReadFitReport(report);
  std::vector<const FitResult*> fits;
  std::size_t marked = entries.size();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    fits.push_back(&entries[i].result);
    if (entries[i].chosen) marked = i;
  }
  ASSERT_LT(marked, entries.size());
  EXPECT_EQ(ChooseFit(fits)->index, marked);

  // Resumed: nothing is refitted and the mark stays.
  r = RunCli({"fit", table.string(), "--model", "auto", "-o", report.string(), "--no-progress"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("0 fits, " + std::to_string(pipeline::kAutoCandidates.size()) + " skipped"),
            std::string::npos)
      << r.out;
  const auto again = ReadFitReport(report);
  ASSERT_EQ(again.size(), entries.size());
  for (std::size_t i = 0; i < again.size(); ++i) EXPECT_EQ(again[i].chosen, i == marked);
}

// Cloth: a body, a faint broad highlight and a sheen at grazing angles. lambert+ggx+sheen
// reproduces it; the rough diffuse bodies (Burley, Oren-Nayar) brighten towards grazing too, but
// with another angular shape, so they render visibly worse and the sheen model is chosen.
TEST(ModelAuto, ClothIsFittedWithTheSheenLobe) {
  ScratchDir dir;
  const std::vector<double> truth = testing::Params(
      "lambert+ggx+sheen",
      {"lambert.kd_r=0.21", "lambert.kd_g=0.13", "lambert.kd_b=0.07", "ggx.ks_r=0.05",
       "ggx.ks_g=0.04", "ggx.ks_b=0.03", "ggx.alpha=0.4", "sheen.sheen_r=0.3",
       "sheen.sheen_g=0.2", "sheen.sheen_b=0.25", "sheen.alpha=0.15"});
  const Table t = testing::SynthModel("lambert+ggx+sheen", truth, testing::SmallGrid());
  const fs::path table = dir.path() / "cloth.h5", json = dir.path() / "fits.json";
  SaveTable(t, table);
  const auto r = RunCli({"fit", table.string(), "-o", (dir.path() / "fits.h5").string(),
                         "--json", json.string(), "-j", "2", "--no-progress"},
                        dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  nlohmann::json j;
  std::ifstream(json) >> j;
  double sheen_score = 0, best_other = -1e9;
  for (const auto& f : j["fits"]) {
    const auto& m = f["metrics"]["rendered"];
    const double s = std::min(m["psnr_db"].get<double>(), kScorePsnrCapDb) -
                     20 * m["median_rel_error"].get<double>();
    if (f["model"] == "lambert+ggx+sheen") {
      sheen_score = s;
      EXPECT_TRUE(f["chosen"].get<bool>()) << f["choice"];
      EXPECT_NEAR(f["params"]["sheen.alpha"].get<double>(), 0.15, 1e-3);
    } else {
      best_other = std::max(best_other, s);
      EXPECT_FALSE(f["chosen"].get<bool>()) << f["model"];
    }
  }
  EXPECT_GT(sheen_score, best_other + ModelChoiceOptions{}.tolerance_db);
}

}  // namespace
}  // namespace brdfit
