// Whole-command time of `brdfit report` and `brdfit compare` on one material with many fits
// (docs/reliability.md: both must grow no faster than linearly with the fits of a material).
//
//   bench_report_cli [--fits 300,600,3000] [--repeats 3] [--timeout 120] [--brdfit PATH]
//                    [--keep DIR]   (write the inputs into DIR and keep them, for profiling)
//
// Writes, in a scratch folder removed at exit, a lambert+ggx table on the MERL grid and, per
// size N, a fit report of N fits of that table (three models in turn, options that differ only
// in max_iterations: N/3 fits share each model | loss | budget key, the case that made the
// report number its duplicates quadratically) and a second report with 10 % of the metrics
// 3 % worse. Then runs `brdfit report FITS -o r.html -q` (slices and renders from the table) and
// `brdfit compare OLD NEW`, each --repeats times, and prints the median wall times. A run over
// --timeout seconds is killed and shown as "> T".
#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_tables.h"
#include "bench/child_process.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "models/registry.h"

namespace {

using namespace brdfit;
namespace fs = std::filesystem;

std::vector<FitReportEntry> ManyFits(const fs::path& table, int n, double worse) {
  const char* models[] = {"lambert+ggx", "lambert+beckmann", "lambert+ward"};
  std::vector<FitReportEntry> out;
  for (int i = 0; i < n; ++i) {
    const ModelInfo* m = FindModel(models[i % 3]);
    FitReportEntry e;
    e.source = table.string();
    e.material = "t";
    e.options = fmt::format(
        R"({{"budget":"full","cosine":true,"cutoff_deg":80,"loss":"log","max_iterations":{},)"
        R"("robust":"none","weighting":"bin-measure"}})",
        100 + i);
    e.chosen = i == 0;
    if (e.chosen) e.choice = "bench";
    FitResult& r = e.result;
    r.model = m->name;
    r.param_names = m->param_names;
    r.params = m->DefaultParams();
    r.at_bound.assign(r.params.size(), false);
    r.status = FitStatus::kConverged;
    r.iterations = 10 + i % 7;
    r.starts = 1;
    const double bad = (worse > 0 && i % 10 == 0) ? 1 + worse : 1;
    FitMetrics& x = r.metrics;
    x.ok = true;
    x.log_rmse = 0.01 * (1 + (i % 97) / 100.0) * bad;
    x.cbrt_rmse = 2 * x.log_rmse;
    x.rel_l2 = 3 * x.log_rmse;
    x.cells = 1000;
    x.total_weight = 1;
    x.weighting = "bin-measure";
    x.cutoff_deg = 80;
    RenderedError& re = x.rendered;
    re.ok = true;
    re.psnr_db = 30 - (i % 89) / 10.0;
    re.psnr_srgb_db = re.psnr_db;
    re.median_rel_error = 0.1 * (1 + (i % 83) / 100.0) * bad;
    re.p95_rel_error = 2 * re.median_rel_error;
    re.resolution = 128;
    re.num_lights = 2;
    re.lights[0].light_deg = 45;
    re.lights[1].light_deg = 80;
    r.times.prepare = 5;
    r.times.init = 10;
    r.times.solve = 100 + i % 50;
    out.push_back(std::move(e));
  }
  return out;
}

// Seconds of one run, or a negative number if it exceeded the timeout (killed) or failed.
double TimeRun(const std::string& exe, const std::vector<std::string>& args, double timeout_s,
               const fs::path& log) {
  const bench::ChildRun run = bench::RunChild(exe, args, timeout_s, log);
  if (run.timed_out) return -1;
  // compare exits 1 on the planted regressions: only a crash or exit 2 is a failure.
  if (run.exit_code > 1) {
    fmt::print(stderr, "{} failed (exit {}); log {}\n", args[0], run.exit_code, log.string());
    return -2;
  }
  return run.seconds;
}

std::string Median(std::vector<double> t, double timeout_s) {
  if (std::any_of(t.begin(), t.end(), [](double x) { return x == -2; })) return "failed";
  if (std::any_of(t.begin(), t.end(), [](double x) { return x < 0; })) {
    return fmt::format("> {:g}", timeout_s);
  }
  std::sort(t.begin(), t.end());
  return fmt::format("{:.2f}", t[t.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {300, 600, 3000};
  int repeats = 3;
  double timeout_s = 120;
  std::string exe = BRDFIT_EXE;
  std::string keep;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--fits") {
      sizes.clear();
      for (const auto& s : bench::SplitList(v)) sizes.push_back(std::stoi(s));
    } else if (a == "--repeats") {
      repeats = std::max(1, std::stoi(v));
    } else if (a == "--timeout") {
      timeout_s = std::stod(v);
    } else if (a == "--brdfit") {
      exe = v;
    } else if (a == "--keep") {
      keep = v;
    } else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 2;
    }
  }
  const fs::path dir = keep.empty() ? fs::temp_directory_path() /
                                         fmt::format("brdfit-bench-report-{}", ::getpid())
                                   : fs::path(keep);
  fs::create_directories(dir);
  const fs::path table = dir / "t.h5";
  WriteHdf5Table(bench::SyntheticLambertGgxTable(), table);
  fmt::print("brdfit report / compare, one material (MERL-grid table), medians of {} runs (s)\n",
             repeats);
  fmt::print("| fits | report | compare |\n|---|---|---|\n");
  for (const int n : sizes) {
    const fs::path old_h5 = dir / fmt::format("old-{}.h5", n), new_h5 = dir / fmt::format("new-{}.h5", n);
    WriteFitReport(ManyFits(table, n, 0), old_h5);
    WriteFitReport(ManyFits(table, n, 0.03), new_h5);
    std::vector<double> report, compare;
    for (int k = 0; k < repeats; ++k) {
      report.push_back(TimeRun(exe, {"report", old_h5.string(), "-q", "-o", (dir / "r.html").string()},
                               timeout_s, dir / "report.log"));
      compare.push_back(TimeRun(exe, {"compare", old_h5.string(), new_h5.string()}, timeout_s,
                                dir / "compare.log"));
    }
    fmt::print("| {} | {} | {} |\n", n, Median(report, timeout_s), Median(compare, timeout_s));
    std::fflush(stdout);
  }
  std::error_code ec;
  if (keep.empty()) fs::remove_all(dir, ec);
  return 0;
}
