// `brdfit fit` end to end: determinism across --jobs, resuming, exit codes, and the report's
// round trip.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fit/fitter.h"
#include "fit_test_util.h"
#include "core/error.h"
#include "core/provenance.h"
#include "io/fit_report.h"
#include "io/table_io.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The log file is per process and test: CTest runs the tests of this file in parallel, and a
// shared log once let one test read another's output.
int RunCli(const std::string& args, std::string* out = nullptr) {
  const std::string log =
      (fs::temp_directory_path() /
       ("brdfit_fit_cli_" + std::to_string(::getpid()) + "_" +
        ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".log"))
          .string();
  const int status =
      std::system((std::string(BRDFIT_EXE) + " " + args + " > " + log + " 2>&1").c_str());
  if (out) *out = Slurp(log);
  std::error_code ec;
  fs::remove(log, ec);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class FitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfit_fit_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    SaveTable(SynthModel("lambert+ggx", Params("lambert+ggx", {"ggx.alpha=0.07"}), SmallGrid(),
                         0.03, 0.2, 1),
              dir_ / "a.h5");
    SaveTable(SynthModel("lambert+beckmann", Params("lambert+beckmann", {"beckmann.alpha=0.3"}),
                         SmallGrid()),
              dir_ / "b.h5");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(FitCli, SameOutputWithOneOrTwoJobsAndResumes) {
  const std::string in = P("a.h5") + " " + P("b.h5") + " --model ggx,beckmann -q --no-timings";
  std::string log;
  ASSERT_EQ(RunCli("fit " + in + " --jobs 1 -o " + P("r1.h5") + " --json " + P("j1.json"), &log), 0)
      << log;
  ASSERT_EQ(RunCli("fit " + in + " --jobs 2 -o " + P("r2.h5") + " --json " + P("j2.json"), &log), 0)
      << log;
  EXPECT_EQ(Slurp(P("r1.h5")), Slurp(P("r2.h5")));
  EXPECT_EQ(Slurp(P("j1.json")), Slurp(P("j2.json")));

  const std::vector<FitReportEntry> e = ReadFitReport(P("r1.h5"));
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].result.model, "lambert+beckmann");  // sorted by (source, model)
  EXPECT_EQ(e[1].result.model, "lambert+ggx");
  EXPECT_EQ(e[0].material, "a");
  for (const auto& x : e) {
    EXPECT_EQ(x.result.status, FitStatus::kConverged) << x.result.message;
    EXPECT_EQ(x.result.param_names.size(), x.result.params.size());
    EXPECT_GT(x.result.metrics.cells, 1000u);
    EXPECT_EQ(x.result.times.solve, 0.0);  // --no-timings
  }
  // b.h5 is noise-free lambert+beckmann: its own model fits it exactly.
  EXPECT_LT(e[2].result.metrics.log_rmse, 1e-6);

  // Resume: nothing to do, the report is unchanged; --force redoes everything.
  std::string quiet_log;
  RunCli(
      "fit " + P("a.h5") + " " + P("b.h5") + " --model ggx,beckmann --no-timings -o " + P("r1.h5"),
      &quiet_log);
  EXPECT_NE(quiet_log.find("0 fits, 4 skipped"), std::string::npos) << quiet_log;
  EXPECT_EQ(Slurp(P("r1.h5")), Slurp(P("r2.h5")));
  // A new model is added next to the kept entries.
  ASSERT_EQ(RunCli("fit " + P("a.h5") + " --model ward -q --no-timings -o " + P("r1.h5")), 0);
  EXPECT_EQ(ReadFitReport(P("r1.h5")).size(), 5u);
  // --force redoes this run's fits only: the report's other fits (b's, a's other models) stay.
  std::string force_log;
  ASSERT_EQ(
      RunCli("fit " + P("a.h5") + " --model ggx --force --no-timings -o " + P("r1.h5"), &force_log),
      0);
  EXPECT_NE(force_log.find("1 fits, 0 skipped"), std::string::npos) << force_log;
  EXPECT_EQ(ReadFitReport(P("r1.h5")).size(), 5u);
  // A report that cannot be read is refused, and replaced with --force.
  std::ofstream(P("r3.h5")) << "not a report";
  EXPECT_EQ(RunCli("fit " + P("a.h5") + " --model ggx -q -o " + P("r3.h5")), 2);
  ASSERT_EQ(RunCli("fit " + P("a.h5") + " --model ggx -q --force -o " + P("r3.h5")), 0);
  EXPECT_EQ(ReadFitReport(P("r3.h5")).size(), 1u);
}

