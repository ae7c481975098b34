// `brdfit bench FILES... --models ... --budgets ... --losses ...`: the run time against error
// benchmark on the user's own tables. Sweeps tables x losses x budgets x models, writes one CSV
// row per fit (report/bench_csv.h) and an HTML page with the Pareto plots (report/html_report.h).
// Also demo step 80 (two demo tables).
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/progress.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "core/metrics.h"
#include "core/result.h"
#include "core/suggest.h"
#include "fit/fitter.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/nbrdf.h"
#include "io/output_policy.h"
#include "pipeline/bench_sweep.h"
#include "pipeline/inputs.h"
#include "pipeline/material_keys.h"
#include "pipeline/shard.h"
#include "report/bench_csv.h"
#include "report/html_report.h"
#include "report/report_inputs.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct BenchCliOptions {
  std::vector<std::string> files;
  std::vector<std::string> models = {"lambert+ggx"};
  std::vector<std::string> budgets = {"full", "stride:4", "stride:16"};
  std::vector<std::string> losses = {"log"};
  std::string out = "bench.csv";
  std::string plot;  // default: the CSV's name with .html
  double cutoff_deg = SampleOptions{}.cutoff_deg;
  int repeat = 1;
  int threads = 1;
  std::string polish = "none";  // the sweep's fits stop at the table's loss unless asked
  std::string shard;  // "I/N" (pipeline/shard.h); empty: every table
  bool no_timings = false;
  bool quiet = false;
};

struct BenchInput {
  std::string file;
  std::string material;  // pipeline/material_keys.h
};

// The tables this run sweeps, by material key (the CSV's order): every input, or the shard's
// whole tables (one unit per table: with fewer tables than shards some shards have none).
std::vector<BenchInput> RunInputs(const std::vector<std::string>& files, const std::string& shard) {
  const std::vector<std::string> keys = pipeline::MaterialKeys(files);
  const pipeline::Shard s = shard.empty() ? pipeline::Shard{} : pipeline::ParseShard(shard);
  const std::vector<bool> in = pipeline::ShardMembership(keys, {{"bench", ""}}, s);
  std::vector<BenchInput> out;
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (in[f]) out.push_back({files[f], keys[f]});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.material < b.material; });
  return out;
}

struct Plan {
  std::vector<Budget> budgets;
  std::vector<LossKind> losses;
  PolishKind polish = PolishKind::kNone;
};

// Everything that can be checked before the first fit.
Plan CheckOptions(const BenchCliOptions& o) {
  Plan p;
  p.polish = FromString<PolishKind>(o.polish);
  if (o.models.empty() || o.budgets.empty() || o.losses.empty()) {
    throw InputError("--models, --budgets and --losses each need at least one value");
  }
  for (const auto& m : o.models) {
    if (!IsFittable(m)) {
      std::string names;
      for (const auto& n : FittableModels()) names += (names.empty() ? "" : ", ") + n;
      throw InputError("unknown model '" + m + "'" + SuggestionAfter(m, FittableModels()) +
                       "; fittable models: " + names);
    }
  }
  for (const auto& b : o.budgets) p.budgets.push_back(Budget::Parse(b));
  for (const auto& l : o.losses) p.losses.push_back(LossKindFromString(l));
  if (o.repeat < 1 || o.repeat > 100) throw InputError("--repeat must be in [1, 100]");
  if (o.threads < 1 || o.threads > 256) throw InputError("--threads must be in [1, 256]");
  if (!(o.cutoff_deg > 0 && o.cutoff_deg <= 90)) {
    throw InputError(fmt::format("--cutoff {} outside (0, 90]", o.cutoff_deg));
  }
  for (const auto& f : o.files) {
    if (!IsNbrdfInput(f)) CheckInputFile(f);
  }
  return p;
}

fs::path PlotPath(const BenchCliOptions& o) {
  if (!o.plot.empty()) return o.plot;
  fs::path p = o.out;
  return p.replace_extension(".html");
}

