// `brdfit fit FILES... --model ggx,beckmann,...`: fits models to tables, prints a metric table,
// writes every fit to an HDF5 report (docs/formats.md, "Fit reports") and optionally the
// parameters as JSON. The batch (parallel, resumable, checkpointed) is pipeline/batch_fit.h;
// this file parses the options and prints. Also demo step 20.
#include <fmt/core.h>

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/interrupt.h"
#include "cli/progress.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "core/model_choice.h"
#include "core/rendered_regions.h"
#include "export/fit_targets.h"
#include "io/atomic_file.h"
#include "io/file_lock.h"
#include "io/fit_report.h"
#include "io/input_file.h"
#include "io/nbrdf.h"
#include "io/output_policy.h"
#include "pipeline/batch_fit.h"
#include "pipeline/fit_settings.h"
#include "pipeline/inputs.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct FitCliOptions {
  std::vector<std::string> files;
  std::vector<std::string> models = {"auto"};
  bool models_given = false;  // --model on the command line
  std::string target;         // --target (export/fit_targets.h)
  std::string diffuse = "lambert";
  pipeline::FitSettings fit;  // --loss ... --threads (pipeline/fit_settings.h)
  int jobs = 1;
  std::string shard;  // "I/N" (pipeline/shard.h); empty: the whole batch
  bool force = false;
  std::string out = "fits.h5";
  std::string json;
  bool no_timings = false;
  bool quiet = false;
  bool no_progress = false;
};

// The loss an entry was fitted under, from its options JSON ("?" if it says none).
std::string LossOf(const FitReportEntry& e) {
  const std::string key = "\"loss\":\"";
  const auto at = e.options.find(key);
  if (at == std::string::npos) return "?";
  const auto end = e.options.find('"', at + key.size());
  return end == std::string::npos ? "?" : e.options.substr(at + key.size(), end - at - key.size());
}

void PrintTable(std::FILE* out, const std::vector<FitReportEntry>& entries) {
  fmt::print(out, "  {:<28} {:<26} {:<8} {:>6} {:>7} {:>7} {:>22} {:>9} {:>5} {:>9} {}\n",
             "material", "model", "loss", "S_dB", "psnr_dB", "med_lum", "front/side/rim/env_dB",
             "log_rmse", "iter", "solve_ms", "status");
  bool any_chosen = false;
  for (const FitReportEntry& e : entries) {
    const FitResult& r = e.result;
    const RenderedError& re = r.metrics.rendered;
    const std::string score = re.ok ? fmt::format("{:.1f}", RenderedScoreDb(re)) : "-";
    const std::string psnr = re.ok ? fmt::format("{:.1f}", re.psnr_db) : "-";
    const std::string lum = re.ok ? fmt::format("{:.1f}%", 100 * re.median_rel_error) : "-";
    std::string regions;
    for (const RegionError& g : RenderedRegions(re)) {
      if (!regions.empty()) regions += '/';
      regions += g.lights > 0 ? fmt::format("{:.1f}", g.psnr_db) : std::string("-");
    }
    any_chosen = any_chosen || e.chosen;
    fmt::print(out, "{} {:<28} {:<26} {:<8} {:>6} {:>7} {:>7} {:>22} {:>9.5f} {:>5} {:>9.1f} {}\n",
               e.chosen ? "*" : " ", TerminalSafe(e.material), r.model, LossOf(e), score, psnr, lum,
               re.ok ? regions : "-", r.metrics.log_rmse, r.iterations,
               r.times.init + r.times.solve, ToString(r.status));
    if (!r.message.empty()) fmt::print(out, "    {}\n", TerminalSafe(r.message));
    if (e.factorization) {
      fmt::print(out, "    textures: {} ({:.1f} KiB)\n", TerminalSafe(e.factorization->sidecar),
                 e.factorization->texture_bytes / 1024.0);
    }
    if (e.chosen) fmt::print(out, "    chosen: {}\n", TerminalSafe(e.choice));
  }
  if (any_chosen) {
    fmt::print(out,
               "* the fit chosen for its table by rendered error S over front, side and rim "
               "light and an environment (docs/accuracy.md)\n");
  }
}

