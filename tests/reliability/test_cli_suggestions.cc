// A CLI that helps: a misspelt command, option, model or NBRDF material gets the closest known
// names (core/suggest.h), and the summary never names a report that was not written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_process.h"
#include "tests/scratch_dir.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing_cli::CliRun;

TEST(CliSuggestions, MisspeltNamesGetTheClosestKnownOnes) {
  ScratchDir dir;
  const std::string table = (dir / "t.h5").string();
  CliRun r = testing_cli::Run({"synth", "--model", "lambert+ggx", "--grid", "8,8,16", "-o", table},
                              dir / "synth.log");
  ASSERT_EQ(r.code, 0) << r.log;

  r = testing_cli::Run({"fti", table}, dir / "a.log");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.log, HasSubstr("brdfit: error: unknown command 'fti' (did you mean fit?)"));

  r = testing_cli::Run({"fit", table, "--modle", "ggx", "-o", (dir / "x.h5").string()},
                       dir / "b.log");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.log, HasSubstr("--modle (did you mean --model?)"));

  r = testing_cli::Run({"fit", table, "--model", "ggxx", "-o", (dir / "x.h5").string()},
                       dir / "c.log");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.log, HasSubstr("unknown model 'ggxx' (did you mean ggx?)"));

  r = testing_cli::Run({"synth", "--model", "bekmann", "-o", (dir / "y.h5").string()},
                       dir / "d.log");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.log, HasSubstr("unknown model 'bekmann' (did you mean beckmann?)"));

  // Nothing close: no guess, the list as before.
  r = testing_cli::Run({"fit", table, "--model", "zzzzzz", "-o", (dir / "x.h5").string()},
                       dir / "e.log");
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.log, Not(HasSubstr("did you mean")));
  EXPECT_THAT(r.log, HasSubstr("(known: "));
  EXPECT_FALSE(fs::exists(dir / "x.h5"));
}

// A misspelt NBRDF material: the closest names instead of all hundred, and the summary does
// not name the report that no fit wrote.
TEST(CliSuggestions, MisspeltNbrdfMaterialAndNoReportWritten) {
  const fs::path zip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
  if (!fs::exists(zip)) GTEST_SKIP() << zip << " is absent (../shared/data)";
  ScratchDir dir;
  const fs::path report = dir / "a.h5";
  const CliRun r = testing_cli::Run(
      {"fit", "nbrdf:gold-metalic-paint", "--model", "ggx", "--no-progress", "-o", report.string()},
      dir / "f.log");
  EXPECT_EQ(r.code, 2) << r.log;
  EXPECT_THAT(r.log, HasSubstr("no material 'gold-metalic-paint': did you mean "
                               "gold-metallic-paint?"));
  EXPECT_THAT(r.log, Not(HasSubstr("alum-bronze")));  // not the whole list
  EXPECT_THAT(r.log, HasSubstr("0 fits, 0 skipped; no report written"));
  EXPECT_THAT(r.log, Not(HasSubstr("report " + report.string())));
  EXPECT_FALSE(fs::exists(report));
}

}  // namespace
}  // namespace brdfit