int RunBench(BenchCliOptions o, std::vector<fs::path>* written = nullptr) {
  o.files = pipeline::ExpandInputs(o.files);
  const std::vector<BenchInput> inputs = RunInputs(o.files, o.shard);
  const Plan plan = CheckOptions(o);
  CheckOutputs(pipeline::InputFiles(o.files),
               {{o.out, "-o"}, {PlotPath(o), o.plot.empty() ? "the plot (-o as .html)" : "--plot"}});
  const std::string chart_js = report::ReadChartJs();  // fail before any fit
  const std::size_t fits_per_table = plan.budgets.size() * plan.losses.size() * o.models.size();
  Progress bar(inputs.size() * fits_per_table, "bench", !o.quiet);
  std::vector<report::BenchPoint> points;
  int code = kExitOk;
  FitOptions fo;
  fo.threads = o.threads;
  fo.polish = plan.polish;
  if (!o.quiet) {
    std::string errors;
    for (const ErrorMetricField& f : kErrorMetrics) errors += fmt::format(" {:>10}", f.name);
    fmt::print("{:<24} {:<16} {:<5} {:<11} {:<14} {:>10}{} {:>9} {:>8} {:>8}\n", "table", "model",
               "loss", "budget", "status", "time ms", errors, "cells", "psnr_dB", "med_lum");
  }
  pipeline::BenchConfig config;
  config.models = o.models;
  config.budgets = plan.budgets;
  config.losses = plan.losses;
  config.samples.cutoff_deg = o.cutoff_deg;
  config.fit = fo;
  config.repeats = o.repeat;
  pipeline::BenchCallbacks callbacks;
  callbacks.on_start = [&](const std::string& label) { bar.Step(label); };
  callbacks.on_point = [&](const report::BenchPoint& b) {
    if (b.status == ToString(FitStatus::kFailed)) code = kExitFitFailed;
    bar.Clear();
    if (!o.quiet) {
      const RenderedError& re = b.metrics.rendered;
      std::string errors;
      for (const ErrorMetricField& f : kErrorMetrics) {
        errors += fmt::format(" {:>10.4g}", b.metrics.*f.value);
      }
      fmt::print("{:<24} {:<16} {:<5} {:<11} {:<14} {:>10.1f}{} {:>9} {:>8} {:>8}\n",
                 TerminalSafe(b.material), b.model, b.loss, b.budget, b.status, b.time_ms, errors,
                 b.fit_cells, re.ok ? fmt::format("{:.2f}", re.psnr_db) : "-",
                 re.ok ? fmt::format("{:.1f}%", 100 * re.median_rel_error) : "-");
    }
  };
  for (const BenchInput& in : inputs) {
    const pipeline::BenchTable table{in.material, in.file, pipeline::LoadInput(in.file)};
    const auto rows = pipeline::RunBenchSweep(table, config, callbacks);
    points.insert(points.end(), rows.begin(), rows.end());
  }
  bar.Done();
  if (o.no_timings) {
    for (report::BenchPoint& b : points) b.time_ms = b.prepare_ms = b.init_ms = b.solve_ms = 0;
  }
  report::WriteBenchCsv(o.out, points);
  report::Report r;
  r.title = "brdfit bench: run time against error";
  r.metric_definition = MetricsDefinition();
  r.bench = points;
  for (const BenchInput& in : inputs) r.inputs.push_back(in.file);
  r.notes.push_back(fmt::format(
      "Time: preparing the samples of the budget + initializer + Levenberg-Marquardt, median of "
      "{} run{} per fit, {} Ceres thread{}; loading the table is not counted.",
      o.repeat, o.repeat == 1 ? "" : "s", o.threads, o.threads == 1 ? "" : "s"));
  const fs::path plot = PlotPath(o);
  WriteTextAtomically(plot, report::RenderHtml(r, chart_js));
  if (written) {
    written->push_back(o.out);
    written->push_back(plot);
  }
  if (!o.quiet) fmt::print("wrote {} and {}\n", o.out, plot.string());
  return code;
}