double MedianOf(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Per (model, loss) over the tables: mean and median rendered PSNR, median of the median
// luminance errors, mean and median log_rmse, median init + solve time, failures; how often
// the run's fits of that kind were chosen.
void PrintSummary(std::FILE* out, const std::vector<FitReportEntry>& entries) {
  std::vector<std::pair<std::string, std::string>> kinds;
  for (const FitReportEntry& e : entries) {
    const std::pair<std::string, std::string> k{e.result.model, LossOf(e)};
    if (std::find(kinds.begin(), kinds.end(), k) == kinds.end()) kinds.push_back(k);
  }
  fmt::print(out, "\n{:<26} {:<8} {:>5} {:>15} {:>8} {:>19} {:>9} {:>6} {:>6}\n",
             "model (over tables)", "loss", "fits", "psnr_dB mean/med", "med_lum",
             "log_rmse mean/med", "solve_ms", "chosen", "failed");
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
  };
  for (const auto& [model, loss] : kinds) {
    std::vector<double> l, p, lum, t;
    int failed = 0, fits = 0, chosen = 0;
    for (const FitReportEntry& e : entries) {
      if (e.result.model != model || LossOf(e) != loss) continue;
      ++fits;
      chosen += e.chosen;
      if (e.result.Failed()) {
        ++failed;
        continue;
      }
      l.push_back(e.result.metrics.log_rmse);
      t.push_back(e.result.times.init + e.result.times.solve);
      if (e.result.metrics.rendered.ok) {
        p.push_back(e.result.metrics.rendered.psnr_db);
        lum.push_back(e.result.metrics.rendered.median_rel_error);
      }
    }
    const std::string psnr = p.empty() ? "-" : fmt::format("{:.2f}/{:.2f}", mean(p), MedianOf(p));
    const std::string med = lum.empty() ? "-" : fmt::format("{:.1f}%", 100 * MedianOf(lum));
    fmt::print(out, "{:<26} {:<8} {:>5} {:>15} {:>8} {:>9.5f}/{:<9.5f} {:>9.1f} {:>6} {:>6}\n",
               model, loss, fits, psnr, med, mean(l), MedianOf(l), MedianOf(t), chosen, failed);
  }
}

// What the interrupt hook needs of a running fit (shared: the hook may outlive RunFit's frame).
struct RunState {
  std::mutex bar_mu;  // guards bar
  std::unique_ptr<Progress> bar;
  std::atomic<std::size_t> on_disk{0};  // entries of the report on disk
  std::atomic<unsigned> writes{0};      // report writes so far
};

struct HookReset {
  ~HookReset() { SetInterruptHook(nullptr); }
};

// SIGINT/SIGTERM/SIGHUP during a fit (cli/interrupt.h): the temporaries are gone already.
void OnInterrupt(RunState& st, const std::string& report, int sig, int drained) {
  using namespace std::chrono_literals;
  // A checkpoint that was being written has been renamed into place; wait for its count.
  const unsigned writes = st.writes;
  for (int i = 0; drained > 0 && st.writes == writes && i < 100; ++i) {
    std::this_thread::sleep_for(10ms);
  }
  {
    std::lock_guard<std::mutex> lock(st.bar_mu);
    if (st.bar) st.bar->Done();  // closes the progress line
  }
  const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
  fmt::print(stderr, "brdfit: interrupted: {} fits kept, rerun to resume (report {}; {})\n",
             st.on_disk.load(), report, name);
}

// --target: for each fit, whether its export to the target is exact, else what it approximates
// (the exporters' own check, export/fit_targets.h).
void PrintTargetFidelity(std::FILE* out, const exports::FitTarget& t,
                         const std::vector<FitReportEntry>& fits) {
  for (const FitReportEntry& e : fits) {
    if (e.result.Failed()) continue;
    if (e.factorization) {
      fmt::print(
          out, "target {}: {} factorization: {}\n", t.name, e.material,
          t.format == exports::Format::kThreejs
              ? "exact export (brdfit export " + e.factorization->sidecar + " --format threejs)"
              : std::string("not exported to this target (textures: three.js only)"));
      continue;
    }
    const exports::Fidelity f = exports::ExportFidelity(e.result, t);
    std::string what;
    for (const std::string& a : f.approximations) what += (what.empty() ? "" : "; ") + a;
    fmt::print(out, "target {}: {} {}: {}\n", t.name, e.material, e.result.model,
               f.Exact() ? "exact export (brdfit export --format " +
                               std::string(exports::FormatName(t.format)) + ")"
                         : "approximate export: " + what);
  }
}

