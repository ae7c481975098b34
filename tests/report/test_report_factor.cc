// Factorizations in the report and the comparison: labelled with their form (rank, diffuse),
// with their texture memory and fetches per light beside the analytic fits' parameter counts.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "core/error.h"
#include "factor/factor_form.h"
#include "pipeline/factor_export.h"
#include "report/compare.h"
#include "report/html_report.h"
#include "report/report_inputs.h"
#include "tests/factor/factor_test_util.h"
#include "tests/report/report_fixture.h"
#include "tests/scratch_dir.h"

namespace brdfit::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A hand-built factorization saved as `brdfit factor` saves it, with metrics and a source.
fs::path SaveHandBuilt(const fs::path& dir, const std::string& stem, FactorParam param, int rank,
                       std::array<double, 3> diffuse, bool refined = false) {
  Factorization r;
  r.options.param = param;
  r.options.resolution = 16;
  r.brdf = testing::HandBuiltFactoredBrdf(param, rank, diffuse, 16);
  if (refined) r.stats.refine_rows = 1000;
  const json metrics = {{"fit_metrics",
                         {{"ok", true},
                          {"log_rmse", 0.05},
                          {"cbrt_rmse", 0.04},
                          {"rel_l2", 0.3},
                          {"cells", 500},
                          {"weighting", "bin-measure"},
                          {"cutoff_deg", 80}}}};
  return SaveFactorization(r, dir, stem,
                           {{"source", {{"file", "/data/gold.binary"}}}, {"metrics", metrics}})
      .json;
}

TEST(ReportFactor, EntryIsLabelledWithItsFormAndCarriesItsCost) {
  const ScratchDir dir;
  const fs::path json_path =
      SaveHandBuilt(dir.path(), "gold", FactorParam::kMcCool, 2, {0.01, 0.02, 0.03});
  std::string material, table;
  const Entry e = FactorEntry(json_path, &material, &table);
  EXPECT_EQ(material, "gold");
  EXPECT_EQ(e.name, "factor:mccool+d r2");
  EXPECT_EQ(e.budget, "res 16");
  EXPECT_EQ(e.loss, "log (linear)");
  ASSERT_TRUE(e.has_cost);
  const FactorCost want = CostOf(LoadFactoredBrdf(json_path));
  EXPECT_EQ(e.cost.texture_bytes, want.texture_bytes);
  EXPECT_EQ(e.cost.texture_bytes, 12u * (16 * 16 * 2 + 8 * 8 * 2) + 12);
  EXPECT_EQ(e.cost.fetches_per_light, 4);
  EXPECT_EQ(e.cost.fetches_per_fragment, 2);

  const Entry r = FactorEntry(
      SaveHandBuilt(dir.path(), "gold.r", FactorParam::kHalfDiff, 1, {0, 0, 0}, /*refined=*/true),
      &material, &table);
  EXPECT_EQ(r.name, "factor:halfdiff");  // rank 1 without diffuse: the name it always had
  EXPECT_EQ(r.loss, "log (linear) + rel (refined)");
  EXPECT_EQ(r.cost.fetches_per_light, 2);
  EXPECT_EQ(r.cost.fetches_per_fragment, 0);
}

TEST(ReportFactor, VersionOneAndBadSidecars) {
  const ScratchDir dir;
  const fs::path p = SaveHandBuilt(dir.path(), "gold", FactorParam::kMcCool, 1, {0, 0, 0});
  json j = json::parse(std::ifstream(p));
  j["format_version"] = 1;
  j.erase("rank");
  j.erase("diffuse");
  std::ofstream(p) << j.dump();
  std::string material, table;
  const Entry e = FactorEntry(p, &material, &table);
  EXPECT_EQ(e.name, "factor:mccool");
  ASSERT_TRUE(e.has_cost);
  EXPECT_EQ(e.cost.texture_bytes, 12u * 16 * 16 * 2);

  // The checks of the files' reader (io/factor_io.h), naming the file.
  for (const auto& [member, value] : std::vector<std::pair<const char*, json>>{
           {"format_version", 3}, {"rank", 9}, {"diffuse", json::array({-1, 0, 0})}}) {
    json bad = j;
    bad["format_version"] = 2;
    bad["rank"] = 1;
    bad["diffuse"] = {0, 0, 0};
    bad[member] = value;
    std::ofstream(p) << bad.dump();
    try {
      FactorEntry(p, &material, &table);
      ADD_FAILURE() << member << " accepted";
    } catch (const InputError& err) {
      EXPECT_NE(std::string(err.what()).find(p.string()), std::string::npos) << err.what();
      EXPECT_NE(std::string(err.what()).find(member), std::string::npos) << err.what();
    }
  }
}

