// The HTML pages in a real browser: headless Chromium (Debian's chromium) loads the report
// offline, and the test reads what the page recorded (every chart drawn, no script error) and
// what Chromium logged (no console message), and checks a screenshot is not blank. A broken
// page must be caught by the same checks (negative control). CI runs these (make test).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fmt/core.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "report/html_report.h"
#include "tests/report/browser.h"
#include "tests/report/report_fixture.h"

namespace brdfit::testing {
namespace {

namespace fs = std::filesystem;

std::string Join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "\n  " + x;
  return s;
}

class Browser : public ::testing::Test {
 protected:
  void SetUp() override {
    if (FindChromium().empty()) {
      FAIL() << "chromium not found: scripts/setup-deps.sh installs Debian's chromium (or set "
                "BRDFIT_CHROMIUM to a Chromium binary)";
    }
    dir_ = fs::temp_directory_path() /
           (std::string("brdfit-browser-") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + "-" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // Every chart drawn, no page error, no console message, and a screenshot with content.
  void ExpectCleanPage(const fs::path& html, int min_charts) {
    const PageCheck p = LoadPage(html, dir_ / ("load-" + html.stem().string()));
    ASSERT_EQ(p.exit_code, 0) << "chromium failed on " << html << ":\n" << p.log;
    ASSERT_TRUE(p.has_body_marker) << "the page's scripts did not run or the DOM is missing:\n"
                                   << p.dom.substr(0, 2000) << "\n" << p.log;
    EXPECT_GE(p.charts_expected, min_charts);
    EXPECT_EQ(p.charts_rendered, p.charts_expected) << html;
    EXPECT_EQ(p.canvases_marked_rendered, p.charts_expected) << html;
    EXPECT_TRUE(p.page_errors.empty()) << "page errors:" << Join(p.page_errors);
    EXPECT_TRUE(p.console_lines.empty()) << "console messages:" << Join(p.console_lines);

    const fs::path png = dir_ / (html.stem().string() + ".png");
    ASSERT_EQ(Screenshot(html, png, dir_ / ("shot-" + html.stem().string()), 1280, 1000), 0);
    ASSERT_TRUE(fs::exists(png)) << "no screenshot";
    const InkStats ink = MeasureInk(png);
    EXPECT_EQ(ink.width, 1280);
    // Text, tables and charts: a few percent of the pixels and many colours. A blank or
    // unstyled error page has almost no ink.
    EXPECT_GT(ink.non_white_fraction, 0.03) << png;
    EXPECT_GT(ink.distinct_colors, 40) << png;
  }

  fs::path dir_;
};

TEST_F(Browser, FixtureReportDrawsEveryChart) {
  const fs::path html = dir_ / "fixture.html";
  report::WriteHtmlReport(html, MakeFixtureReport(dir_));
  ExpectCleanPage(html, 15);
}

// The tables fit the page at 1280 and 1920 px without sideways scrolling, with the longest
// status a fit reports; a window narrower than the tables does scroll (the check can fail).
// The renders are set up to enlarge on a click.
TEST_F(Browser, TablesFitThePageAndRendersEnlarge) {
  report::Report r = MakeFixtureReport(dir_);
  for (report::Material& m : r.materials) {
    for (report::Entry& e : m.entries) {
      e.message =
          "a peak narrower than a pixel of the judge's images (f(0) / f(1 px) = 4e+06); the "
          "body's colour is off by 337 % in a channel; alpha ends on its bound";
    }
  }
  const fs::path html = dir_ / "wide.html";
  report::WriteHtmlReport(html, r);
  for (const int width : {1280, 1920}) {
    const PageCheck p = LoadPage(html, dir_ / fmt::format("load-{}", width), 120, width);
    ASSERT_EQ(p.exit_code, 0) << p.log;
    EXPECT_EQ(p.wide_tables, 0) << "tables wider than the page at " << width << " px";
    EXPECT_TRUE(p.page_errors.empty()) << Join(p.page_errors);
    EXPECT_NE(p.dom.find("id=\"lightbox\""), std::string::npos);
    EXPECT_NE(p.dom.find("title=\"click to enlarge\""), std::string::npos);
  }
  const PageCheck narrow = LoadPage(html, dir_ / "load-480", 120, 480);
  ASSERT_EQ(narrow.exit_code, 0) << narrow.log;
  EXPECT_GT(narrow.wide_tables, 0);
}

// Negative control: the same checks must catch a script error and a chart Chart.js rejects.
TEST_F(Browser, BrokenPageIsCaught) {
  const std::string js = report::ReadChartJs();
  std::string html = report::RenderHtml(MakeFixtureReport(dir_), js);
  const std::string first_type = R"("type":"bar")";
  const auto pos = html.find(first_type);
  ASSERT_NE(pos, std::string::npos);
  html.replace(pos, first_type.size(), R"("type":"no-such-chart-type")");
  const auto end = html.rfind("</body>");
  html.insert(end, "<script>notAFunction();</script>\n");
  const fs::path path = dir_ / "broken.html";
  std::ofstream(path) << html;
  const PageCheck p = LoadPage(path, dir_ / "load-broken");
  ASSERT_EQ(p.exit_code, 0) << p.log;
  ASSERT_TRUE(p.has_body_marker);
  EXPECT_EQ(p.charts_rendered, p.charts_expected - 1);
  ASSERT_EQ(p.page_errors.size(), 2u) << Join(p.page_errors);
  EXPECT_NE(p.page_errors[0].find("no-such-chart-type"), std::string::npos) << p.page_errors[0];
  EXPECT_NE(p.page_errors[1].find("notAFunction"), std::string::npos) << p.page_errors[1];
  EXPECT_FALSE(p.console_lines.empty());
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Acceptance: the demo ends by writing the report and printing its path; the report, the bench
// CSV and the bench plot open cleanly.
TEST_F(Browser, DemoReportAndBenchPlot) {
  const fs::path out = dir_ / "demo";
  const std::string cmd = std::string(BRDFIT_EXE) + " demo --quick -o " + out.string() + " > " +
                          (dir_ / "demo.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << ReadText(dir_ / "demo.log");
  const std::string log = ReadText(dir_ / "demo.log");
  const fs::path report = fs::absolute(out / "report.html");
  EXPECT_NE(log.find("report: " + report.string()), std::string::npos) << log;
  ASSERT_TRUE(fs::exists(report));
  ASSERT_TRUE(fs::exists(out / "bench.csv"));
  ASSERT_TRUE(fs::exists(out / "bench.html"));
  ExpectCleanPage(report, 10);
  ExpectCleanPage(out / "bench.html", 2);
}

}  // namespace
}  // namespace brdfit::testing