// `--json -`: the parameters JSON is the standard output (the same bytes as --json FILE); the
// table goes to stderr.
TEST_F(FitCli, JsonDashWritesTheParametersToStdout) {
  const std::string in = P("b.h5") + " --model beckmann --no-timings --no-progress";
  ASSERT_EQ(RunCli("fit " + in + " -o " + P("r1.h5") + " --json " + P("j1.json")), 0);
  const std::string out = P("stdout.json");
  const int status = std::system((std::string(BRDFIT_EXE) + " fit " + in + " --force -o " +
                                  P("r2.h5") + " --json - > " + out + " 2> " + P("stderr.txt"))
                                     .c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << Slurp(P("stderr.txt"));
  EXPECT_EQ(Slurp(out), Slurp(P("j1.json")));
  EXPECT_NE(Slurp(P("stderr.txt")).find("lambert+beckmann"), std::string::npos);
}

TEST_F(FitCli, FailedFitExitsOneAndBadInputTwo) {
  SaveTable(Table::Empty(SmallGrid()), dir_ / "empty.h5");
  std::string log;
  EXPECT_EQ(
      RunCli("fit " + P("empty.h5") + " " + P("a.h5") + " --model ggx -q -o " + P("r.h5"), &log), 1)
      << log;
  const std::vector<FitReportEntry> e = ReadFitReport(P("r.h5"));
  ASSERT_EQ(e.size(), 2u);
  const auto& failed = e[1].result;  // "empty.h5" sorts after "a.h5"
  EXPECT_EQ(failed.status, FitStatus::kFailed);
  EXPECT_FALSE(failed.message.empty());
  for (double v : failed.params) EXPECT_TRUE(std::isfinite(v));

  EXPECT_EQ(RunCli("fit " + P("missing.h5") + " --model ggx -q -o " + P("r3.h5"), &log), 2);
  EXPECT_NE(log.find("missing.h5"), std::string::npos) << log;
  EXPECT_EQ(RunCli("fit " + P("a.h5") + " --model glossy -q -o " + P("r3.h5"), &log), 2);
  EXPECT_NE(log.find("unknown model"), std::string::npos) << log;
  EXPECT_EQ(RunCli("fit " + P("a.h5") + " --model ggx --budget stride:0 -o " + P("r3.h5")), 2);
  EXPECT_EQ(RunCli("fit " + P("a.h5") + " --model ggx --cutoff 95 -o " + P("r3.h5")), 2);
}

TEST(FitReport, RoundTripKeepsEveryField) {
  const Table t = SynthModel("lambert+ggx", Params("lambert+ggx", {}), SmallGrid(), 0.05, 0.1, 2);
  FitReportEntry e{"dir/t.binary",
                   "t",
                   "{\"loss\":\"log\"}",
                   FitTable("lambert+ggx", t, SampleOptions{}, LogLossUnpolished()),
                   true,
                   "best rendered score",
                   TableContentHash(t),
                   false,
                   std::nullopt};
  e.result.times.load = 12.5;
  const fs::path p =
      fs::temp_directory_path() / ("brdfit_report_" + std::to_string(::getpid()) + ".h5");
  WriteFitReport({e}, p);
  const std::vector<FitReportEntry> back = ReadFitReport(p);
  ASSERT_EQ(back.size(), 1u);
  const FitResult &a = e.result, &b = back[0].result;
  EXPECT_EQ(back[0].source, e.source);
  EXPECT_EQ(back[0].options, e.options);
  EXPECT_TRUE(back[0].chosen);
  EXPECT_EQ(back[0].choice, e.choice);
  EXPECT_EQ(back[0].source_hash, e.source_hash);
  EXPECT_TRUE(back[0].source_hash.starts_with("t64:"));
  EXPECT_EQ(b.model, a.model);
  EXPECT_EQ(b.params, a.params);
  EXPECT_EQ(b.param_names, a.param_names);
  EXPECT_EQ(b.at_bound, a.at_bound);
  EXPECT_EQ(b.status, a.status);
  EXPECT_EQ(b.iterations, a.iterations);
  EXPECT_EQ(b.final_cost, a.final_cost);
  EXPECT_EQ(b.metrics.log_rmse, a.metrics.log_rmse);
  EXPECT_EQ(b.metrics.worst.cell, a.metrics.worst.cell);
  EXPECT_EQ(b.metrics.worst.predicted, a.metrics.worst.predicted);
  EXPECT_EQ(b.sample_counts.eligible, a.sample_counts.eligible);
  EXPECT_EQ(b.times.load, 12.5);
  EXPECT_TRUE(back[0].timed);  // the reader notes the /timing group (brdfit merge keeps it)
  EXPECT_EQ(b.times.solve_cpu, a.times.solve_cpu);
  // A table is not a report.
  const fs::path table =
      fs::temp_directory_path() / ("brdfit_table_" + std::to_string(::getpid()) + ".h5");
  SaveTable(t, table);
  EXPECT_THROW(ReadFitReport(table), InputError);
  fs::remove(p);
  fs::remove(table);
}

}  // namespace
}  // namespace brdfit
