// Whole-command time and peak memory of `brdfit fit` (docs/scale.md): what a user waits for, from
// process start to exit, with the report's stage breakdown (load, prepare, initializer, solve,
// metrics) beside it.
//
//   bench_fit_cli [--repeats 5] [--model lambert+ggx] [--args "--budget full"]
//                 [--brdfit PATH] [--baseline PATH] [--batch 0|1] [--batch-models a,b,..]
//                 [--jobs 2]
//
// Writes, in a scratch folder removed at exit, the six bench tables as users hold them: the
// synthetic Lambert + GGX table of bench_fit (.h5) and five MERL NBRDF proxies tabulated on the
// MERL grid as MERL .binary files (when ../shared/data/merl_nbrdf.zip is present). Each is
// fitted --repeats times by `brdfit fit T --model M -o fits.h5 --force -q ARGS` (one thread);
// the medians of wall time and child peak RSS (wait4 ru_maxrss, as /usr/bin/time -v) are
// printed with the medians of the stage times the report records, the fit's log_rmse and
// rendered PSNR / median luminance error. --batch 1 also times the 100-material batch of the
// issue: `brdfit fit nbrdf:all --model <batch-models> -j <jobs>`, once, with its CPU time and the
// medians of its report's stage times.
// --brdfit PATH times another build (before / after comparisons on the same tables).
// --baseline PATH also times that build, run by run alternately with the measured one (same
// table; baseline first on even repeats, measured first on odd ones, so that neither always
// runs second), and prints their medians and ratios: on a virtual machine whose speed drifts by
// tens of percent over an hour, only runs this close in time compare. With --batch 1 the batch
// runs once per build, baseline first.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bench/bench_tables.h"
#include "bench/child_process.h"
#include "io/fit_report.h"
#include "io/hdf5_table.h"
#include "io/merl.h"
#include "io/nbrdf.h"

