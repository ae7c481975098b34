// pipeline/inputs.h: nbrdf:NAME and nbrdf:all resolve the same way for every command, and the
// content key of an input changes with its content. NBRDF cases skip when the archive is absent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "io/merl.h"
#include "pipeline/inputs.h"
#include "tests/io/io_test_util.h"
#include "tests/pipeline/lab_tables.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing_io::CliResult;
using testing_io::RunCli;

const fs::path kZip = fs::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";

class NbrdfInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kZip)) GTEST_SKIP() << kZip << " not found: NBRDF inputs not tested";
    setenv("BRDFIT_NBRDF_ZIP", kZip.c_str(), 1);
  }
  ScratchDir dir_;
};

TEST_F(NbrdfInputs, AllExpandsToEveryMaterialOfTheArchive) {
  const auto all = pipeline::ExpandInputs({"a.binary", "nbrdf:all"});
  ASSERT_EQ(all.size(), 101u);  // the MERL database holds 100 materials
  EXPECT_EQ(all.front(), "a.binary");
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_EQ(all[i].rfind("nbrdf:", 0), 0u);
}

TEST_F(NbrdfInputs, ContentKeyNamesTheArchiveAndTheMaterial) {
  EXPECT_EQ(pipeline::InputContentKey("nbrdf:pink-felt"),
            pipeline::InputContentKey("nbrdf:pink-felt"));
  EXPECT_NE(pipeline::InputContentKey("nbrdf:pink-felt"),
            pipeline::InputContentKey("nbrdf:chrome"));
}

TEST(InputContentKey, ChangesWithTheFileContent) {
  ScratchDir dir;
  const fs::path f = dir / "t.bin";
  std::ofstream(f) << "one";
  const std::string a = pipeline::InputContentKey(f.string());
  std::ofstream(f) << "two";
  EXPECT_NE(a, pipeline::InputContentKey(f.string()));
  EXPECT_THROW(pipeline::InputContentKey((dir / "missing").string()), InputError);
}

// info, fit, factor, bench, render and report all take nbrdf:NAME (docs/architecture.md). The
// tabulation `info` describes is the one `synth --nbrdf` writes (an independent path to it).
TEST_F(NbrdfInputs, EveryCommandTakesAnNbrdfInput) {
  const std::string in = "nbrdf:pink-felt";
  const fs::path d = dir_.path();
  const CliResult info = RunCli({"info", in, "--json"}, d);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j.at("format"), "nbrdf");
  const CliResult synth =
      RunCli({"synth", "--nbrdf", "pink-felt", "-o", (d / "pf.h5").string()}, d);
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const CliResult info2 = RunCli({"info", (d / "pf.h5").string(), "--json"}, d);
  ASSERT_EQ(info2.exit_code, 0) << info2.err;
  const auto j2 = nlohmann::json::parse(info2.out);
  EXPECT_EQ(j.at("valid"), j2.at("valid"));
  EXPECT_EQ(j.at("channels_1_per_sr"), j2.at("channels_1_per_sr"));
  EXPECT_EQ(j.at("directional_albedo"), j2.at("directional_albedo"));

  const CliResult fit = RunCli(
      {"fit", in, "--budget", "stride:32", "-q", "--no-timings", "-o", (d / "fits.h5").string()},
      d);
  EXPECT_EQ(fit.exit_code, 0) << fit.err;
  const CliResult factor = RunCli({"factor", in, "--res", "8", "-o", (d / "factor").string()}, d);
  EXPECT_EQ(factor.exit_code, 0) << factor.err;
  EXPECT_TRUE(fs::exists(d / "factor" / "pink-felt.factor.json"));
  const CliResult bench =
      RunCli({"bench", in, "--budgets", "stride:32", "-q", "-o", (d / "bench.csv").string()}, d);
  EXPECT_EQ(bench.exit_code, 0) << bench.err;
  const CliResult render = RunCli({"render", in, "--size", "64x64", "--cache",
                                   (d / "cache").string(), "-o", (d / "r.png").string()},
                                  d);
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(fs::exists(d / "r.png"));
  const CliResult report =
      RunCli({"report", (d / "fits.h5").string(), "-o", (d / "report.html").string()}, d);
  EXPECT_EQ(report.exit_code, 0) << report.err;
  // The table given as nbrdf:NAME itself, as a file table would be: its slices are drawn.
  const CliResult table_report = RunCli({"report", in, "--theta-d", "30", "--no-renders", "-o",
                                         (d / "table.html").string()},
                                        d);
  EXPECT_EQ(table_report.exit_code, 0) << table_report.err;
  const std::string html = brdfit::testing::ReadAll(d / "table.html");
  EXPECT_NE(html.find("pink-felt: θd = 29.5°"), std::string::npos);  // the bin centre nearest 30°
  EXPECT_EQ(html.find("No θh slices"), std::string::npos);
  const CliResult bad_report =
      RunCli({"report", "nbrdf:no-such-material", "-o", (d / "bad.html").string()}, d);
  EXPECT_EQ(bad_report.exit_code, 2);
  EXPECT_NE(bad_report.err.find("no-such-material"), std::string::npos) << bad_report.err;
  EXPECT_FALSE(fs::exists(d / "bad.html"));

  const CliResult bad = RunCli({"info", "nbrdf:no-such-material"}, d);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("no-such-material"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace brdfit
