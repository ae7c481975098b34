// Report building blocks: encoders (RFC 4648 vectors), the Pareto front against an
// independent sweep, slices against the generating model, the bench CSV round trip, the
// comparison's rules, factorization sidecars, input classification and the HTML structure.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>

#include "core/error.h"
#include "core/model_params.h"
#include "core/synth.h"
#include "io/factor_io.h"
#include "io/image_io.h"
#include "models/registry.h"
#include "report/bench_csv.h"
#include "report/compare.h"
#include "report/html_report.h"
#include "report/report_charts.h"
#include "report/report_inputs.h"
#include "report/report_slices.h"
#include "tests/report/report_fixture.h"
#include "tests/scratch_dir.h"

namespace brdfit::report {
namespace {

namespace fs = std::filesystem;

void WriteFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// ---- encoders -------------------------------------------------------------------------------

TEST(Encoders, Base64MatchesRfc4648TestVectors) {
  // RFC 4648 §10.
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64(std::string("\x00\xff\xfe", 3)), "AP/+");
}

TEST(Encoders, HtmlEscapeNeutralizesMarkup) {
  EXPECT_EQ(HtmlEscape("<a href=\"x\">&'</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
  EXPECT_EQ(HtmlEscape("θh plain"), "θh plain");
  EXPECT_EQ(HtmlEscape(std::string("a\x1b[31mb\x7f\0c\td", 12)),
            "a&#xFFFD;[31mb&#xFFFD;&#xFFFD;c\td");
}

TEST(Encoders, ScriptSafeJsonKeepsTheValueAndHasNoAngleBracket) {
  const nlohmann::json j = {{"title", "</script><script>alert(1)</script>"}, {"x", {1, 2}}};
  const std::string safe = ScriptSafeJson(j.dump());
  EXPECT_EQ(safe.find('<'), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(safe), j);
}

// ---- Pareto front ---------------------------------------------------------------------------

// Oracle: sort by (cost, error); walking in that order, a point is on the front iff its error
// is below every error seen at a strictly lower cost, and no point of equal cost has a lower
// error.
std::vector<std::size_t> SweepFront(const std::vector<CostError>& pts) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts[i].usable) idx.push_back(i);
  }
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return pts[a].cost != pts[b].cost ? pts[a].cost < pts[b].cost : pts[a].error < pts[b].error;
  });
  std::vector<std::size_t> front;
  double best_before = INFINITY;  // lowest error at strictly lower cost
  for (std::size_t k = 0; k < idx.size();) {
    std::size_t end = k;
    while (end < idx.size() && pts[idx[end]].cost == pts[idx[k]].cost) ++end;
    const double group_min = pts[idx[k]].error;
    for (std::size_t q = k; q < end; ++q) {
      const double e = pts[idx[q]].error;
      if (e == group_min && e < best_before) front.push_back(idx[q]);
    }
    best_before = std::min(best_before, group_min);
    k = end;
  }
  std::sort(front.begin(), front.end());
  return front;
}

TEST(Pareto, HandExample) {
  //            0 fast+bad  1 dominated  2 mid       3 slow+best  4 failed (would dominate)
  const std::vector<CostError> pts = {
      {1, 0.5, true}, {2, 0.6, true}, {3, 0.2, true}, {10, 0.1, true}, {0.5, 0.01, false}};
  EXPECT_EQ(ParetoFront(pts), (std::vector<std::size_t>{0, 2, 3}));
}

TEST(Pareto, AgreesWithSortSweepOnRandomSets) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coarse(1, 6);  // ties on purpose
  std::bernoulli_distribution usable(0.85);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<CostError> pts(1 + trial % 17);
    for (auto& p : pts) p = {double(coarse(rng)), double(coarse(rng)), usable(rng)};
    std::vector<std::size_t> got = ParetoFront(pts);
    // Sorted by cost as documented.
    for (std::size_t k = 1; k < got.size(); ++k) EXPECT_LE(pts[got[k - 1]].cost, pts[got[k]].cost);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, SweepFront(pts)) << "trial " << trial;
  }
}