namespace {

using namespace brdfit;
namespace fs = std::filesystem;

const fs::path kZip = bench::NbrdfZip();

std::vector<std::string> SplitArgs(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string a;
  while (in >> a) out.push_back(a);
  return out;
}

// The bench tables as files: {label, path}.
std::vector<std::pair<std::string, fs::path>> WriteTables(const fs::path& dir) {
  std::vector<std::pair<std::string, fs::path>> out;
  const fs::path synth = dir / "synthetic-lambert-ggx.h5";
  WriteHdf5Table(bench::SyntheticLambertGgxTable(), synth);
  out.emplace_back("synthetic (h5)", synth);
  if (!fs::exists(kZip)) {
    fmt::print(stderr, "{} not found: the MERL proxies are skipped\n", kZip.string());
    return out;
  }
  for (const std::string& name : bench::kBenchNbrdf) {
    const fs::path p = dir / (name + ".binary");
    WriteMerl(TabulateNbrdf(ReadNbrdf(kZip, name), Grid::Merl(), 1).table, p);
    out.emplace_back(name, p);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5, jobs = 2;
  bool batch = false;
  std::string exe = BRDFIT_EXE, model = "lambert+ggx", extra, baseline;
  std::string batch_models = "lambert+ggx,lambert+cook-torrance,lambert+ggx+ggx,ue4";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--repeats") {
      repeats = std::max(1, std::stoi(v));
    } else if (a == "--model") {
      model = v;
    } else if (a == "--args") {
      extra = v;
    } else if (a == "--brdfit") {
      exe = v;
    } else if (a == "--baseline") {
      baseline = v;
    } else if (a == "--batch") {
      batch = v == "1";
    } else if (a == "--batch-models") {
      batch_models = v;
    } else if (a == "--jobs") {
      jobs = std::max(1, std::stoi(v));
    } else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 2;
    }
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("brdfit-bench-fit-{}", ::getpid());
  fs::create_directories(dir);
  const auto tables = WriteTables(dir);
  const double load_before = bench::LoadAverage();
  fmt::print("brdfit fit T --model {} {} -q (one thread unless --threads is given); medians of {} "
             "runs; {}\n",
             model, extra, repeats, exe);
  fmt::print(
      "| table | wall s | CPU s | peak RSS MB | load ms | prepare ms | init ms | solve ms | "
      "metrics ms (CPU) | log_rmse | PSNR dB | median lum. err. |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int failures = 0;
  struct Times {
    std::vector<double> wall, cpu;
  };
  std::vector<std::tuple<std::string, Times, Times>> compared;  // label, baseline, measured
  // One `brdfit fit` of a table by build `bin`; false (and counted) when it failed.
  auto fit_once = [&](const std::string& bin, const std::string& label, const fs::path& path,
                      bench::ChildRun* run) {
    const fs::path out = dir / "fits.h5";
    std::vector<std::string> args = {"fit", path.string(), "--model", model,
                                     "-o",  out.string(),  "--force", "-q"};
    for (const auto& a : SplitArgs(extra)) args.push_back(a);
    *run = bench::RunChild(bin, args, 600, dir / "fit.log");
    if (run->exit_code == 0) return true;
    fmt::print(stderr, "{}: {} fit exited {} (log {})\n", label, bin, run->exit_code,
               (dir / "fit.log").string());
    ++failures;
    return false;
  };
  for (const auto& [label, path] : tables) {
    std::vector<double> wall, cpu, rss, load, prep, init, solve, metrics, metrics_cpu;
    Times base_times;
    FitMetrics last;
    for (int k = 0; k < repeats; ++k) {
      bench::ChildRun run;
      auto time_baseline = [&] {
        if (baseline.empty()) return true;
        bench::ChildRun b;
        if (!fit_once(baseline, label, path, &b)) return false;
        base_times.wall.push_back(b.seconds);
        base_times.cpu.push_back(b.cpu_seconds);
        return true;
      };
      if (k % 2 == 0 && !time_baseline()) break;
      if (!fit_once(exe, label, path, &run)) break;
      wall.push_back(run.seconds);
      cpu.push_back(run.cpu_seconds);
      rss.push_back(run.peak_rss_mb);
      const std::vector<FitReportEntry> entries = ReadFitReport(dir / "fits.h5");
      const FitResult& r = entries.front().result;
      load.push_back(r.times.load);
      prep.push_back(r.times.prepare);
      init.push_back(r.times.init);
      solve.push_back(r.times.solve);
      metrics.push_back(r.times.metrics);
      metrics_cpu.push_back(r.times.metrics_cpu);
      last = r.metrics;
      // On odd repeats the baseline runs now, once the measured build's report has been read.
      if (k % 2 == 1 && !time_baseline()) break;
    }
    if (wall.empty()) continue;
    if (!baseline.empty()) compared.emplace_back(label, base_times, Times{wall, cpu});
    using bench::Median;
    fmt::print("| {} | {:.3f} | {:.3f} | {:.0f} | {:.0f} | {:.0f} | {:.0f} | {:.0f} | {:.0f} ({:.0f}) "
               "| {:.5f} | {:.2f} | {:.1f} % |\n",
               label, Median(wall), Median(cpu), Median(rss), Median(load), Median(prep),
               Median(init), Median(solve), Median(metrics), Median(metrics_cpu), last.log_rmse,
               last.rendered.psnr_db,
               100 * last.rendered.median_rel_error);
    std::fflush(stdout);
  }
  if (!compared.empty()) {
    using bench::Median;
    fmt::print(
        "\nalternately with the baseline {}:\n"
        "| table | baseline wall s | wall s | ratio | baseline CPU s | CPU s | ratio |\n"
        "|---|---|---|---|---|---|---|\n",
        baseline);
    for (const auto& [label, b, m] : compared) {
      if (b.wall.empty() || m.wall.empty()) continue;
      fmt::print("| {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n", label,
                 Median(b.wall), Median(m.wall), Median(m.wall) / Median(b.wall), Median(b.cpu),
                 Median(m.cpu), Median(m.cpu) / std::max(Median(b.cpu), 1e-9));
    }
  }
  if (batch && fs::exists(kZip)) {
    setenv("BRDFIT_NBRDF_ZIP", kZip.c_str(), 1);
    if (!baseline.empty()) {
      const bench::ChildRun base =
          bench::RunChild(baseline,
                          {"fit", "nbrdf:all", "--model", batch_models, "-j", std::to_string(jobs),
                           "-o", (dir / "batch-baseline.h5").string(), "-q"},
                          3600, dir / "batch-baseline.log");
      fmt::print("\nbatch, baseline {}: {:.1f} s ({:.1f} s CPU), peak RSS {:.0f} MB, exit {}\n",
                 baseline, base.seconds, base.cpu_seconds, base.peak_rss_mb, base.exit_code);
      if (base.exit_code != 0) ++failures;
    }
    const bench::ChildRun run =
        bench::RunChild(exe,
                        {"fit", "nbrdf:all", "--model", batch_models, "-j", std::to_string(jobs),
                         "-o", (dir / "batch.h5").string(), "-q"},
                        3600, dir / "batch.log");
    fmt::print("\nbatch: brdfit fit nbrdf:all --model {} -j {}: {:.1f} s ({:.1f} s CPU), peak RSS "
               "{:.0f} MB, exit {}\n",
               batch_models, jobs, run.seconds, run.cpu_seconds, run.peak_rss_mb, run.exit_code);
    if (run.exit_code != 0) ++failures;
    if (run.exit_code == 0) {
      // The report's stage times: per table (load, prepare: shared by its fits) and per fit.
      std::vector<double> load, prep, init, solve, metrics;
      std::set<std::string> tables;
      for (const FitReportEntry& e : ReadFitReport(dir / "batch.h5")) {
        const FitTimes& t = e.result.times;
        if (tables.insert(e.material).second) {
          load.push_back(t.load);
          prep.push_back(t.prepare);
        }
        init.push_back(t.init);
        solve.push_back(t.solve);
        metrics.push_back(t.metrics_cpu);
      }
      using bench::Median;
      fmt::print("batch stage medians: per table load {:.0f} ms, prepare {:.0f} ms; per fit init "
                 "{:.0f} ms, solve {:.0f} ms, metrics {:.0f} ms CPU ({} tables, {} fits)\n",
                 Median(load), Median(prep), Median(init), Median(solve), Median(metrics),
                 tables.size(), init.size());
    }
  }
  fmt::print("load average: {:.2f} before, {:.2f} after (2 cores)\n", load_before,
             bench::LoadAverage());
  std::error_code ec;
  fs::remove_all(dir, ec);
  return failures == 0 ? 0 : 1;
}