int RunFit(const FitCliOptions& o) {
  pipeline::BatchFitRequest req;
  req.inputs = pipeline::ExpandInputs(o.files);
  if (req.inputs.empty()) throw InputError("no input files");
  if (o.jobs < 1 || o.jobs > 256) throw InputError("--jobs must be in [1, 256]");
  pipeline::ApplyFitSettings(o.fit, &req.samples, &req.fit);
  const exports::FitTarget* target = o.target.empty() ? nullptr : &exports::FitTargetOf(o.target);
  const std::vector<std::string> models =
      target && !o.models_given && !target->models.empty() ? target->models : o.models;
  req.models = pipeline::ResolveModelRuns(models, o.diffuse, !o.fit.loss.empty());
  req.report = o.out;
  req.force = o.force;
  req.timings = !o.no_timings;
  req.jobs = o.jobs;
  if (!o.shard.empty()) req.shard = pipeline::ParseShard(o.shard);
  const std::size_t num_inputs = req.inputs.size();

  // Before any work: every input file is there (a missing one is exit 2 with no report
  // written), the outputs pass the output policy, and the report is ours.
  for (const std::string& f : req.inputs) {
    if (!IsNbrdfInput(f)) CheckInputFile(f);
  }
  // The report's lock file is written too (its pid): never onto an input.
  CheckOutputs(
      pipeline::InputFiles(req.inputs),
      {{o.out, "-o"}, {o.json, "--json"}, {LockPathFor(o.out).string(), "the report's lock"}});
  // The hook first: a signal that arrives while the lock is being taken still gets the fit's
  // message (make test-asan: SIGINT right after the lock file appeared found no hook).
  const auto state = std::make_shared<RunState>();
  req.on_report_written = [state](std::size_t entries) {
    state->on_disk = entries;
    ++state->writes;
  };
  SetInterruptHook(
      [state, report = o.out](int sig, int drained) { OnInterrupt(*state, report, sig, drained); });
  const HookReset reset_hook;
  const OutputLock report_lock(o.out);
  // In a job log, one line per finished fit (cli/progress.h).
  req.on_fit_done = [&](const FitReportEntry& e) {
    std::lock_guard<std::mutex> lock(state->bar_mu);
    if (state->bar) {
      state->bar->Finish(e.source + " " + e.result.model + " " + LossOf(e),
                         ToString(e.result.status));
    }
  };

  // The progress bar counts the fits still to make: the report may already hold some.
  const auto run = pipeline::RunBatchFit(req, [&](std::size_t planned, const std::string& label) {
    std::lock_guard<std::mutex> lock(state->bar_mu);
    if (!state->bar) {
      state->bar = std::make_unique<Progress>(planned, "fitting", !o.no_progress && !o.quiet);
      state->bar->CountFinishes();  // parallel fits end out of order: req.on_fit_done
    }
    state->bar->Step(label);
  });
  {
    std::lock_guard<std::mutex> lock(state->bar_mu);
    if (state->bar) state->bar->Done();
  }

  // `--json -`: the parameters are the standard output; the table goes to stderr.
  const bool json_to_stdout = o.json == "-";
  if (json_to_stdout) {
    fmt::print("{}", FitParamsJson(run.all, !o.no_timings));
  } else if (!o.json.empty() && !(run.all.empty() && !run.input_errors.empty())) {
    WriteTextAtomically(o.json, FitParamsJson(run.all, !o.no_timings));
  }

  if (!o.quiet) {
    for (const auto& c : run.changed_sources) {
      fmt::print(stderr, "brdfit: note: {}\n", TerminalSafe(c));
    }
    std::FILE* table_out = json_to_stdout ? stderr : stdout;
    if (!run.fresh.empty()) PrintTable(table_out, run.fresh);
    if (num_inputs > 1 && !run.fresh.empty()) PrintSummary(table_out, run.fresh);
    if (!req.shard.Whole()) {
      fmt::print(table_out,
                 "shard {}/{}: {} of {} fits of the batch (merge the shards' "
                 "reports with brdfit merge)\n",
                 req.shard.index, req.shard.count, run.skipped + run.planned,
                 run.skipped + run.planned + run.other_shards);
    }
    // Nothing fitted and no report before (every input unreadable): no file is named.
    std::error_code ec;
    const bool written = fs::exists(o.out, ec);
    const bool json_written = !o.json.empty() && !json_to_stdout && fs::exists(o.json, ec);
    fmt::print(table_out, "{} fits, {} skipped{}; {}{}\n", run.fresh.size(), run.skipped,
               run.skipped ? " (already in the report with the same options; --force redoes "
                             "them)"
                           : "",
               written ? "report " + o.out : std::string("no report written"),
               json_written ? ", parameters " + o.json : "");
  }
  if (target && !o.quiet) PrintTargetFidelity(json_to_stdout ? stderr : stdout, *target, run.fresh);
  for (const auto& e : run.input_errors) fmt::print(stderr, "brdfit: error: {}\n", TerminalSafe(e));
  if (!run.input_errors.empty()) return kExitBadInput;
  const bool failed = std::any_of(run.fresh.begin(), run.fresh.end(),
                                  [](const FitReportEntry& e) { return e.result.Failed(); });
  // -q keeps a success silent, not a failure: each failed fit is named on stderr (the table,
  // which names them otherwise, is not printed).
  if (o.quiet) {
    for (const FitReportEntry& e : run.fresh) {
      if (e.result.Failed()) {
        fmt::print(stderr, "brdfit: error: {} {}: fit failed: {}\n", TerminalSafe(e.source),
                   e.result.model,
                   TerminalSafe(e.result.message.empty() ? "(no message)" : e.result.message));
      }
    }
  }
  return failed ? kExitFitFailed : kExitOk;
}