TEST(Pareto, BestEntrySkipsFailedAndUnscored) {
  std::vector<Entry> e(3);
  const std::pair<const char*, double> spec[3] = {
      {"converged", 0.3}, {"failed", 0.01}, {"no_convergence", 0.2}};
  for (int i = 0; i < 3; ++i) {
    e[i].status = spec[i].first;
    e[i].metrics.ok = true;
    e[i].metrics.log_rmse = spec[i].second;
  }
  EXPECT_EQ(BestEntry(e), 2);
  e[2].metrics.ok = false;
  EXPECT_EQ(BestEntry(e), 0);
  EXPECT_EQ(BestEntry({}), -1);
}

// ---- slices ---------------------------------------------------------------------------------

TEST(Slices, GeneratingModelReproducesTheMeasuredCells) {
  const ModelInfo* m = FindModel("lambert+ggx");
  const std::vector<double> p = ResolveModelParams(*m, {"alpha=0.2", "kd_r=0.3"});
  const Grid grid{30, 30, 60, ThetaHMapping::kSqrt};
  Table t = SynthesizeTable(grid, [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); },
                            {});
  t.valid[grid.Index(5, 0, 29)] = 0;  // a hole in the θd = 0 slice (φd bin 29 holds 87..90°)
  std::vector<double> other = p;
  other.back() = 0.4;
  const auto slices = ComputeThetaHSlices(
      t, {0, 44}, 89, {{"truth", "fitted", ModelPredictor("lambert+ggx", p)},
                       {"other", "fitted", ModelPredictor("lambert+ggx", other)}});
  ASSERT_EQ(slices.size(), 2u);
  EXPECT_NEAR(slices[0].theta_d_deg, 1.5, 1e-12);  // bin 0 of 30 over 90°: centre 1.5°
  EXPECT_NEAR(slices[1].theta_d_deg, 43.5, 1e-12);  // bin 14 holds 42..45°
  EXPECT_NEAR(slices[0].phi_d_deg, 88.5, 1e-12);
  for (const Slice& s : slices) {
    ASSERT_EQ(s.series.size(), 3u);
    ASSERT_EQ(s.theta_h_deg.size(), 30u);
    int compared = 0, differs = 0;
    for (std::size_t i = 0; i < s.theta_h_deg.size(); ++i) {
      if (i > 0) {
        EXPECT_GT(s.theta_h_deg[i], s.theta_h_deg[i - 1]);
      }
      const double meas = s.series[0].value[i], fit = s.series[1].value[i];
      if (std::isnan(meas)) continue;
      EXPECT_NEAR(fit, meas, 1e-12 * meas) << "theta_h " << s.theta_h_deg[i];
      differs += std::abs(s.series[2].value[i] - meas) > 1e-3 * meas;
      ++compared;
    }
    EXPECT_GT(compared, 10);
    EXPECT_GT(differs, compared / 2);
  }
  EXPECT_TRUE(std::isnan(slices[0].series[0].value[5]));  // the hole is a gap, not a zero
  EXPECT_FALSE(std::isnan(slices[0].series[1].value[5]));
}

TEST(Slices, ModelPredictorRejectsUnknownModelsAndWrongParameterCounts) {
  EXPECT_THROW(ModelPredictor("no-such-model", {}), InputError);
  EXPECT_THROW(ModelPredictor("lambert+ggx", {0.1, 0.2}), InputError);
}

// ---- bench CSV ------------------------------------------------------------------------------

