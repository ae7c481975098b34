// `brdfit report RESULTS... -o report.html`: one self-contained HTML page from fit reports,
// factorizations, bench CSVs, renders and tables, with θh slices and renders of every material
// whose table is at hand (built by pipeline/build_report.h, drawn by report/html_report.h).
// Also the demo's last step (order 90).
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/progress.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "pipeline/build_report.h"
#include "pipeline/inputs.h"
#include "pipeline/rendered_views.h"
#include "report/html_report.h"
#include "report/report_inputs.h"
#include "report/report_slices.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct ReportCliOptions {
  std::vector<std::string> inputs;
  std::string out = "report.html";
  std::string title;
  std::vector<double> theta_d = report::DefaultSliceThetaD();
  double phi_d = 90;
  bool no_slices = false;
  std::vector<double> render_lights = pipeline::DefaultViewLights();
  bool no_renders = false;
  std::string chart_js;
  bool keep_going = false;
  bool quiet = false;
};

void CheckOptions(const ReportCliOptions& o) {
  for (const double td : o.theta_d) {
    if (!(td >= 0 && td < 90)) throw InputError(fmt::format("--theta-d {} outside [0, 90)", td));
  }
  if (!(o.phi_d >= 0 && o.phi_d < 180)) {
    throw InputError(fmt::format("--phi-d {} outside [0, 180)", o.phi_d));
  }
  if (!o.no_renders) pipeline::CheckViewLights(o.render_lights);
  if (fs::is_directory(o.out)) throw InputError(o.out, "is a folder; give the HTML file name");
}

int RunReport(const ReportCliOptions& o) {
  CheckOptions(o);
  const fs::path chart_js = o.chart_js.empty() ? report::ChartJsPath() : fs::path(o.chart_js);
  const std::vector<std::string> given = pipeline::ExpandInputs(o.inputs);  // nbrdf:all
  std::vector<fs::path> read = pipeline::InputFiles(given);
  read.push_back(chart_js);
  CheckOutputs(read, {{o.out, "-o"}});
  const std::string js = report::ReadChartJs(chart_js);  // fail before any work
  std::vector<std::string> unreadable;                   // with --keep-going: the inputs left out
  report::ReportSources sources = report::ReadReportInputs(
      std::vector<fs::path>(given.begin(), given.end()), o.keep_going ? &unreadable : nullptr);
  pipeline::ReportRequest q;
  q.title = o.title;
  q.theta_d = o.theta_d;
  q.phi_d = o.phi_d;
  q.slices = !o.no_slices;
  q.renders = !o.no_renders;
  q.render_lights = o.render_lights;
  q.keep_going = o.keep_going;
  std::optional<Progress> bar;
  q.on_material = [&](std::size_t materials, const std::string& material) {
    if (!bar) bar.emplace(materials, "slices and renders", !o.quiet);
    bar->Step(material);
  };
  q.on_warning = [&](const std::string& material, const std::string& warning) {
    if (!o.quiet) {
      fmt::print(stderr, "brdfit: warning: material '{}': {}: no slices or renders\n",
                 TerminalSafe(material), TerminalSafe(warning));
    }
  };
  const pipeline::BuiltReport built =
      pipeline::BuildReport(std::move(sources), std::move(unreadable), q);
  if (bar) bar->Done();
  const report::Report& r = built.report;
  const std::string html = report::RenderHtml(r, js);
  WriteTextAtomically(o.out, html);
  if (!o.quiet) {
    std::size_t entries = 0, views = 0;
    for (const auto& m : r.materials) {
      entries += m.entries.size();
      views += m.views.lights.size();
    }
    // The sphere renders of the metric's scene, and the PNG renders given as inputs.
    fmt::print(
        "wrote {} ({} materials, {} results, {} bench points, {} sphere renders, {} "
        "renders given)\n",
        fs::absolute(o.out).string(), r.materials.size(), entries, r.bench.size(), views,
        r.renders.size());
  }
  if (!built.problems.empty()) {
    for (const std::string& p : built.problems) {
      fmt::print(stderr, "brdfit: error: {}\n", TerminalSafe(p));
    }
    fmt::print(stderr, "brdfit: {} problem{} noted in {} (--keep-going)\n", built.problems.size(),
               built.problems.size() == 1 ? "" : "s", o.out);
    return kExitBadInput;
  }
  return kExitOk;
}

