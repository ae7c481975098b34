// One material with many fits (issue 14 item 8: `report` and `compare` grew faster than
// quadratically with them): fits that share a key are numbered once each, compare pairs them,
// and the page draws a bounded number of results per material. The times themselves are
// measured by bench/bench_report_cli.cc, not here.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <set>

#include "io/fit_report.h"
#include "models/registry.h"
#include "report/compare.h"
#include "report/html_report.h"
#include "report/report_charts.h"
#include "report/report_inputs.h"
#include "tests/scratch_dir.h"

namespace brdfit::report {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModels[] = {"lambert+ggx", "lambert+beckmann", "lambert+ward"};

// n fits of one table, three models in turn, options differing only in max_iterations (not
// part of an entry's key): n / 3 fits share each key.
std::vector<FitReportEntry> ManyFits(int n) {
  std::vector<FitReportEntry> out;
  for (int i = 0; i < n; ++i) {
    const ModelInfo* m = FindModel(kModels[i % 3]);
    FitReportEntry e;
    e.source = "/no/such/t.h5";
    e.material = "t";
    e.options = R"({"budget":"full","loss":"log","max_iterations":)" + std::to_string(100 + i) + "}";
    FitResult& r = e.result;
    r.model = m->name;
    r.param_names = m->param_names;
    r.params = m->DefaultParams();
    r.at_bound.assign(r.params.size(), false);
    r.status = FitStatus::kConverged;
    r.metrics.ok = true;
    r.metrics.log_rmse = 0.01 + 1e-5 * i;
    r.metrics.cbrt_rmse = r.metrics.rel_l2 = r.metrics.log_rmse;
    r.metrics.cells = 100;
    r.times.solve = 10 + i;
    out.push_back(std::move(e));
  }
  return out;
}

TEST(ReportScaling, FitsSharingAKeyAreNumberedAndCompareMatchesThemOneToOne) {
  ScratchDir dir;
  WriteFitReport(ManyFits(600), dir / "fits.h5");
  const ReportSources s = ReadReportInputs({dir / "fits.h5"});
  ASSERT_EQ(s.report.materials.size(), 1u);
  const std::vector<Entry>& entries = s.report.materials[0].entries;
  ASSERT_EQ(entries.size(), 600u);
  std::set<std::string> keys, models;
  for (const Entry& e : entries) {
    keys.insert(e.Key());
    models.insert(e.Model());
    // A numbered duplicate keeps its model as base_name.
    if (e.name.find(" #") != std::string::npos) {
      EXPECT_EQ(e.base_name + " #", e.name.substr(0, e.base_name.size() + 2)) << e.name;
    } else {
      EXPECT_TRUE(e.base_name.empty()) << e.name;
    }
  }
  EXPECT_EQ(keys.size(), 600u);  // every entry told apart
  EXPECT_EQ(models, (std::set<std::string>(std::begin(kModels), std::end(kModels))));
  // Each model's 200 fits are "M", "M #2" ... "M #200".
  for (const char* m : kModels) {
    EXPECT_EQ(keys.count(std::string(m) + " #200 | log | full"), 1u) << m;
    EXPECT_EQ(keys.count(std::string(m) + " #201 | log | full"), 0u) << m;
  }

  // The same report against itself: every entry paired with itself, nothing added or missing.
  const Comparison c = Compare(s.report, s.report);
  EXPECT_EQ(c.deltas.size(), 600u);
  EXPECT_EQ(c.Count(Change::kSame), 600);
  // One duplicate worse in the new report: exactly that one is the regression.
  Report worse = s.report;
  worse.materials[0].entries[437].metrics.log_rmse *= 2;
  const Comparison w = Compare(s.report, worse);
  ASSERT_EQ(w.Regressions(), 1);
  for (const EntryDelta& d : w.deltas) {
    if (d.regression) {
      EXPECT_EQ(d.name, entries[437].name);
    }
  }
}

TEST(ReportScaling, ThePageDrawsABoundedNumberOfResultsPerMaterial) {
  ScratchDir dir;
  WriteFitReport(ManyFits(600), dir / "fits.h5");
  const ReportSources s = ReadReportInputs({dir / "fits.h5"});
  const std::string html = RenderHtml(s.report, "");
  // The summary has one column per model, not one per numbered duplicate.
  const std::string summary = html.substr(0, html.find("</table>"));
  std::size_t columns = 0;
  for (std::size_t at = summary.find("<th class=\"wrap\">"); at != std::string::npos;
       at = summary.find("<th class=\"wrap\">", at + 1)) {
    ++columns;
  }
  EXPECT_EQ(columns, 1u + 3) << "median lum. err. + one per model";
  // Each metric's chart draws the best kMaxMetricBars and says so.
  for (const ErrorMetricField& f : kErrorMetrics) {
    EXPECT_NE(html.find(fmt::format("{}: t (the best {} of 600)", f.name, kMaxMetricBars)),
              std::string::npos)
        << f.name;
  }
  // The Pareto chart: one dataset per model and budget (+ the front), not one per fit.
  for (const char* m : kModels) {
    EXPECT_NE(html.find(std::string("\"label\":\"") + m + " · full\""), std::string::npos) << m;
  }
  EXPECT_EQ(html.find("#2 · full"), std::string::npos);
  // Every fit is still listed in the metrics table.
  EXPECT_NE(html.find("lambert+ward #200</td>"), std::string::npos);
}

}  // namespace
}  // namespace brdfit::report
