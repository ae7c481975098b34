// `brdfit export` without --model, when a material's fits hold none of the target's own models
// (export/fit_targets.h): they are fitted on the spot to the table the fits came from
// (pipeline/refit_source.h), the best exported, the fits file left as it was; a table that
// changed or vanished is said, and the export goes on with the fits there are.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "io/fit_report.h"
#include "io/table_io.h"
#include "pipeline/refit_source.h"
#include "tests/fit/fit_test_util.h"
#include "tests/io/io_test_util.h"

namespace brdfit {
namespace {

namespace fs = std::filesystem;
using testing_io::RunCli;

std::string Bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Fujii's Oren-Nayar under a GGX lobe: Blender's Diffuse BSDF with Roughness sigma + Glossy.
std::vector<double> FujiiTruth(double sigma) {
  return testing::Params(
      "oren-nayar-fujii+ggx",
      {"oren-nayar-fujii.kd_r=0.40", "oren-nayar-fujii.kd_g=0.25", "oren-nayar-fujii.kd_b=0.12",
       "oren-nayar-fujii.sigma=" + std::to_string(sigma), "ggx.ks_r=0.2", "ggx.ks_g=0.15",
       "ggx.ks_b=0.1", "ggx.alpha=0.1"});
}

// A Fujii + GGX table at `table` with one fit of lambert+abc (which no target but three.js
// takes) in the report `report`.
void TableWithAnAbcFit(const fs::path& table, const fs::path& report, const fs::path& scratch) {
  SaveTable(testing::SynthModel("oren-nayar-fujii+ggx", FujiiTruth(0.7), testing::SmallGrid()),
            table);
  const auto r = RunCli(
      {"fit", table.string(), "--model", "lambert+abc", "-o", report.string(), "--no-progress"},
      scratch);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST(RefitSource, FitsTheTargetsModelsToTheReportsTable) {
  ScratchDir dir;
  const fs::path table = dir.path() / "felt.h5", report = dir.path() / "fits.h5";
  ASSERT_NO_FATAL_FAILURE(TableWithAnAbcFit(table, report, dir.path()));
  const auto entries = ReadFitReport(report);
  ASSERT_EQ(entries.size(), 1u);

  const pipeline::SourceRefit refit =
      pipeline::RefitSource(entries[0], {"oren-nayar-fujii+ggx", "lambert+ggx"});
  ASSERT_EQ(refit.entries.size(), 2u);
  EXPECT_TRUE(refit.same_options);  // lambert+abc was fitted with the defaults too
  for (const FitReportEntry& e : refit.entries) {
    EXPECT_EQ(e.material, entries[0].material);
    EXPECT_EQ(e.source_hash, entries[0].source_hash);
    EXPECT_FALSE(e.chosen);
    if (e.result.model != "oren-nayar-fujii+ggx") continue;
    // Parameter recovery on the table the model generated.
    for (std::size_t i = 0; i < e.result.params.size(); ++i) {
      EXPECT_NEAR(e.result.params[i], FujiiTruth(0.7)[i], 1e-3) << e.result.param_names[i];
    }
  }

  // The table changed since the fits: refused, naming it.
  SaveTable(testing::SynthModel("oren-nayar-fujii+ggx", FujiiTruth(0.2), testing::SmallGrid()),
            table);
  try {
    pipeline::RefitSource(entries[0], {"lambert+ggx"});
    FAIL() << "a changed table was refitted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the table changed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("felt.h5"), std::string::npos) << e.what();
  }
  // Gone: refused, naming it.
  fs::remove(table);
  EXPECT_THROW(pipeline::RefitSource(entries[0], {"lambert+ggx"}), InputError);
}

TEST(RefitSource, ExportFitsBlendersModelsOnTheSpotAndLeavesTheFitsAlone) {
  ScratchDir dir;
  const fs::path table = dir.path() / "felt.h5", report = dir.path() / "fits.h5",
                 script = dir.path() / "felt.py";
  ASSERT_NO_FATAL_FAILURE(TableWithAnAbcFit(table, report, dir.path()));
  const std::string before = Bytes(report);

  // --no-fit: lambert+abc is not exportable to Blender, and nothing else is there.
  auto r =
      RunCli({"export", report.string(), "--format", "blender", "--no-fit", "-o", script.string()},
             dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("none of the fits (lambert+abc) can be exported"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(script));

  // Default: Blender's models fitted on the spot, the exact one that renders best exported.
  r = RunCli({"export", report.string(), "--format", "blender", "-o", script.string()}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("holds none of blender's own models: fitted lambert+ggx, lambert+ggx+ggx, "
                       "oren-nayar-fujii+ggx, burley-2012+ggx to"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("oren-nayar-fujii+ggx"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[exact]"), std::string::npos) << r.out;
  const std::string py = Bytes(script);
  EXPECT_NE(py.find("\"body\": \"oren-nayar-fujii\", \"body_roughness\": 0.7"), std::string::npos)
      << py.substr(0, 4000);
  EXPECT_EQ(Bytes(report), before) << "the fits file was modified";

  // The table gone: said, and the export goes on with the fits there are (none exportable).
  fs::remove(table);
  fs::remove(script);
  r = RunCli({"export", report.string(), "--format", "blender", "-o", script.string()}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("could not be fitted on the spot"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace brdfit