Registrar reg{
    "report", "One self-contained HTML page of metrics, Pareto plots, slices and renders",
    [](CLI::App& sub) {
      auto o = std::make_shared<ReportCliOptions>();
      sub.add_option("results", o->inputs,
                     "fit reports, .factor.json sidecars, bench .csv, .png renders, tables "
                     "(files or nbrdf:NAME), or folders holding them")
          ->required();
      sub.add_option("-o,--out", o->out, "output HTML file")->capture_default_str();
      sub.add_option("--title", o->title, "page title");
      sub.add_option("--theta-d", o->theta_d,
                     "theta_d of the slices in degrees (each snaps to its bin's centre)")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_option("--phi-d", o->phi_d, "phi_d of the slices in degrees")->capture_default_str();
      sub.add_flag("--no-slices", o->no_slices, "skip the theta_h slices");
      sub.add_option("--render-lights", o->render_lights,
                     "lights of the renders beside each material, degrees from the view (among "
                     "the rendered-image metric's 0,30,45,60,70,80,95,110,125,140,152,165)")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_flag("--no-renders", o->no_renders,
                   "skip the renders (with --no-slices: no table is read)");
      sub.add_option("--chart-js", o->chart_js,
                     "Chart.js to inline (default $BRDFIT_CHART_JS or "
                     "/usr/share/javascript/chart.js/chart.min.js)");
      sub.add_flag("--keep-going", o->keep_going,
                   "write the page despite unreadable inputs or tables (each noted on it and "
                   "printed), then exit 2");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line, no progress bar");
      sub.footer(
          "The page needs no network: Chart.js (Debian's libjs-chart.js) and the renders are "
          "inlined.\nSlices and renders need each material's table: the one a result names, or give "
          "it.\nBest result per material: highest min(PSNR, 60 dB) - 20 x median luminance error of the "
          "rendered-image\nmetric; lowest log_rmse when no result has it (docs/accuracy.md).\n"
          "Exit codes: 0 written, 2 bad input (a file missing, unreadable, damaged or of no known "
          "kind: nothing written; with --keep-going the page is written, then exit 2).\n"
          "Examples:\n"
          "  brdfit report fits.h5 -o report.html\n"
          "  brdfit report fits.h5 factor/*.factor.json bench.csv compare.png -o report.html\n"
          "  brdfit report demo-out/ demo-out/factor -o report.html --theta-d 0,20,45,70\n"
          "  brdfit report gold.h5 nbrdf:gold-metallic-paint -o report.html");
      return [o] { return RunReport(*o); };
    }};

// Demo step 90: everything the demo wrote, in one page.
int DemoReport(DemoContext& ctx) {
  ReportCliOptions o;
  for (const auto& p : ctx.outputs) {
    const std::string name = p.filename().string();
    const bool factor = name.size() > 12 && name.ends_with(".factor.json");
    const bool table = std::find(ctx.tables.begin(), ctx.tables.end(), p) != ctx.tables.end();
    const bool fits = p.extension() == ".h5" && !table;  // the fit step's report
    const bool known = factor || fits || p.extension() == ".csv" || p.extension() == ".png";
    if (known) o.inputs.push_back(p.string());
  }
  for (const auto& t : ctx.tables) o.inputs.push_back(t.string());
  o.out = (ctx.out_dir / "report.html").string();
  o.title = "brdfit demo report";
  o.quiet = true;
  const int code = RunReport(o);
  if (code == kExitOk) {
    ctx.outputs.push_back(o.out);
    ctx.report = o.out;
    fmt::print("report: {}\n", fs::absolute(o.out).string());
  }
  return code;
}

DemoStepRegistrar demo_step{90, "report", DemoReport};

}  // namespace
}  // namespace brdfit::cli
