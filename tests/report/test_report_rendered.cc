// The rendered-image metric in the report layer: how the best result is chosen, the HTML
// tables, renders and legend, `compare` on rendered errors, the bench CSV's rendered columns,
// and the renders of pipeline/rendered_views.h against exact properties of the scene (a fit
// equal to its table: white error map, identical spheres; twice the table: full colour).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/model_params.h"
#include "core/synth.h"
#include "io/image_io.h"
#include "models/registry.h"
#include "pipeline/rendered_views.h"
#include "report/bench_csv.h"
#include "report/compare.h"
#include "report/html_report.h"
#include "report/rendered_colors.h"
#include "report/report_charts.h"
#include "report/report_model.h"
#include "tests/report/report_fixture.h"
#include "tests/scratch_dir.h"

namespace brdfit::report {
namespace {

namespace fs = std::filesystem;

RenderedError Rendered(double psnr, double median) {
  RenderedError r;
  r.ok = true;
  r.psnr_db = psnr;
  r.psnr_srgb_db = psnr - 5;
  r.median_rel_error = median;
  r.p95_rel_error = 2 * median;
  return r;
}

Entry Fit(const std::string& name, double log_rmse) {
  Entry e;
  e.name = name;
  e.loss = "log";
  e.budget = "full";
  e.status = "converged";
  e.metrics = testing::Scored(log_rmse, 2 * log_rmse, 3 * log_rmse, 100);
  e.time_ms = 10;
  return e;
}

std::size_t Count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

// ---- best ---------------------------------------------------------------------------------

TEST(RenderedBest, HighestPsnrMinusTwentyTimesMedianAmongRenderedFits) {
  std::vector<Entry> e = {Fit("a", 0.01), Fit("b", 0.02), Fit("c", 0.001), Fit("d", 0.03)};
  e[0].metrics.rendered = Rendered(33.4, 0.79);  // 17.6
  e[1].metrics.rendered = Rendered(30.6, 0.56);  // 19.4: best
  // c has the lowest log_rmse but no rendered error: not a candidate while others have one.
  e[3].metrics.rendered = Rendered(40, 0.05);  // 39 but failed: never
  e[3].status = "failed";
  BestPick p = PickBest(e);
  EXPECT_EQ(p.index, 1);
  EXPECT_EQ(p.by, BestBy::kRendered);
  EXPECT_DOUBLE_EQ(RenderedScore(e[1].metrics.rendered), 30.6 - 20 * 0.56);
  // No rendered error anywhere (an old report): log_rmse, and the rule says so.
  for (Entry& x : e) x.metrics.rendered = {};
  p = PickBest(e);
  EXPECT_EQ(p.index, 2);
  EXPECT_EQ(p.by, BestBy::kLogRmse);
  EXPECT_NE(BestRule(p.by).find("no result has a rendered-image error"), std::string::npos);
  EXPECT_EQ(PickBest({}).by, BestBy::kNone);
  // A fit the fit report marks as chosen (core/model_choice.h) is preferred to any score.
  e[0].metrics.rendered = Rendered(33.4, 0.79);
  e[1].metrics.rendered = Rendered(30.6, 0.56);
  e[0].chosen = true;
  p = PickBest(e);
  EXPECT_EQ(p.index, 0);
  EXPECT_EQ(p.by, BestBy::kChosen);
  e[0].status = "failed";  // but never a failed one
  EXPECT_EQ(PickBest(e).index, 1);
}

// ---- HTML ---------------------------------------------------------------------------------

Report TwoFits() {
  Report r;
  Material& m = r.GetOrAddMaterial("gold");
  m.entries = {Fit("lambert+ggx", 0.0104), Fit("lambert+ward", 0.0166)};
  m.entries[0].metrics.rendered = Rendered(33.43, 0.787);
  m.entries[1].metrics.rendered = Rendered(30.55, 0.563);
  return r;
}

// Every model with a rendered error has its bar, the chosen fit's model included (its pick is
// BestBy::kChosen, not kRendered: the chart drew no bar for it, seen on a `--model auto` report).
TEST(RenderedCharts, PsnrSummaryHasABarForEveryRenderedModelChosenIncluded) {
  Report r = TwoFits();
  r.materials[0].entries[1].chosen = true;
  const Palette palette(r);
  const nlohmann::json chart = PsnrSummaryChart("t", r, palette);
  const auto& sets = chart["data"]["datasets"];
  ASSERT_EQ(sets.size(), 2u);
  for (const auto& set : sets) {
    ASSERT_EQ(set["data"].size(), 1u);
    ASSERT_TRUE(set["data"][0].is_number()) << set.dump();
    const double want = set["label"] == "lambert+ggx" ? 33.43 : 30.55;
    EXPECT_DOUBLE_EQ(set["data"][0].get<double>(), want) << set["label"];
  }
}

// The per-region chart: one dataset per judged region, one bar per rendered entry, the
// region's PSNR on one linear dB axis; a region no entry judged has no dataset; a fit without a
// rendered error has no group.
TEST(RenderedCharts, RegionPsnrChartHasOneDatasetPerJudgedRegion) {
  Report r = TwoFits();
  Material& m = r.materials[0];
  m.entries.push_back(Fit("lambert", 0.05));  // no rendered error
  const double psnr[2][3] = {{48.9, 36.0, 23.7}, {41.0, 30.5, 28.2}};
  for (int i = 0; i < 2; ++i) {
    for (int g = 0; g < 3; ++g) {
      m.entries[i].metrics.rendered.regions[g].lights = 3;
      m.entries[i].metrics.rendered.regions[g].psnr_db = psnr[i][g];
      m.entries[i].metrics.rendered.regions[g].median_rel_error = 0.1;
    }
  }
  const nlohmann::json chart = RegionPsnrChart("t", m);
  EXPECT_EQ(chart["type"], "bar");
  EXPECT_EQ(chart["options"]["scales"]["y"]["type"], "linear");
  EXPECT_NE(chart["options"]["scales"]["y"]["title"]["text"].get<std::string>().find("dB"),
            std::string::npos);
  ASSERT_EQ(chart["data"]["labels"].size(), 2u);
  const auto& sets = chart["data"]["datasets"];
  ASSERT_EQ(sets.size(), 3u) << "front, side, rim; the environment was not judged";
  const char* names[] = {"front", "side", "rim"};
  // Entries in RankEntries' order: lambert+ggx (the higher whole-domain score from its regions)
  // first.
  for (int g = 0; g < 3; ++g) {
    EXPECT_EQ(sets[g]["label"], names[g]);
    EXPECT_DOUBLE_EQ(sets[g]["data"][0].get<double>(), psnr[0][g]);
    EXPECT_DOUBLE_EQ(sets[g]["data"][1].get<double>(), psnr[1][g]);
  }
  // No rendered error anywhere: no chart.
  for (Entry& e : m.entries) e.metrics.rendered = {};
  EXPECT_TRUE(RegionPsnrChart("t", m).is_null());
}

// One error metric per chart: its own log axis, titled with its name, one dataset.
TEST(RenderedCharts, EachErrorMetricHasItsOwnChartAndAxis) {
  const Report r = TwoFits();
  for (std::size_t k = 0; k < kNumErrorMetrics; ++k) {
    const nlohmann::json chart = MetricsChart("t", r.materials[0], k);
    ASSERT_EQ(chart["data"]["datasets"].size(), 1u);
    EXPECT_EQ(chart["data"]["datasets"][0]["label"], kErrorMetrics[k].name);
    const auto& y = chart["options"]["scales"]["y"];
    EXPECT_EQ(y["type"], "logarithmic");
    EXPECT_EQ(y["title"]["text"].get<std::string>().rfind(kErrorMetrics[k].name, 0), 0u);
    // Bars in RankEntries' order: lambert+ward (the higher rendered score, 30.55 - 20 * 0.563)
    // first.
    const auto& data = chart["data"]["datasets"][0]["data"];
    ASSERT_EQ(data.size(), 2u);
    EXPECT_EQ(chart["data"]["labels"][0], "lambert+ward (full)");
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_DOUBLE_EQ(data[i].get<double>(),
                       r.materials[0].entries[1 - i].metrics.*kErrorMetrics[k].value);
    }
  }
}

TEST(RenderedHtml, PsnrAndLuminanceErrorLeadTheTablesAndPickTheStar) {
  const std::string html = RenderHtml(TwoFits(), "");
  // The metric table: approximation, then PSNR and luminance error.
  EXPECT_NE(html.find("<th class=\"l\">approximation</th><th>PSNR (dB)</th><th class=\"wrap\">"
                      "median lum. err.</th>"),
            std::string::npos);
  // The summary: material, then PSNR and luminance error of its best.
  EXPECT_NE(html.find("<th class=\"l\">material</th><th>PSNR (dB)</th>"), std::string::npos);
  // The star goes to ward (30.55 - 11.26 > 33.43 - 15.74) although ggx has the lower log_rmse.
  EXPECT_NE(html.find("<tr class=\"best\"><td class=\"l\">★ lambert+ward</td><td>30.55</td>"),
            std::string::npos)
      << html.substr(html.find("<section id=\"m-gold\""), 3000);
  EXPECT_NE(html.find("highest rendered score S (per region min(PSNR, 60 dB) − 20 × median"),
            std::string::npos);
  EXPECT_NE(html.find("30.55 · 56.3 %"), std::string::npos);
  EXPECT_EQ(html.find("no result has a rendered-image error"), std::string::npos);

  Report old = TwoFits();
  for (Entry& e : old.materials[0].entries) e.metrics.rendered = {};
  const std::string old_html = RenderHtml(old, "");
  EXPECT_NE(old_html.find("★ lambert+ggx"), std::string::npos);
  EXPECT_NE(old_html.find("no result has a rendered-image error"), std::string::npos);
}

TEST(RenderedHtml, ViewsAreEmbeddedWithALegendOrTheReasonIsGiven) {
  Report r = TwoFits();
  Image img(4, 4);
  const std::string png = EncodePng(img);
  MaterialViews& v = r.materials[0].views;
  v.entry_key = "lambert+ward | log | full";
  v.resolution = 4;
  v.exposure = 2;
  v.lights = {{45, png, png, png, 30.1, 0.5}, {80, png, png, png, 31.2, 0.25}};
  const std::string html = RenderHtml(r, "");
  EXPECT_EQ(Count(html, "src=\"data:image/png;base64," + Base64(png) + "\""), 6u);
  EXPECT_NE(html.find("light at 80° from the view: PSNR 31.20 dB, median lum. err. 25.0 %"),
            std::string::npos);
  // The legend's gradient is drawn from the scale's own colours.
  EXPECT_NE(html.find(HexColor(ErrorColor(-1)) + " 0%"), std::string::npos);
  EXPECT_NE(html.find(HexColor(ErrorColor(1)) + " 100%"), std::string::npos);
  EXPECT_NE(html.find(HexColor(kViewMasked)), std::string::npos);

  Report none = TwoFits();
  none.materials[0].views.missing = "No renders: the table of this material was not given.";
  const std::string html2 = RenderHtml(none, "");
  EXPECT_NE(html2.find("No renders: the table of this material was not given."), std::string::npos);
  EXPECT_EQ(html2.find("class=\"legend\""), std::string::npos);
}

TEST(RenderedColors, ScaleIsWhiteToOnePercentAndFullAtOneHundred) {
  EXPECT_EQ(ErrorColor(0.005), (Srgb{1, 1, 1}));
  EXPECT_EQ(ErrorColor(-0.01), (Srgb{1, 1, 1}));
  EXPECT_EQ(ErrorColor(1.0), kErrorBrighter);
  EXPECT_EQ(ErrorColor(7.0), kErrorBrighter);
  EXPECT_EQ(ErrorColor(-1.0), kErrorDarker);
  EXPECT_DOUBLE_EQ(ErrorScaleT(0.1), 0.5);  // a decade is half the scale
  const Srgb half = ErrorColor(0.1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(half[c], 0.5 * (1 + kErrorBrighter[c]), 1e-12);
  EXPECT_EQ(HexColor({1, 0, 0.5}), "#ff0080");
}

// ---- renders of a material ------------------------------------------------------------------

Image Decode(const std::string& png, const fs::path& dir) {
  const fs::path p = dir / "x.png";
  std::ofstream(p, std::ios::binary) << png;
  return ReadPng(p);
}

// A Lambertian table: trilinear lookups of a constant are exact, so a fit with the table's own
// albedo renders identically and one with twice the albedo is +100 % at every pixel.
TEST(RenderedViews, ExactFitIsWhiteAndTwiceTheTableIsFullRed) {
  const ScratchDir scratch("views");
  const ModelInfo& m = *FindModel("lambert");
  const std::vector<double> truth = m.DefaultParams();
  const Table table = SynthesizeTable(Grid{30, 30, 60, ThetaHMapping::kSqrt},
                                      [&](const Geometry& g, double rgb[3]) { m.eval(truth.data(), g, rgb); },
                                      {});
  Material mat;
  mat.name = "synthetic";
  mat.entries = {Fit("lambert", 0.01)};
  mat.entries[0].params = truth;
  // A fit reproducing the table is white wherever the error is compared; 2x is +100 %.
  const MaterialViews same = pipeline::RenderMaterialViews(table, mat, {}, {45, 80});
  ASSERT_TRUE(same.missing.empty()) << same.missing;
  ASSERT_EQ(same.lights.size(), 2u);
  EXPECT_EQ(same.resolution, pipeline::kViewResolution);
  EXPECT_EQ(same.metric_resolution, 64);
  EXPECT_EQ(same.entry_key, mat.entries[0].Key());
  std::vector<double> twice = truth;
  for (double& kd : twice) kd *= 2;  // f = kd / pi: linear
  mat.entries[0].params = twice;
  const MaterialViews bright = pipeline::RenderMaterialViews(table, mat, {}, {45, 80});
  ASSERT_TRUE(bright.missing.empty()) << bright.missing;
  for (std::size_t k = 0; k < 2; ++k) {
    const Image meas = Decode(same.lights[k].measured_png, scratch.path());
    const Image fit = Decode(same.lights[k].approx_png, scratch.path());
    const Image err = Decode(same.lights[k].error_png, scratch.path());
    const Image err2 = Decode(bright.lights[k].error_png, scratch.path());
    const int n = pipeline::kViewResolution;
    ASSERT_EQ(meas.width, n);
    EXPECT_GT(same.lights[k].psnr_db, 150);  // round-off only
    EXPECT_LT(same.lights[k].median_rel_error, 1e-12);
    EXPECT_EQ(bright.lights[k].median_rel_error, 1.0);
    int white = 0, red = 0, lit = 0;
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const float* a = meas.At(x, y);
        const float* b = fit.At(x, y);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1.01f / 255) << x << "," << y;
        const float* e = err.At(x, y);
        const float* e2 = err2.At(x, y);
        const bool shaded = e[0] > 0.9f && e[1] > 0.9f && e[2] > 0.9f;  // white: compared, <= 1 %
        if (!shaded) continue;
        ++lit;
        ++white;
        const bool full = std::abs(e2[0] - kErrorBrighter[0]) < 1.0f / 255 &&
                          std::abs(e2[1] - kErrorBrighter[1]) < 1.0f / 255 &&
                          std::abs(e2[2] - kErrorBrighter[2]) < 1.0f / 255;
        red += full;
      }
    }
    EXPECT_GT(lit, 1000);
    EXPECT_EQ(red, white);  // every compared pixel: +100 %, full colour
  }
  // An unknown light is refused; a failed fit gives the reason.
  EXPECT_THROW(pipeline::RenderMaterialViews(table, mat, {}, {50}), InputError);
  mat.entries[0].status = "failed";
  EXPECT_NE(pipeline::RenderMaterialViews(table, mat, {}, {45}).missing.find("no usable"),
            std::string::npos);
}

