// The CLI's report, compare and bench commands, run as a user would: exit codes, outputs,
// messages that name the problem, and --help with examples for every subcommand.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/core.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "core/metrics.h"
#include "core/model_choice.h"
#include "factor/factor_form.h"
#include "io/fit_report.h"
#include "models/registry.h"
#include "pipeline/factor_export.h"
#include "report/bench_csv.h"
#include "tests/factor/factor_test_util.h"
#include "tests/report/report_fixture.h"

namespace brdfit::report {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out, err;
};

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           (std::string("brdfit-report-cli-") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  CliRun Brdfit(const std::string& args) {
    const std::string cmd = std::string(BRDFIT_EXE) + " " + args + " > " +
                            (dir_ / "out.txt").string() + " 2> " + (dir_ / "err.txt").string();
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = ReadText(dir_ / "out.txt");
    r.err = ReadText(dir_ / "err.txt");
    return r;
  }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }

  // Bench results of one material and two models.
  void WriteBench(const std::string& file, double gold_ggx, double gold_beckmann,
                  double plastic_ggx) {
    std::vector<BenchPoint> pts;
    auto add = [&](const char* material, const char* model, double err) {
      BenchPoint b;
      b.material = material;
      b.model = model;
      b.loss = "log";
      b.budget = "full";
      b.status = "converged";
      b.time_ms = 100;
      b.metrics = testing::Scored(err, 2 * err, 3 * err, 100);
      pts.push_back(b);
    };
    add("gold", "lambert+ggx", gold_ggx);
    add("gold", "lambert+beckmann", gold_beckmann);
    add("plastic", "lambert+ggx", plastic_ggx);
    WriteBenchCsv(dir_ / file, pts);
  }

  fs::path dir_;
};