TEST(ReportFactor, HtmlTableShowsMemoryAndFetchesOfFactorizationsAndParametersOfFits) {
  const ScratchDir dir;
  const fs::path p = SaveHandBuilt(dir.path(), "gold", FactorParam::kMcCool, 2, {0.01, 0.02, 0.03});
  ReportSources src = ReadReportInputs({p});
  Report& r = src.report;
  Entry fit;
  fit.name = "lambert+ggx";
  fit.loss = "log";
  fit.budget = "full";
  fit.status = "converged";
  fit.params = {0.3, 0.2, 0.1, 0.05, 0.05, 0.05, 0.2};
  fit.metrics = testing::Scored(0.01, 0.02, 0.1, 500);
  r.GetOrAddMaterial("gold").entries.push_back(fit);
  const std::string html = RenderHtml(r, "/* Chart stand-in */");
  const FactorCost c = r.FindMaterial("gold")->entries[0].cost;
  // The rows of the cost table (after the accuracy table, headed by "cells") start with the
  // approximation: the factorization's has its memory, fetches per light and per fragment.
  const std::string cost = html.substr(html.find("<th>cells</th>"));
  auto row_of = [&](const std::string& name) {
    std::smatch m;
    const std::regex re("<tr[^>]*><td class=\"l\">(★ )?" + name + "</td>.*?</tr>");
    return std::regex_search(cost, m, re) ? m.str() : std::string();
  };
  const std::string row = row_of("factor:mccool\\+d r2");
  ASSERT_FALSE(row.empty());
  EXPECT_NE(row.find("<td>" + BytesText(c.texture_bytes) + "</td><td>4</td><td>2</td>"),
            std::string::npos)
      << row;
  const std::string fit_row = row_of("lambert\\+ggx");
  ASSERT_FALSE(fit_row.empty());
  EXPECT_NE(fit_row.find("<td>7 params</td><td>–</td><td>–</td>"), std::string::npos) << fit_row;
  EXPECT_NE(html.find("fetches / light"), std::string::npos);
}

TEST(CompareFactor, ListsEachFactorizationsCostAndItsChange) {
  const ScratchDir dir;
  fs::create_directories(dir / "old");
  fs::create_directories(dir / "new");
  SaveHandBuilt(dir / "old", "gold", FactorParam::kMcCool, 2, {0.01, 0.02, 0.03});
  SaveHandBuilt(dir / "new", "gold", FactorParam::kMcCool, 2, {0.01, 0.02, 0.03});
  SaveHandBuilt(dir / "new", "gold.h", FactorParam::kHalfDiff, 1, {0, 0, 0});
  const Report a = ReadReportInputs({dir / "old"}).report;
  const Report b = ReadReportInputs({dir / "new"}).report;
  const Comparison c = Compare(a, b);
  const std::string text = FormatComparison(c, /*all=*/true);
  const FactorCost mc = a.FindMaterial("gold")->entries[0].cost;
  EXPECT_NE(text.find("factor:mccool+d r2 (log (linear), res 16)"), std::string::npos) << text;
  EXPECT_NE(text.find(FactorCostText(mc)), std::string::npos) << text;
  EXPECT_NE(text.find("2 fetches per light"), std::string::npos) << text;  // the added halfdiff
  const json j = ComparisonToJson(c);
  ASSERT_EQ(j["deltas"].size(), 2u);
  EXPECT_EQ(j["deltas"][0]["kind"], "factorization");
  EXPECT_EQ(j["deltas"][0]["new_cost"]["texture_bytes"], mc.texture_bytes);
  EXPECT_EQ(j["deltas"][0]["old_cost"]["fetches_per_fragment"], 2);
  EXPECT_TRUE(j["deltas"][1]["old_cost"].is_null());  // only in the new report

  // A cost is shown, never judged: the same metrics and an added entry are no regression.
  EXPECT_FALSE(c.Regressed());
  EXPECT_EQ(c.Count(Change::kAdded), 1);
}

}  // namespace
}  // namespace brdfit::report