Registrar reg{
    "bench", "Run time against error: sweep models x sample budgets x losses on your tables",
    [](CLI::App& sub) {
      auto o = std::make_shared<BenchCliOptions>();
      sub.add_option("files", o->files,
                     "tables (MERL .binary or brdfit .h5), nbrdf:NAME or nbrdf:all")
          ->required();
      sub.add_option("--models", o->models, "models to fit, comma-separated (brdfit models)")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_option("--budgets", o->budgets,
                     "sample budgets: full, stride:K (every K-th phi_d bin), random:N")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_option("--losses", o->losses, "losses: log, cbrt, rel, l2")
          ->delimiter(',')
          ->capture_default_str();
      sub.add_option("-o,--out", o->out, "CSV file, one row per fit")->capture_default_str();
      sub.add_option("--plot", o->plot,
                     "HTML page with the Pareto plots (default: CSV name .html)");
      sub.add_option("--cutoff", o->cutoff_deg, "angle cut-off of fits and metrics (degrees)")
          ->capture_default_str();
      sub.add_option("--repeat", o->repeat, "runs per fit; times are medians")
          ->capture_default_str();
      sub.add_option("--threads", o->threads, "Ceres threads per fit")->capture_default_str();
      sub.add_option("--polish", o->polish,
                     "none | rendered: end each fit with the rendered polish, as brdfit fit "
                     "does (its time is in solve_ms)")
          ->capture_default_str();
      sub.add_option("--shard", o->shard,
                     "I/N: sweep only the I-th of N slices of the tables (whole tables, "
                     "docs/scale.md); join the CSVs with brdfit merge");
      sub.add_flag("--no-timings", o->no_timings,
                   "write the times as 0 (byte-identical reruns and merges of the CSV)");
      sub.add_flag("-q,--quiet", o->quiet, "no table on stdout, no progress bar");
      sub.footer(
          "Every fit's metrics are computed on all valid cells inside the cut-off, whatever its "
          "budget,\nso rows are comparable. Open the HTML page in a browser (no network "
          "needed); docs/cli.md lists\nthe CSV columns.\n"
          "Exit codes: 0 ok, 1 some fit failed (its row says why), 2 bad input.\n"
          "Examples:\n"
          "  brdfit bench mats/*.binary --models lambert+ggx,lambert+beckmann -o bench.csv\n"
          "  brdfit bench gold.binary --budgets full,stride:8,stride:32,random:20000 \\\n"
          "      --losses log,cbrt --repeat 5 -o gold-bench.csv --plot gold-bench.html\n"
          "  brdfit bench nbrdf:all --models lambert+ggx --shard 1/4 -o bench-1.csv");
      return [o] { return RunBench(*o); };
    }};

// Demo step 80: the sweep on the first two demo tables.
int DemoBench(DemoContext& ctx) {
  if (ctx.tables.empty()) {
    fmt::print("bench: no demo table (the synth step wrote none)\n");
    return kExitOk;
  }
  BenchCliOptions o;
  for (std::size_t i = 0; i < ctx.tables.size() && i < 2; ++i) {
    o.files.push_back(ctx.tables[i].string());
  }
  o.models = {"lambert+ggx", "lambert+beckmann"};
  o.budgets = ctx.quick ? std::vector<std::string>{"full", "stride:4"}
                        : std::vector<std::string>{"full", "stride:8", "stride:32"};
  o.out = (ctx.out_dir / "bench.csv").string();
  o.plot = (ctx.out_dir / "bench.html").string();
  return RunBench(o, &ctx.outputs);
}

DemoStepRegistrar demo_step{80, "bench (run time against error)", DemoBench};

}  // namespace
}  // namespace brdfit::cli
