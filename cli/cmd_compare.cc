// `brdfit compare OLD NEW`: per material and approximation, the metric deltas between two sets
// of results (fit reports, factorizations, bench CSVs, or folders of them), a summary, and an
// exit code that gates CI: 1 when anything regressed beyond the threshold (report/compare.h).
#include <fmt/core.h>

#include <filesystem>
#include <string>

#include "cli/command.h"
#include "report/compare.h"
#include "core/error.h"
#include "report/report_inputs.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct CompareCliOptions {
  std::string old_path, new_path;
  std::string metric = kErrorMetrics[kPrimaryErrorMetric].name;
  report::CompareOptions options;
  bool ignore_missing = false;
  bool ignore_rendered = false;
  bool all = false;
  bool json = false;
};

report::Report Load(const std::string& path) {
  report::ReportSources s = report::ReadReportInputs({fs::path(path)});
  report::AddBenchEntries(&s.report);
  return std::move(s.report);
}

int RunCompare(CompareCliOptions o) {
  o.options.metric = report::ErrorMetricIndex(o.metric);
  o.options.missing_is_regression = !o.ignore_missing;
  o.options.judge_rendered = !o.ignore_rendered;
  if (!(o.options.threshold >= 0) || !(o.options.abs_floor >= 0) ||
      !(o.options.time_threshold >= 0) || !(o.options.psnr_drop_db >= 0) ||
      !(o.options.lum_rise_points >= 0)) {
    throw InputError(
        "--threshold, --abs-floor, --time-threshold, --psnr-threshold and --lum-threshold must "
        "be >= 0");
  }
  const report::Report a = Load(o.old_path), b = Load(o.new_path);
  auto entries = [](const report::Report& r) {
    std::size_t n = 0;
    for (const auto& m : r.materials) n += m.entries.size();
    return n;
  };
  if (entries(a) == 0) throw InputError(o.old_path, "holds no results to compare");
  if (entries(b) == 0) throw InputError(o.new_path, "holds no results to compare");
  const report::Comparison c = report::Compare(a, b, o.options);
  if (o.json) {
    auto j = report::ComparisonToJson(c);
    j["old"] = o.old_path;
    j["new"] = o.new_path;
    fmt::print("{}\n", j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace));
  } else {
    fmt::print("old {}\nnew {}\n\n{}", o.old_path, o.new_path, report::FormatComparison(c, o.all));
  }
  return c.Regressed() ? kExitFitFailed : kExitOk;
}

Registrar reg{
    "compare", "Metric deltas between two sets of results; non-zero exit on regressions",
    [](CLI::App& sub) {
      auto o = std::make_shared<CompareCliOptions>();
      sub.add_option("old", o->old_path,
                     "baseline: fit report, .factor.json, bench .csv, or a folder of them")
          ->required();
      sub.add_option("new", o->new_path, "results to judge, same kinds")->required();
      sub.add_option("--metric", o->metric, "deciding metric: " + ErrorMetricNames(" | "))
          ->capture_default_str();
      sub.add_option("--threshold", o->options.threshold,
                     "relative increase of the metric counted as a regression (0.05 = 5 %)")
          ->capture_default_str();
      sub.add_option("--abs-floor", o->options.abs_floor,
                     "ignore increases smaller than this in absolute terms")
          ->capture_default_str();
      sub.add_option("--time-threshold", o->options.time_threshold,
                     "also fail when time grows by more than this fraction (0: ignore time)")
          ->capture_default_str();
      sub.add_option("--psnr-threshold", o->options.psnr_drop_db,
                     "rendered PSNR drop (dB) counted as a regression")
          ->capture_default_str();
      sub.add_option("--lum-threshold", o->options.lum_rise_points,
                     "rise of the median relative luminance error (percentage points) counted as "
                     "a regression")
          ->capture_default_str();
      sub.add_flag("--ignore-rendered", o->ignore_rendered,
                   "do not judge the rendered-image metric (PSNR, luminance error)");
      sub.add_flag("--ignore-missing", o->ignore_missing,
                   "results present in OLD but absent from NEW are not regressions");
      sub.add_flag("--all", o->all, "list unchanged results too");
      sub.add_flag("--json", o->json, "machine-readable output");
      sub.footer(
          "Results are matched by material (table stem) and by model, loss and budget.\n"
          "Where both have the rendered-image metric (docs/accuracy.md), a PSNR drop beyond\n"
          "--psnr-threshold or a luminance error rise beyond --lum-threshold is a regression too.\n"
          "Exit codes: 0 no regression, 1 at least one regression (named in the output), "
          "2 bad input.\n"
          "Examples:\n"
          "  brdfit compare baseline/fits.h5 fits.h5\n"
          "  brdfit compare old-bench.csv new-bench.csv --metric rel_l2 --threshold 0.02\n"
          "  brdfit compare main-results/ pr-results/ --json > delta.json");
      return [o] { return RunCompare(*o); };
    }};

}  // namespace
}  // namespace brdfit::cli