TEST_F(Cli, CompareNamesTheRegressedMaterialAndFails) {
  WriteBench("old.csv", 0.010, 0.020, 0.030);
  WriteBench("new.csv", 0.0101, 0.0195, 0.036);  // plastic +20 %
  const CliRun r = Brdfit("compare " + P("old.csv") + " " + P("new.csv"));
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("REGRESSED: plastic"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("REGRESSED: gold"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("+20.0 %"), std::string::npos) << r.out;

  const CliRun j = Brdfit("compare --json " + P("old.csv") + " " + P("new.csv"));
  EXPECT_EQ(j.code, 1);
  const auto json = nlohmann::json::parse(j.out);
  EXPECT_EQ(json["regressed_materials"], nlohmann::json::array({"plastic"}));
  EXPECT_EQ(json["counts"]["worse"], 1);
  EXPECT_EQ(json["counts"]["same"], 2);

  // Within a looser threshold nothing regressed.
  const CliRun ok = Brdfit("compare --threshold 0.25 " + P("old.csv") + " " + P("new.csv"));
  EXPECT_EQ(ok.code, 0) << ok.out;
  EXPECT_NE(ok.out.find("no regressions"), std::string::npos);
  // Same file: no change at all.
  EXPECT_EQ(Brdfit("compare " + P("old.csv") + " " + P("old.csv")).code, 0);
}

TEST_F(Cli, CompareBadInputExitsTwoAndNamesTheFile) {
  WriteBench("old.csv", 0.01, 0.02, 0.03);
  CliRun r = Brdfit("compare " + P("old.csv") + " " + P("missing.csv"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos) << r.err;
  r = Brdfit("compare --metric psnr " + P("old.csv") + " " + P("old.csv"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("psnr"), std::string::npos) << r.err;
  r = Brdfit("compare " + P("old.csv"));
  EXPECT_EQ(r.code, 2);
}

TEST_F(Cli, ReportWritesOnePageAndRejectsBadInput) {
  WriteBench("bench.csv", 0.01, 0.02, 0.03);
  CliRun r = Brdfit("report " + P("bench.csv") + " -o " + P("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(dir_ / "r.html");
  EXPECT_NE(html.find("data-charts-expected=\"2\""), std::string::npos);
  EXPECT_NE(html.find("Chart.js v3"), std::string::npos);  // inlined, not linked

  std::ofstream(dir_ / "notes.txt") << "x";
  r = Brdfit("report " + P("notes.txt") + " -o " + P("r2.html"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("notes.txt"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "r2.html"));

  r = Brdfit("report " + P("bench.csv") + " --chart-js /no/chart.js -o " + P("r3.html"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("libjs-chart.js"), std::string::npos) << r.err;
}

TEST_F(Cli, BenchOnTwoSyntheticTablesWritesCsvAndPlot) {
  for (const char* name : {"a", "b"}) {
    const CliRun s = Brdfit(std::string("synth --model lambert+ggx --param alpha=0.2 --grid 16,16,32 -o ") +
                         P(std::string(name) + ".h5"));
    ASSERT_EQ(s.code, 0) << s.err;
  }
  const CliRun r = Brdfit("bench " + P("a.h5") + " " + P("b.h5") +
                       " --models lambert+ggx,lambert+beckmann --budgets full,stride:4"
                       " --losses log,cbrt -o " + P("bench.csv"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const auto pts = ReadBenchCsv(dir_ / "bench.csv");
  ASSERT_EQ(pts.size(), 2u * 2 * 2 * 2);  // tables x models x budgets x losses
  for (const auto& p : pts) {
    EXPECT_TRUE(p.metrics.ok) << p.material << " " << p.model << " " << p.budget;
    EXPECT_GT(p.time_ms, 0);
    EXPECT_EQ(p.status, "converged") << p.message;
  }
  // The generating model fits its own table better than the other model, at the full budget.
  for (const auto& p : pts) {
    if (p.model != "lambert+ggx" || p.budget != "full") continue;
    for (const auto& q : pts) {
      if (q.model == "lambert+beckmann" && q.budget == "full" && q.material == p.material &&
          q.loss == p.loss) {
        EXPECT_LT(p.metrics.log_rmse, q.metrics.log_rmse);
      }
    }
  }
  // A stride budget uses fewer cells than the full one.
  EXPECT_LT(pts[2].fit_cells, pts[0].fit_cells);
  const std::string html = ReadText(dir_ / "bench.html");
  EXPECT_NE(html.find("data-charts-expected=\"2\""), std::string::npos);  // one Pareto per table
  EXPECT_EQ(r.err.find("bench ["), std::string::npos);  // no progress bar when not a terminal

  const CliRun bad = Brdfit("bench " + P("a.h5") + " --models no-such-model -o " + P("x.csv"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("no-such-model"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

// `bench --polish rendered` makes brdfit fit's fits: on a table one lobe cannot express, the
// rendered score is at least the unpolished one's (fit/rendered_polish.h); a bad name exits 2.
TEST_F(Cli, BenchPolishIsTheFitsPolish) {
  const CliRun s = Brdfit(
      "synth --model lambert+ggx+ggx --param ggx1.alpha=0.05 --param ggx2.alpha=0.35 "
      "--grid 24,24,48 -o " + P("two.h5"));
  ASSERT_EQ(s.code, 0) << s.err;
  double score[2] = {0, 0};
  int k = 0;
  for (const char* polish : {"none", "rendered"}) {
    const std::string csv = std::string(polish) + ".csv";
    const CliRun r = Brdfit("bench " + P("two.h5") + " --budgets full --losses rel --polish " +
                            polish + " -q -o " + P(csv));
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const auto pts = ReadBenchCsv(dir_ / csv);
    ASSERT_EQ(pts.size(), 1u);
    ASSERT_TRUE(pts[0].metrics.rendered.ok);
    score[k++] = RenderedScoreDb(pts[0].metrics.rendered);
  }
  EXPECT_GT(score[1], score[0]);
  const CliRun bad = Brdfit("bench " + P("two.h5") + " --polish bogus -o " + P("bad.csv"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("unknown polish 'bogus'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.csv"));
}

// Fit reports of `brdfit fit` (io/fit_report.h): two materials fitted with lambert+ggx.
std::vector<FitReportEntry> FitEntries(const fs::path& dir, double plastic_error) {
  const ModelInfo* m = FindModel("lambert+ggx");
  std::vector<FitReportEntry> out;
  for (const char* material : {"gold", "plastic"}) {
    FitReportEntry e;
    e.source = (dir / (std::string(material) + ".h5")).string();
    e.material = material;
    e.options = R"({"cutoff_deg":80,"weighting":"bin-measure","budget":"full","loss":"log",)"
                R"("cosine":true,"robust":"none"})";
    FitResult& r = e.result;
    r.model = m->name;
    r.param_names = m->param_names;
    r.params = m->DefaultParams();
    r.at_bound.assign(r.params.size(), false);
    r.status = FitStatus::kConverged;
    r.iterations = 9;
    r.metrics.ok = true;
    r.metrics.log_rmse = std::string(material) == "plastic" ? plastic_error : 0.01;
    r.metrics.cbrt_rmse = 2 * r.metrics.log_rmse;
    r.metrics.rel_l2 = 3 * r.metrics.log_rmse;
    r.metrics.cells = 1000;
    r.metrics.weighting = "bin-measure";
    r.metrics.cutoff_deg = 80;
    r.times.prepare = 5;
    r.times.init = 10;
    r.times.solve = 100;
    out.push_back(e);
  }
  return out;
}

// Acceptance: compare on two reports where one material regressed exits non-zero and names it.
TEST_F(Cli, CompareFitReportsNamesTheRegressedMaterial) {
  WriteFitReport(FitEntries(dir_, 0.02), dir_ / "old.h5");
  WriteFitReport(FitEntries(dir_, 0.03), dir_ / "new.h5");
  const CliRun r = Brdfit("compare " + P("old.h5") + " " + P("new.h5"));
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("REGRESSED: plastic (1 regressions)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("+50.0 %"), std::string::npos) << r.out;
  EXPECT_EQ(Brdfit("compare " + P("new.h5") + " " + P("old.h5")).code, 0);
}

// A fit report whose sources exist gets θh slices; the page counts its charts.
TEST_F(Cli, ReportOnAFitReportDrawsSlicesFromItsTables) {
  for (const char* name : {"gold", "plastic"}) {
    ASSERT_EQ(Brdfit(std::string("synth --model lambert+ggx --grid 16,16,32 -o ") +
                     P(std::string(name) + ".h5")).code, 0);
  }
  WriteFitReport(FitEntries(dir_, 0.02), dir_ / "fits.h5");
  const CliRun r = Brdfit("report " + P("fits.h5") + " -o " + P("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 materials, 2 results"), std::string::npos) << r.out;
  const std::string html = ReadText(dir_ / "r.html");
  // Summary + per material: Pareto, one chart per error metric, 4 slices (no rendered errors:
  // no per-region chart).
  EXPECT_NE(
      html.find(fmt::format("data-charts-expected=\"{}\"", 1 + 2 * (1 + kNumErrorMetrics + 4))),
      std::string::npos);
  EXPECT_NE(html.find("plastic: θd = "), std::string::npos);
  EXPECT_NE(html.find("ggx.alpha"), std::string::npos);  // parameters listed
}

// A rank-2 factorization with a diffuse value (hand-built, saved as `brdfit factor` saves it)
// in the report and in compare: labelled with its form, its cost listed, its slices and renders
// drawn from every term (pipeline/factor_export.h LoadFactoredBrdf).
TEST_F(Cli, ReportAndCompareShowRankKFactorizationsWithTheirCost) {
  ASSERT_EQ(Brdfit("synth --model lambert+ggx --grid 16,16,32 -o " + P("gold.h5")).code, 0);
  Factorization f;
  f.options.resolution = 16;
  f.brdf = testing::HandBuiltFactoredBrdf(FactorParam::kMcCool, 2, {0.02, 0.03, 0.04}, 16);
  const nlohmann::json metrics = {
      {"fit_metrics",
       {{"ok", true}, {"log_rmse", 0.05}, {"cbrt_rmse", 0.02}, {"rel_l2", 0.1}, {"cells", 10},
        {"cutoff_deg", 80}}}};
  fs::create_directories(dir_ / "f");
  SaveFactorization(f, dir_ / "f", "gold",
                    {{"source", {{"file", P("gold.h5")}}}, {"metrics", metrics}});
  const std::string cost = FactorCostText(CostOf(f.brdf));

  const CliRun r = Brdfit("report " + P("f") + " -o " + P("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(dir_ / "r.html");
  EXPECT_NE(html.find("factor:mccool+d r2"), std::string::npos);
  EXPECT_NE(html.find("<td>" + BytesText(CostOf(f.brdf).texture_bytes) + "</td><td>4</td>"),
            std::string::npos);
  EXPECT_NE(html.find("gold: θd = "), std::string::npos);  // slices of the factorization
  EXPECT_EQ(html.find("No θh slices"), std::string::npos);
  EXPECT_EQ(html.find("No renders:"), std::string::npos);  // the material's renders are drawn
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);

  const CliRun c = Brdfit("compare --all " + P("f") + " " + P("f"));
  ASSERT_EQ(c.code, 0) << c.out << c.err;
  EXPECT_NE(c.out.find("factor:mccool+d r2"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find(cost), std::string::npos) << c.out;
}

// Issue 14 item 8: the slices of a material with 600 fits draw its best 8 (and say so), not
// 600 lines per slice; every fit is still in the metrics table. The best is a numbered
// duplicate ("lambert+ggx #k"): it is drawn and rendered as its model.
TEST_F(Cli, ReportOnManyFitsOfOneMaterialSlicesOnlyTheBest) {
  ASSERT_EQ(Brdfit("synth --model lambert+ggx --grid 16,16,32 -o " + P("gold.h5")).code, 0);
  std::vector<FitReportEntry> fits;
  for (int i = 0; i < 600; ++i) {
    FitReportEntry e = FitEntries(dir_, 0.02)[0];  // gold, lambert+ggx
    e.options = R"({"budget":"full","loss":"log","max_iterations":)" + std::to_string(i) + "}";
    e.result.metrics.log_rmse = i == 7 ? 0.001 : 0.01 + 1e-5 * i;
    fits.push_back(e);
  }
  WriteFitReport(fits, dir_ / "fits.h5");
  const CliRun r = Brdfit("report " + P("fits.h5") + " -o " + P("r.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(dir_ / "r.html");
  EXPECT_NE(html.find("The θh slices draw the best 8 of this material&#39;s 600 results"),
            std::string::npos);
  EXPECT_EQ(html.find("not drawn"), std::string::npos);
  // 4 slices, each with the measured series and 8 fits.
  std::size_t series = 0;
  for (std::size_t at = html.find("\"spanGaps\""); at != std::string::npos;
       at = html.find("\"spanGaps\"", at + 1)) {
    ++series;
  }
  EXPECT_EQ(series, 4u * (1 + 8));
  EXPECT_NE(html.find("<b>Renders</b> of <b>lambert+ggx #"), std::string::npos);
  EXPECT_NE(html.find("lambert+ggx #600</td>"), std::string::npos);
}

// Fits of NBRDF inputs ("nbrdf:NAME") get their slices too: the report tabulates the network.
TEST_F(Cli, ReportOnNbrdfFitsDrawsSlices) {
  const fs::path zip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  if (!fs::exists(zip)) GTEST_SKIP() << zip << " not found: NBRDF inputs not tested";
  const CliRun f = Brdfit("fit nbrdf:pink-felt --model lambert --budget stride:32 -q -o " +
                          P("fits.h5"));
  ASSERT_EQ(f.code, 0) << f.err;
  const CliRun r = Brdfit("report " + P("fits.h5") + " -o " + P("r.html") + " --theta-d 30");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(dir_ / "r.html");
  EXPECT_NE(html.find("pink-felt: θd = 29.5°"), std::string::npos);  // the cell centre nearest 30°
  EXPECT_EQ(html.find("No θh slices"), std::string::npos);
}

// Manners: every subcommand's --help shows examples.
TEST_F(Cli, EveryCommandHelpHasExamplesAndExitCodes) {
  const CliRun top = Brdfit("--help");
  ASSERT_EQ(top.code, 0);
  const std::regex sub(R"(^\s{2}([a-z][a-z-]*)\s{2,})");
  std::vector<std::string> names;
  std::istringstream lines(top.out.substr(top.out.find("Subcommands:")));
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, sub)) names.push_back(m[1]);
  }
  ASSERT_GE(names.size(), 5u) << top.out;
  for (const auto& n : {"report", "compare", "bench"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  }
  for (const auto& n : names) {
    const CliRun h = Brdfit(n + " --help");
    EXPECT_EQ(h.code, 0) << n;
    EXPECT_NE(h.out.find("Example"), std::string::npos) << "brdfit " << n << " --help has no examples";
    EXPECT_NE(h.out.find("Exit codes: 0"), std::string::npos)
        << "brdfit " << n << " --help does not state its exit codes";
  }
}

}  // namespace
}  // namespace brdfit::report