// ---- compare --------------------------------------------------------------------------------

TEST(RenderedCompare, PsnrDropOrLuminanceRiseBeyondThresholdIsARegression) {
  Report a = TwoFits(), b = TwoFits();
  auto& eb = b.materials[0].entries;
  eb[0].metrics.rendered = Rendered(33.43 - 0.6, 0.787);         // -0.6 dB
  eb[1].metrics.rendered = Rendered(30.55 - 0.4, 0.563 + 0.01);  // -0.4 dB, +1 point
  Comparison c = Compare(a, b);
  ASSERT_EQ(c.deltas.size(), 2u);
  EXPECT_EQ(c.deltas[0].change, Change::kWorseRendered);
  EXPECT_TRUE(c.deltas[0].regression);
  EXPECT_NEAR(c.deltas[0].psnr_change_db, -0.6, 1e-9);
  EXPECT_EQ(c.deltas[1].change, Change::kSame);
  EXPECT_FALSE(c.deltas[1].regression);
  EXPECT_NEAR(c.deltas[1].lum_change_points, 1.0, 1e-9);
  EXPECT_EQ(c.Regressions(), 1);
  // +3 points of luminance error is a regression too; --ignore-rendered turns both off.
  eb[1].metrics.rendered = Rendered(30.55, 0.563 + 0.03);
  c = Compare(a, b);
  EXPECT_TRUE(c.deltas[1].rendered_regression);
  EXPECT_EQ(c.Regressions(), 2);
  CompareOptions o;
  o.judge_rendered = false;
  EXPECT_FALSE(Compare(a, b, o).Regressed());
  const auto j = ComparisonToJson(c);
  EXPECT_EQ(j["counts"]["worse-rendered"], 2);
  EXPECT_NEAR(j["deltas"][1]["lum_change_points"].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(j["deltas"][0]["new_metrics"]["rendered"]["psnr_db"].get<double>(), 32.83, 1e-9);
  const std::string text = FormatComparison(c);
  EXPECT_NE(text.find("PSNR 33.43 -> 32.83 dB (-0.60)"), std::string::npos) << text;
  EXPECT_NE(text.find("(+3.0 pt)"), std::string::npos) << text;
  // A region that fell counts though the pooled numbers hold: the rim 1 dB worse.
  Report ra = TwoFits(), rb = TwoFits();
  for (Report* r : {&ra, &rb}) {
    for (Entry& e : r->materials[0].entries) {
      e.metrics.rendered.regions[0] = {6, 40.0, 0.05};
      e.metrics.rendered.regions[2] = {3, 30.0, 0.2};
    }
  }
  EXPECT_FALSE(Compare(ra, rb).Regressed());
  rb.materials[0].entries[0].metrics.rendered.regions[2].psnr_db = 29.0;
  const Comparison rc = Compare(ra, rb);
  EXPECT_TRUE(rc.deltas[0].rendered_regression);
  EXPECT_EQ(rc.deltas[0].worst_region, "rim");
  EXPECT_NEAR(rc.deltas[0].region_drop_db, 1.0, 1e-12);
  EXPECT_NE(FormatComparison(rc).find("rim light PSNR -1.00 dB"), std::string::npos)
      << FormatComparison(rc);
  EXPECT_EQ(ComparisonToJson(rc)["deltas"][0]["new_metrics"]["rendered"]["regions"]["rim"]
                                ["psnr_db"]
                                    .get<double>(),
            29.0);
  // Without the metric on one side (an old report) nothing is judged on it.
  Report old = TwoFits();
  for (Entry& e : old.materials[0].entries) e.metrics.rendered = {};
  EXPECT_FALSE(Compare(old, b).Regressed());
  EXPECT_NE(FormatComparison(Compare(old, b), true).find("rendered error only in the new report"),
            std::string::npos);
}

// ---- bench CSV ------------------------------------------------------------------------------

TEST(RenderedBenchCsv, ColumnsAppendedAndReadBack) {
  const ScratchDir scratch("csvr");
  const auto& cols = BenchCsvColumns();
  ASSERT_EQ(cols.size(), 33u);
  // The columns before the metric keep their places; its five follow, then the regions'.
  EXPECT_EQ(cols[19], "message");
  EXPECT_EQ(std::vector<std::string>(cols.begin() + 20, cols.begin() + 25),
            (std::vector<std::string>{"psnr_db", "psnr_srgb_db", "median_rel_error",
                                      "p95_rel_error", "body_color_error"}));
  EXPECT_EQ(
      std::vector<std::string>(cols.end() - 8, cols.end()),
      (std::vector<std::string>{"front_psnr_db", "front_median_rel_error", "side_psnr_db",
                                "side_median_rel_error", "rim_psnr_db", "rim_median_rel_error",
                                "environment_psnr_db", "environment_median_rel_error"}));
  BenchPoint b;
  b.material = "gold";
  b.model = "lambert+ggx";
  b.budget = "full";
  b.status = "converged";
  b.metrics = testing::Scored(0.01, 0.02, 0.1, 10);
  b.metrics.rendered = Rendered(33.41, 0.788);
  b.metrics.rendered.body_color_error = 0.375;
  b.metrics.rendered.regions[0] = {6, 35.5, 0.5};
  b.metrics.rendered.regions[2] = {3, 21.25, 1.5};  // no side lights: its columns stay empty
  BenchPoint none = b;
  none.metrics.rendered = {};
  WriteBenchCsv(scratch.path() / "b.csv", {b, none});
  const auto back = ReadBenchCsv(scratch.path() / "b.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(back[0].metrics.rendered.ok);
  EXPECT_EQ(back[0].metrics.rendered.psnr_db, 33.41);
  EXPECT_EQ(back[0].metrics.rendered.psnr_srgb_db, b.metrics.rendered.psnr_srgb_db);
  EXPECT_EQ(back[0].metrics.rendered.median_rel_error, 0.788);
  EXPECT_EQ(back[0].metrics.rendered.p95_rel_error, b.metrics.rendered.p95_rel_error);
  EXPECT_EQ(back[0].metrics.rendered.body_color_error, 0.375);
  EXPECT_EQ(back[0].metrics.rendered.regions[0].psnr_db, 35.5);
  EXPECT_EQ(back[0].metrics.rendered.regions[0].median_rel_error, 0.5);
  EXPECT_EQ(back[0].metrics.rendered.regions[1].lights, 0);
  EXPECT_EQ(back[0].metrics.rendered.regions[2].psnr_db, 21.25);
  EXPECT_EQ(back[0].metrics.rendered.regions[2].lights, 1);  // judged; the CSV has no count
  EXPECT_FALSE(back[1].metrics.rendered.ok);
  for (const RenderedRegionError& g : back[1].metrics.rendered.regions) EXPECT_EQ(g.lights, 0);
  // A region's PSNR without its median is refused.
  std::string text = BenchCsvText({b});
  text.replace(text.rfind("1.5"), 3, "");
  std::ofstream(scratch.path() / "half.csv") << text;
  try {
    ReadBenchCsv(scratch.path() / "half.csv");
    ADD_FAILURE() << "a region's PSNR without its median was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rim_psnr_db and rim_median_rel_error must both"),
              std::string::npos)
        << e.what();
  }
  // The body's colour is optional (core/metrics.h): a row without it reads as not computed,
  // and is written back without it.
  BenchPoint no_body = b;
  no_body.metrics.rendered.body_color_error = std::numeric_limits<double>::quiet_NaN();
  WriteBenchCsv(scratch.path() / "nobody.csv", {no_body});
  const auto nb = ReadBenchCsv(scratch.path() / "nobody.csv");
  ASSERT_EQ(nb.size(), 1u);
  EXPECT_TRUE(nb[0].metrics.rendered.ok);
  EXPECT_TRUE(std::isnan(nb[0].metrics.rendered.body_color_error));
  EXPECT_EQ(BenchCsvText(nb), BenchCsvText({no_body}));
  // A file written before the columns existed reads without them.
  std::ofstream(scratch.path() / "old.csv") << "material,model,budget,time_ms,log_rmse\na,b,full,1,0.1\n";
  const auto old = ReadBenchCsv(scratch.path() / "old.csv");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_FALSE(old[0].metrics.rendered.ok);
}

}  // namespace
}  // namespace brdfit::report