TEST(BenchCsv, RoundTripsEveryFieldIncludingQuotedText) {
  const ScratchDir scratch("csv");
  const fs::path& dir = scratch.path();
  BenchPoint b;
  b.material = "gold, \"metallic\"";
  b.table = "/x/gold.binary";
  b.model = "lambert+ggx";
  b.loss = "cbrt";
  b.budget = "stride:8";
  b.status = "failed";
  b.message = "line one\nline two";
  b.time_ms = 12.5;
  b.prepare_ms = 1.25;
  b.init_ms = 2.5;
  b.solve_ms = 8.75;
  b.fit_cells = 1234;
  b.iterations = 17;
  b.metrics = testing::Scored(0.01, 0.02, 0.125, 999);
  BenchPoint c = b;
  c.material = "plain";
  c.metrics.ok = false;
  c.message.clear();
  WriteBenchCsv(dir / "b.csv", {b, c});
  const auto back = ReadBenchCsv(dir / "b.csv");
  ASSERT_EQ(back.size(), 2u);
  const BenchPoint& r = back[0];
  EXPECT_EQ(r.material, b.material);
  EXPECT_EQ(r.message, b.message);
  EXPECT_EQ(r.budget, "stride:8");
  EXPECT_EQ(r.status, "failed");
  EXPECT_EQ(r.time_ms, 12.5);
  EXPECT_EQ(r.solve_ms, 8.75);
  EXPECT_EQ(r.fit_cells, 1234u);
  EXPECT_EQ(r.iterations, 17);
  EXPECT_EQ(r.metrics.rel_l2, 0.125);
  EXPECT_EQ(r.metrics.cells, 999u);
  EXPECT_TRUE(r.metrics.ok);
  EXPECT_FALSE(back[1].metrics.ok);
}