// Demo step 20: fit the synthesized tables with the main models, report into the demo folder.
int DemoFit(DemoContext& ctx) {
  FitCliOptions o;
  for (const auto& t : ctx.tables) o.files.push_back(t.string());
  o.models = ctx.quick ? std::vector<std::string>{"ggx", "beckmann"}
                       : std::vector<std::string>{"ggx",         "beckmann",      "ward",
                                                  "blinn-phong", "cook-torrance", "lafortune"};
  o.jobs = 2;
  o.force = true;
  o.no_progress = true;
  o.out = (ctx.out_dir / "fits.h5").string();
  o.json = (ctx.out_dir / "fits.json").string();
  const int code = RunFit(o);
  ctx.outputs.push_back(o.out);
  ctx.outputs.push_back(o.json);
  return code;
}

Registrar reg{
    "fit", "Fit analytic models to tables; metrics, times and an HDF5 report", [](CLI::App& sub) {
      auto o = std::make_shared<FitCliOptions>();
      sub.add_option("files", o->files,
                     "tables (MERL .binary or brdfit .h5); nbrdf:NAME or nbrdf:all tabulates the "
                     "NBRDF networks of ../shared/data/merl_nbrdf.zip on the MERL grid")
          ->required();
      CLI::Option* model_opt =
          sub.add_option(
                 "-m,--model", o->models,
                 "models, comma-separated (brdfit models lists them); NAME:N for N lobes, "
                 "e.g. lafortune:2, ggx:2; auto: fit the candidates of docs/accuracy.md and "
                 "mark the one chosen by rendered error; factorization: also factor each "
                 "table as brdfit factor does (textures in REPORT.factors/), a candidate of "
                 "the choice with its texture values as parameters")
              ->delimiter(',')
              ->capture_default_str();
      sub.add_option("--diffuse", o->diffuse,
                     "diffuse lobe added to bare specular names (lambert, oren-nayar, burley, "
                     "oren-nayar-fujii, burley-2012): "
                     "ggx -> lambert+ggx; a name without that sum in the catalog is refused "
                     "(none: fit names as given)")
          ->capture_default_str();
      sub.add_option("--loss", o->fit.loss,
                     "rel (default) | logratio | log (Low 2012 E2) | cbrt | l2; with --model "
                     "auto, unset: each candidate's own loss");
      sub.add_flag("--no-cosine", o->fit.no_cosine, "leave cos(theta_i) out of the loss");
      sub.add_option("--robust", o->fit.robust, "none | huber | cauchy")->capture_default_str();
      sub.add_option("--robust-scale", o->fit.robust_scale, "robust loss scale, in loss units")
          ->capture_default_str();
      sub.add_option("--cutoff", o->fit.cutoff, "angle cut-off on theta_i and theta_o, degrees")
          ->capture_default_str();
      sub.add_option("--weighting", o->fit.weighting, "cell weights: bin-measure | uniform")
          ->capture_default_str();
      sub.add_option("--budget", o->fit.budget,
                     "samples fitted: full | stride:K (every K-th phi_d bin) | random:N "
                     "(N stratified samples); metrics always use every cell; the default "
                     "renders as well as full in a quarter of the time (docs/fitting.md)")
          ->capture_default_str();
      sub.add_option("--polish", o->fit.polish,
                     "rendered: finish each fit on the rendered-image metric's own pixels "
                     "(docs/accuracy.md, \"The rendered polish\") | none: the table's loss only")
          ->capture_default_str();
      sub.add_option("--seed", o->fit.seed, "seed of random budgets and subsets")
          ->capture_default_str();
      sub.add_option("--multistart", o->fit.multistart,
                     "LM runs from the best N initializer points")
          ->capture_default_str();
      sub.add_option("--max-iterations", o->fit.max_iterations, "per LM run")
          ->capture_default_str();
      sub.add_option("-j,--jobs", o->jobs, "fits in parallel (over files and models)")
          ->capture_default_str();
      sub.add_option("--threads", o->fit.threads,
                     "threads per fit: Ceres' and the metric pass's (same results for any count)")
          ->capture_default_str();
      sub.add_option("--shard", o->shard,
                     "I/N: fit only the I-th of N cost-balanced slices of the (table x model) "
                     "work list, for N processes or machines (docs/scale.md); merge their "
                     "reports with brdfit merge");
      sub.add_flag("--force", o->force,
                   "redo this run's fits even where the report holds them (its other fits stay); "
                   "replace a report that cannot be read");
      sub.add_option("-o,--out", o->out, "HDF5 report (docs/formats.md)")->capture_default_str();
      sub.add_option("--json", o->json,
                     "also write the parameters as JSON (- for standard output)");
      sub.add_flag("--no-timings", o->no_timings,
                   "leave timings, the command line and the date out of the report and JSON "
                   "(byte-identical reruns)");
      sub.add_flag("-q,--quiet", o->quiet, "no table, no progress bar");
      sub.add_flag("--no-progress", o->no_progress, "no progress bar");
      sub.footer(
          "Exit codes: 0 ok, 1 some fit failed, 2 bad input or output (an output that is an "
          "input, a FIFO or a folder; a report another fit is writing); 128 + signal when "
          "interrupted (the report keeps the finished fits).\n"
          "Examples:\n"
          "  brdfit fit mats/*.binary --model ggx,beckmann,ward -o fits.h5 --jobs 2\n"
          "  brdfit fit gold.binary --model ggx --budget random:4000 --json gold.json\n"
          "  brdfit fit gold.binary --model ggx --json - | jq '.fits[0].params'\n"
          "  brdfit fit gold.binary --model ggx:2,lafortune:3 --loss cbrt --multistart 4\n"
          "  brdfit fit nbrdf:all --model ggx,beckmann,ward -j 2 -o nbrdf-fits.h5\n"
          "  brdfit fit nbrdf:all --model auto --shard 3/8 -o shard-3.h5\n"
          "  brdfit fit gold.binary --model auto,factorization -o gold.h5   # + gold.factors/\n"
          "  brdfit fit gold.binary --target gltf --json gold.json   # then brdfit export");
      sub.add_option(
          "--target", o->target,
          "gltf | threejs | blender | mitsuba | pbrt: without --model, fit the model the "
          "target renders exactly (lambert+ggx-hc for gltf and pbrt; lambert+ggx, "
          "lambert+ggx+ggx, burley-2012+ggx for mitsuba, and oren-nayar-fujii+ggx too for "
          "blender; any for threejs); print per fit whether its export is exact and what it "
          "approximates");
      return [o, model_opt] {
        o->models_given = model_opt->count() > 0;
        return RunFit(*o);
      };
    }};

DemoStepRegistrar demo_step{20, "fit models", DemoFit};

}  // namespace
}  // namespace brdfit::cli