TEST(BenchCsv, ErrorsNameTheFileAndLine) {
  const ScratchDir scratch("csvbad");
  const fs::path& dir = scratch.path();
  WriteFile(dir / "nocol.csv", "material,model\nx,y\n");
  try {
    ReadBenchCsv(dir / "nocol.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nocol.csv"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("budget"), std::string::npos);
  }
  WriteFile(dir / "num.csv", "material,model,budget,time_ms,log_rmse\na,b,full,12,0.1\na,b,full,fast,0.1\n");
  try {
    ReadBenchCsv(dir / "num.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  WriteFile(dir / "quote.csv", "material,model,budget,time_ms,log_rmse\n\"a,b,full,1,2\n");
  EXPECT_THROW(ReadBenchCsv(dir / "quote.csv"), InputError);
}

// ---- compare --------------------------------------------------------------------------------

Report OneMaterial(const std::string& name, std::vector<std::pair<std::string, double>> fits) {
  Report r;
  Material& m = r.GetOrAddMaterial(name);
  for (const auto& [model, err] : fits) {
    Entry e;
    e.name = model;
    e.loss = "log";
    e.budget = "full";
    e.status = err < 0 ? "failed" : "converged";
    e.metrics.ok = err >= 0;
    e.metrics.log_rmse = e.metrics.cbrt_rmse = e.metrics.rel_l2 = std::max(err, 0.0);
    e.time_ms = 100;
    m.entries.push_back(e);
  }
  return r;
}

TEST(Compare, ThresholdDecidesBetterSameWorse) {
  const Report a = OneMaterial("gold", {{"ggx", 0.100}, {"beckmann", 0.100}, {"ward", 0.100}});
  const Report b = OneMaterial("gold", {{"ggx", 0.104}, {"beckmann", 0.106}, {"ward", 0.090}});
  const Comparison c = Compare(a, b, {});  // 5 %
  ASSERT_EQ(c.deltas.size(), 3u);
  EXPECT_EQ(c.deltas[0].change, Change::kSame);
  EXPECT_EQ(c.deltas[1].change, Change::kWorse);
  EXPECT_NEAR(c.deltas[1].rel_change, 0.06, 1e-12);
  EXPECT_EQ(c.deltas[2].change, Change::kBetter);
  EXPECT_EQ(c.Regressions(), 1);
  EXPECT_EQ(c.regressed_materials, std::vector<std::string>{"gold"});
  CompareOptions loose;
  loose.threshold = 0.10;
  EXPECT_FALSE(Compare(a, b, loose).Regressed());
}

TEST(Compare, AbsoluteFloorIgnoresRoundOffOnPerfectFits) {
  const Report a = OneMaterial("synthetic", {{"ggx", 1e-16}});
  const Report b = OneMaterial("synthetic", {{"ggx", 5e-16}});  // +400 %, but 4e-16 absolute
  EXPECT_FALSE(Compare(a, b).Regressed());
  CompareOptions strict;
  strict.abs_floor = 0;
  EXPECT_TRUE(Compare(a, b, strict).Regressed());
}

TEST(Compare, FailuresMissingAndAddedEntries) {
  Report a = OneMaterial("gold", {{"ggx", 0.1}, {"ward", -1}, {"phong", 0.2}});
  a.GetOrAddMaterial("gone").entries = OneMaterial("x", {{"ggx", 0.1}}).materials[0].entries;
  Report b = OneMaterial("gold", {{"ggx", -1}, {"ward", 0.1}, {"lafortune", 0.1}});
  b.GetOrAddMaterial("new").entries = OneMaterial("x", {{"ggx", 0.1}}).materials[0].entries;
  const Comparison c = Compare(a, b);
  EXPECT_EQ(c.Count(Change::kNowFails), 1);
  EXPECT_EQ(c.Count(Change::kFixed), 1);
  EXPECT_EQ(c.Count(Change::kMissing), 2);  // gold/phong and gone/ggx
  EXPECT_EQ(c.Count(Change::kAdded), 2);    // gold/lafortune and new/ggx
  EXPECT_EQ(c.Regressions(), 3);            // now-fails + 2 missing
  EXPECT_EQ(c.missing_materials, std::vector<std::string>{"gone"});
  EXPECT_EQ(c.added_materials, std::vector<std::string>{"new"});
  CompareOptions o;
  o.missing_is_regression = false;
  EXPECT_EQ(Compare(a, b, o).Regressions(), 1);
  const auto j = ComparisonToJson(c);
  EXPECT_EQ(j["regressions"], 3);
  EXPECT_EQ(j["counts"]["now-fails"], 1);
  const std::string text = FormatComparison(c);
  EXPECT_NE(text.find("REGRESSED: gold, gone"), std::string::npos) << text;
}

TEST(Compare, TimeRegressionOnlyWhenAsked) {
  Report a = OneMaterial("gold", {{"ggx", 0.1}});
  Report b = a;
  b.materials[0].entries[0].time_ms = 300;
  EXPECT_FALSE(Compare(a, b).Regressed());
  CompareOptions o;
  o.time_threshold = 0.5;
  const Comparison c = Compare(a, b, o);
  EXPECT_EQ(c.deltas[0].change, Change::kSlower);
  EXPECT_TRUE(c.Regressed());
}

TEST(Compare, MetricChoice) {
  EXPECT_EQ(kErrorMetrics[ErrorMetricIndex("cbrt_rmse")].value, &FitMetrics::cbrt_rmse);
  EXPECT_THROW(ErrorMetricIndex("psnr"), InputError);
}

// ---- inputs ---------------------------------------------------------------------------------

TEST(Inputs, FactorSidecarBecomesAnEntryOfItsTablesMaterial) {
  const ScratchDir scratch("sidecar");
  const fs::path& dir = scratch.path();
  // The sidecar with its two textures (io/factor_io.h adds format, version and textures): the
  // report reads a sidecar only together with them.
  const nlohmann::json j = {
      {"parameterization", "halfdiff"},
      {"solver", {{"resolution", 48}}},
      {"stats", {{"seconds", 0.25}, {"system_seconds", 0.2}, {"system_reused", false}}},
      {"source", {{"file", "/data/gold-paint.binary"}}},
      {"metrics",
       {{"fit_metrics",
         {{"ok", true}, {"log_rmse", 0.03}, {"cbrt_rmse", 0.04}, {"rel_l2", 0.5}, {"cells", 77},
          {"weighting", "bin-measure"}, {"cutoff_deg", 80}}},
        {"rendered",
         {{"ok", true}, {"psnr_db", 31.5}, {"psnr_srgb_db", 30.1}, {"median_rel_error", 0.058},
          {"p95_rel_error", 0.2}}}}}};
  FactorFiles files;
  files.sidecar = j;
  files.terms.resize(1);
  files.terms[0].p.image = files.terms[0].q.image = RgbImage::Filled(4, 4, 0.5f);
  WriteFactorFiles(FactorFilePaths(dir, "gold-paint.halfdiff"), files);
  std::string material, table;
  const Entry e = FactorEntry(dir / "gold-paint.halfdiff.factor.json", &material, &table);
  EXPECT_EQ(material, "gold-paint");
  EXPECT_EQ(table, "/data/gold-paint.binary");
  EXPECT_EQ(e.kind, Entry::Kind::kFactor);
  EXPECT_EQ(e.name, "factor:halfdiff");
  EXPECT_EQ(e.budget, "res 48");
  EXPECT_DOUBLE_EQ(e.time_ms, 250);
  EXPECT_DOUBLE_EQ(e.metrics.log_rmse, 0.03);
  EXPECT_EQ(e.metrics.cells, 77u);
  // The rendered error beside fit_metrics is read (the report ranks factorizations by it).
  EXPECT_TRUE(e.metrics.rendered.ok);
  EXPECT_DOUBLE_EQ(e.metrics.rendered.psnr_db, 31.5);
  EXPECT_DOUBLE_EQ(e.metrics.rendered.median_rel_error, 0.058);
  WriteFile(dir / "other.factor.json", R"({"format": "something-else"})");
  EXPECT_THROW(FactorEntry(dir / "other.factor.json", &material, &table), InputError);
}

TEST(Inputs, FoldersKeepKnownKindsAndExplicitUnknownFilesAreErrors) {
  const ScratchDir scratch("inputs");
  const fs::path& dir = scratch.path();
  BenchPoint b;
  b.material = "m";
  b.model = "ggx";
  b.budget = "full";
  b.status = "converged";
  WriteBenchCsv(dir / "bench.csv", {b});
  WriteFile(dir / "notes.txt", "hello");
  WritePng(dir / "render.png", Image(2, 2));
  const ReportSources s = ReadReportInputs({dir});
  EXPECT_EQ(s.report.bench.size(), 1u);
  EXPECT_EQ(s.report.renders.size(), 1u);  // a PNG by its name, decoded in full
  EXPECT_THROW(ReadReportInputs({dir / "notes.txt"}), InputError);
  EXPECT_THROW(ReadReportInputs({dir / "missing.csv"}), InputError);
  // A file named .png that is not one is refused (issue 14 item 14), in a folder too.
  WriteFile(dir / "fake.png", "not a png");
  EXPECT_THROW(ReadReportInputs({dir}), InputError);
}

// An NBRDF input is a table like a file (no file to read here: the caller tabulates it), its
// material named after the network; "nbrdf:" alone names none and is refused.
TEST(Inputs, NbrdfInputIsATableOfItsMaterial) {
  const ReportSources s = ReadReportInputs({"nbrdf:pink-felt"});
  ASSERT_EQ(s.tables.size(), 1u);
  EXPECT_EQ(s.tables.at("pink-felt"), fs::path("nbrdf:pink-felt"));
  ASSERT_EQ(s.report.materials.size(), 1u);
  EXPECT_EQ(s.report.materials[0].name, "pink-felt");
  EXPECT_EQ(s.report.materials[0].source, "nbrdf:pink-felt");
  EXPECT_THROW(ReadReportInputs({"nbrdf:"}), InputError);
  EXPECT_THROW(ReadReportInputs({"nbrdf-pink-felt"}), InputError);  // not a prefix: a missing file
}

// ---- HTML ----------------------------------------------------------------------------------

int Count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

Report OneMaterialForHtml() {
  Report r;
  Entry e;
  e.name = "lambert+ggx";
  e.loss = "log";
  e.budget = "full";
  e.status = "converged";
  e.metrics.ok = true;
  e.metrics.log_rmse = 0.01;
  e.metrics.cbrt_rmse = 0.02;
  e.metrics.rel_l2 = 0.1;
  r.GetOrAddMaterial("gold").entries.push_back(e);
  return r;
}

TEST(Html, StructureOfTheFixtureReport) {
  const ScratchDir scratch("html");
  const fs::path& dir = scratch.path();
  const Report r = testing::MakeFixtureReport(dir);
  const std::string html = RenderHtml(r, "/* Chart stand-in */");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(html, m, std::regex(R"(data-charts-expected="(\d+)\")")));
  const int expected = std::stoi(m[1]);
  // Summary + 2 bench materials + per material (Pareto, one chart per error metric, 4 slices;
  // no rendered errors, so no per-region chart).
  EXPECT_EQ(expected, 1 + 2 + 2 * (1 + static_cast<int>(kNumErrorMetrics) + 4));
  EXPECT_EQ(Count(html, "<canvas id=\"chart-"), expected);
  EXPECT_EQ(Count(html, "<script type=\"application/json\" data-chart="), expected);
  // Every chart configuration is valid JSON with a type.
  const std::regex spec(R"re(<script type="application/json" data-chart="[^"]+">([^<]*)</script>)re");
  int parsed = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), spec); it != std::sregex_iterator();
       ++it) {
    const auto j = nlohmann::json::parse((*it)[1].str());
    EXPECT_TRUE(j.contains("type"));
    ++parsed;
  }
  EXPECT_EQ(parsed, expected);
  // Best fit of each material starred; the failed fit flagged; title escaped; render inlined.
  // (each row is in a material's accuracy table and its cost table).
  EXPECT_EQ(Count(html, "<tr class=\"best\">"), 2 * 2);
  EXPECT_EQ(Count(html, "<tr class=\"failed\">"), 2 * 2);
  EXPECT_NE(html.find("fixture report &lt;with&gt; &quot;markup&quot; &amp; ampersands"),
            std::string::npos);
  EXPECT_EQ(html.find("<with>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);
  // Nothing is loaded from elsewhere.
  EXPECT_EQ(Count(html, "src=\"http"), 0);
  EXPECT_EQ(Count(html, "<link"), 0);
}

TEST(Html, ChartsWithoutDataBecomeNotes) {
  // Fits without times (a parameters JSON): no Pareto plot, but one chart per error metric and a
  // summary.
  Report r = OneMaterialForHtml();
  const std::string html = RenderHtml(r, "");
  EXPECT_NE(html.find(fmt::format("data-charts-expected=\"{}\"", 1 + kNumErrorMetrics)),
            std::string::npos);
  EXPECT_NE(html.find("No data to plot: scatter plot of fit time"), std::string::npos);
}

TEST(Html, UnreadableRenderBecomesANote) {
  Report r;
  r.renders.push_back({"gone", "/no/such/render.png"});
  const std::string html = RenderHtml(r, "");
  EXPECT_NE(html.find("/no/such/render.png could not be read as a PNG"), std::string::npos);
}

TEST(Html, ChartJsMissingIsAnInputErrorWithTheFix) {
  try {
    ReadChartJs("/no/such/chart.min.js");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("/no/such/chart.min.js"), std::string::npos);
    EXPECT_NE(msg.find("libjs-chart.js"), std::string::npos);
  }
}

TEST(Html, DebianChartJsIsVersion3) {
  if (!fs::exists(kDefaultChartJs)) GTEST_SKIP() << kDefaultChartJs << " not found, skipping";
  const std::string js = ReadChartJs(kDefaultChartJs);
  EXPECT_NE(js.find("Chart.js v3."), std::string::npos);
}

}  // namespace
}  // namespace brdfit::report
