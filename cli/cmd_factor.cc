// `brdfit factor FILES... -o DIR`: homomorphic factorization of each table into float32 OpenEXR
// textures (two per term; with --rank K, K products, with --diffuse a diffuse value added) plus
// a JSON sidecar (factor/factor.h, docs/factorization.md), scored
// like a fit (fit metrics and the rendered-image metric, docs/accuracy.md). The factored system
// is built once per grid and mask and reused for every further file.
#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "core/error.h"
#include "core/file_stem.h"
#include "core/model_choice.h"
#include "factor/factor.h"
#include "factor/factor_choice.h"
#include "factor/factor_form.h"
#include "io/factor_io.h"
#include "io/input_file.h"
#include "io/nbrdf.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "pipeline/factor_settings.h"
#include "pipeline/factor_table.h"
#include "pipeline/inputs.h"
#include "pipeline/material_keys.h"
#include "pipeline/shard.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

// The defaults of the factored form and its solve, in one place: they are to be chosen by a
// study over the MERL proxies (docs/factorization.md §12); until then McCool et al.'s rank 1.
constexpr bool kDefaultDiffuse = false;
constexpr int kDefaultRank = 1;
constexpr bool kDefaultRefine = false;
// Without an explicit form (--param, --diffuse, --rank, --refine, --refine-loss), every form
// of factor/factor_choice.h is tried and the one the rendered metric prefers is kept.
constexpr bool kDefaultAutoForm = true;
using pipeline::kMaxRefineIterations;

struct FactorCliOptions {
  std::vector<std::string> files;
  std::string out_dir;
  std::string param = "mccool";
  int resolution = 64;
  double lambda = FactorOptions{}.lambda;
  std::string weighting = "solid-angle";
  double max_theta_deg = 90;
  double metric_cutoff_deg = SampleOptions{}.cutoff_deg;
  bool diffuse = kDefaultDiffuse;
  int rank = kDefaultRank;
  bool refine = kDefaultRefine;
  int refine_iterations = FactorOptions{}.refine_iterations;
  std::string refine_loss = "rel";
  bool auto_form = kDefaultAutoForm;  // cleared by any option that names the form
  std::string suffix;                 // appended to each output stem (the demo writes both forms)
  std::string shard;                  // "I/N" (pipeline/shard.h); empty: every table
  bool no_timings = false;            // nothing run-dependent in the outputs
  bool quiet = false;
};

// A table of the run: its input and its material key (pipeline/material_keys.h).
struct FactorInput {
  std::string file;
  std::string material;
};

// The tables this run factors: every input, or the shard's whole tables (pipeline/shard.h; one
// unit per table, so with fewer tables than shards some shards have none).
std::vector<FactorInput> RunInputs(const FactorCliOptions& o) {
  const std::vector<std::string> files = pipeline::ExpandInputs(o.files);
  const std::vector<std::string> keys = pipeline::MaterialKeys(files);
  const pipeline::Shard shard = o.shard.empty() ? pipeline::Shard{} : pipeline::ParseShard(o.shard);
  const std::vector<bool> in = pipeline::ShardMembership(keys, {{"factor", ""}}, shard);
  std::vector<FactorInput> out;
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (in[f]) out.push_back({files[f], keys[f]});
  }
  return out;
}

// The rendered score of one candidate or rank, for the printed line.
std::string ScoreText(const RenderedError& e) {
  return fmt::format("S {:>7} dB  psnr {:>6} dB  med_lum {:>6}",
                     e.ok ? fmt::format("{:.2f}", RenderedScoreDb(e)) : "-",
                     e.ok ? fmt::format("{:.1f}", e.psnr_db) : "-",
                     e.ok ? fmt::format("{:.1f}%", 100 * e.median_rel_error) : "-");
}

// The stem of a table's outputs: its material key (pipeline/material_keys.h: "a/x" for
// a/x.binary beside b/x.binary), which may come from inside an archive, made one safe path
// component (core/file_stem.h): "a_x".
std::string OutputStem(const std::string& material, const std::string& suffix) {
  return SafeFileStem(material + suffix);
}

// Validates everything that can be checked before any work: options, inputs, output names.
FactorOptions CheckOptions(const FactorCliOptions& o, const std::vector<FactorInput>& inputs) {
  const FactorOptions f = pipeline::MakeFactorOptions({o.param, o.resolution, o.lambda, o.weighting,
                                                       o.max_theta_deg, o.diffuse, o.rank, o.refine,
                                                       o.refine_iterations, o.refine_loss});
  // The forms tried include halfdiff: its limit before any solve (a mccool solve at 1024 takes
  // minutes, and the halfdiff candidate after it would be refused).
  if ((o.auto_form || f.param == FactorParam::kHalfDiff) && o.resolution > kMaxHalfDiffResolution) {
    throw InputError(fmt::format(
        "--res {} is too large for halfdiff{} (at most {}: its q texture is solved texel by "
        "texel); {}",
        o.resolution, o.auto_form ? ", one of the parameterizations --auto tries" : "",
        kMaxHalfDiffResolution,
        o.auto_form ? "give --param mccool for larger textures, or --res " +
                          std::to_string(kMaxHalfDiffResolution) + " or less"
                    : "give --res " + std::to_string(kMaxHalfDiffResolution) + " or less"));
  }
  std::map<std::string, std::string> stems;
  std::vector<PlannedOutput> outputs;
  std::vector<std::string> files;
  for (const auto& [file, material] : inputs) {
    files.push_back(file);
    if (!IsNbrdfInput(file)) CheckInputFile(file);
    const std::string stem = OutputStem(material, o.suffix);
    if (auto [it, fresh] = stems.emplace(stem, file); !fresh) {
      throw InputError(file, fmt::format("writes the same outputs ({}.*) as {}", stem, it->second));
    }
    const int rank = o.auto_form ? kMaxFactorRank : o.rank;  // auto: any form may be written
    for (const fs::path& p : FactorFilePaths(o.out_dir, stem, rank).All()) {
      outputs.push_back({p, "-o " + o.out_dir});
    }
  }
  CheckOutputFolder(o.out_dir, "-o");
  CheckOutputs(pipeline::InputFiles(files), outputs);
  return f;
}

// One line per table (as brdfit fit prints its metrics: "-" when the rendered metric failed,
// the sidecar says why), then, when there is one, the diffuse value, and what the refinement did.
void PrintSummary(const std::string& stem, const Factorization& r, double ln_rmse,
                  const FitMetrics& m, const RenderedError& re) {
  const FactorForm form = FormOf(r.brdf);
  const FactorCost cost = ComputeFactorCost(form);
  const std::string psnr = re.ok ? fmt::format("{:.1f}", re.psnr_db) : "-";
  const std::string lum = re.ok ? fmt::format("{:.1f}%", 100 * re.median_rel_error) : "-";
  // Per light, and (mccool's p(wo)) per fragment.
  const std::string fetches =
      cost.fetches_per_fragment > 0
          ? fmt::format("{}+{}", cost.fetches_per_light, cost.fetches_per_fragment)
          : fmt::format("{}", cost.fetches_per_light);
  const FactorStats& s = r.stats;
  std::string errors;
  for (const ErrorMetricField& f : kErrorMetrics) errors += fmt::format(" {:>9.4g}", m.*f.value);
  fmt::print(
      "{:<28} {:<13} {:>4} {:>8} {:>7} {:>10.4g}{} {:>7} {:>7} {:>8.1f} "
      "{:>7} {:>8} {:>8.1f}ms\n",
      stem, FactorFormLabel(form), r.options.resolution, s.used_cells, s.nonpositive_cells, ln_rmse,
      errors, psnr, lum, cost.texture_bytes / 1024.0, fetches,
      s.system_rebuilt  ? "rebuilt"
      : s.system_reused ? "reused"
                        : "built",
      1e3 * s.seconds);
  if (r.options.diffuse || r.brdf.has_diffuse()) {
    const auto& d = r.brdf.diffuse();
    fmt::print(
        "  diffuse d = kd/pi = ({:.4g}, {:.4g}, {:.4g}) 1/sr (kd = {:.4g}, {:.4g}, {:.4g})\n", d[0],
        d[1], d[2], kPi * d[0], kPi * d[1], kPi * d[2]);
  }
  if (r.brdf.rank() != r.options.rank) {
    fmt::print("  rank {} of the {} asked for\n", r.brdf.rank(), r.options.rank);
  }
  if (s.refine_rows > 0) {
    fmt::print("  refine: relative RMS {:.4g} -> {:.4g}, {} iterations, {} rows, {:.2f} s\n",
               s.refine_rel_rms_start, s.refine_rel_rms, s.refine_iterations, s.refine_rows,
               s.refine_seconds);
  }
  std::fflush(stdout);  // one table at a time, visible as it finishes
}

int RunFactor(const FactorCliOptions& o, std::vector<fs::path>* written = nullptr) {
  const std::vector<FactorInput> inputs = RunInputs(o);
  const FactorOptions options = CheckOptions(o, inputs);
  if (!o.auto_form && options.param == FactorParam::kHalfDiff && options.NeedsRefinement() &&
      options.resolution >= 32) {
    // The sparse LM path (factor/factor_refine.h): docs/nbrdf-results.md measured ~6 s (d),
    // ~80 s (d + rank 2) and > 10 min (d + rank 4) per MERL table at 64^2.
    fmt::print(stderr,
               "brdfit: note: a refined halfdiff factorization ({}^2, rank {}) solves {} unknowns "
               "per channel with a sparse factorization per step: seconds (rank 1) to many "
               "minutes (rank >= 2) per MERL-size table; mccool refines in well under a second\n",
               options.resolution, options.rank,
               options.rank * (FactorSystem::NumP(options.resolution) +
                               FactorSystem::NumQ(options.param, options.resolution)) +
                   (options.diffuse ? 1 : 0));
  }
  MakeOutputFolder(o.out_dir);
  SampleOptions metric_samples;
  metric_samples.cutoff_deg = o.metric_cutoff_deg;
  FactorSystemCache cache;
  int code = kExitOk;
  if (!o.quiet) {
    std::string errors;
    for (const ErrorMetricField& f : kErrorMetrics) errors += fmt::format(" {:>9}", f.name);
    fmt::print(
        "{:<28} {:<13} {:>4} {:>8} {:>7} {:>10}{} {:>7} {:>7} {:>8} {:>7} {:>8} "
        "{:>9}\n",
        "table", "form", "res", "cells", "f<=0", "ln-rmse", errors, "psnr_dB", "med_lum", "tex_KiB",
        "fetches", "system", "time");
  }
  for (const FactorInput& input : inputs) {
    const std::string& file = input.file;
    const bool last = &input == &inputs.back();
    try {
      const Table table = pipeline::LoadInput(file);
      pipeline::FactorTableRequest q;
      q.file = file;
      q.material = input.material;
      q.stem = OutputStem(input.material, o.suffix);
      q.options = options;
      q.auto_form = o.auto_form;
      q.metric_samples = metric_samples;
      q.out_dir = o.out_dir;
      q.timings = !o.no_timings;
      q.cache = &cache;
      q.last = last;
      const pipeline::FactoredTable t = pipeline::FactorTable(table, q);
      if (written) {
        for (const fs::path& p : t.paths.All()) written->push_back(p);
      }
      if (!o.quiet) {
        for (const pipeline::FormScore& f : t.forms) {
          fmt::print("  candidate {:<16} {}{}\n", f.name, ScoreText(f.rendered),
                     f.chosen ? "  <- chosen" : "");
        }
        for (const pipeline::RankScore& k : t.ranks) {
          fmt::print("  rank {}: {}  {:>7.1f} KiB  {} fetches per light\n", k.rank,
                     ScoreText(k.rendered), k.cost.texture_bytes / 1024.0,
                     k.cost.fetches_per_light);
        }
        PrintSummary(q.stem, t.result, t.ln_rmse, t.metrics, t.rendered);
      }
    } catch (const InputError& e) {
      fmt::print(stderr, "brdfit: error: {}\n", e.what());
      code = kExitBadInput;
    } catch (const OutputError& e) {
      // A read-only or full output folder is an output error (exit 2), not a failed solve, and
      // the next table would meet it too.
      fmt::print(stderr, "brdfit: error: {}\n", e.what());
      code = kExitBadInput;
      break;
    } catch (const std::runtime_error& e) {
      fmt::print(stderr, "brdfit: error: {}: {}\n", file, e.what());
      if (code == kExitOk) code = kExitFitFailed;
    }
  }
  if (!o.quiet) fmt::print("outputs in {}\n", fs::absolute(o.out_dir).string());
  return code;
}

Registrar reg{
    "factor", "Factor tables into textures (McCool 2001 homomorphic factorization)",
    [](CLI::App& sub) {
      auto o = std::make_shared<FactorCliOptions>();
      sub.add_option("files", o->files,
                     "tables (MERL .binary or brdfit .h5); nbrdf:NAME or nbrdf:all tabulates the "
                     "NBRDF networks of ../shared/data/merl_nbrdf.zip on the MERL grid")
          ->required();
      sub.add_option("-o,--out", o->out_dir, "output folder")->required();
      const auto explicit_form = [o](const auto&) { o->auto_form = false; };
      sub.add_option("--param", o->param,
                     "mccool: f = p(wi) q(wh) p(wo); halfdiff: f = p(wh) q(theta_d, phi_d)")
          ->capture_default_str()
          ->each(explicit_form);
      sub.add_option("--res", o->resolution, "texture side N (N x N texels per factor)")
          ->capture_default_str();
      sub.add_option("--lambda", o->lambda, "smoothness weight (> 0)")->capture_default_str();
      sub.add_option("--weighting", o->weighting,
                     "data weights: solid-angle (bin measure) or cell (every cell alike)")
          ->capture_default_str();
      sub.add_option("--max-theta", o->max_theta_deg,
                     "use cells with theta_i, theta_o <= this (degrees)")
          ->capture_default_str();
      sub.add_option("--metric-cutoff", o->metric_cutoff_deg,
                     "angle cut-off of the fit metrics (degrees), as brdfit fit")
          ->capture_default_str();
      sub.add_flag("--diffuse,!--no-diffuse", o->diffuse,
                   "add a diffuse value d = kd/pi to the products, solved with them")
          ->capture_default_str()
          ->each(explicit_form);
      sub.add_option(
             "--rank", o->rank,
             fmt::format("products in the sum, 1 to {} (two textures each)", kMaxFactorRank))
          ->capture_default_str()
          ->each(explicit_form);
      sub.add_flag("--refine,!--no-refine", o->refine,
                   "refine the log-space solution under the relative loss of the analytic fits "
                   "(implied by --diffuse and --rank > 1)")
          ->capture_default_str()
          ->each(explicit_form);
      sub.add_option("--refine-loss", o->refine_loss,
                     "loss of the refinement: rel ((f - m) / (m + eps)) or logratio "
                     "(ln((f + eps) / (m + eps)))")
          ->capture_default_str()
          ->each(explicit_form);
      sub.add_flag("--auto,!--no-auto", o->auto_form,
                   "try the forms of docs/factorization.md \"Choosing the form\" and keep the one "
                   "the rendered metric prefers (the default unless an option names the form)")
          ->capture_default_str();
      sub.add_option("--refine-iterations", o->refine_iterations,
                     "Levenberg-Marquardt iterations of the refinement, at most")
          ->capture_default_str();
      sub.add_option("--shard", o->shard,
                     "I/N: factor only the I-th of N slices of the tables (whole tables, "
                     "docs/scale.md); join the output folders with brdfit merge");
      sub.add_flag("--no-timings", o->no_timings,
                   "leave the times, the factored system's reuse, the command line and the date "
                   "out of the sidecars and textures (byte-identical reruns and merges)");
      sub.add_flag("-q,--quiet", o->quiet, "no table on stdout");
      sub.footer(
          "Exit codes: 0 ok, 1 a solve failed, 2 bad input (named, the other tables are still "
          "factored) or an output error (the run stops).\n"
          "Writes DIR/<stem>.p.exr, DIR/<stem>.q.exr (float32 RGB OpenEXR; with --rank K also\n"
          "<stem>.p2.exr, <stem>.q2.exr, ... up to K) and DIR/<stem>.factor.json per table\n"
          "(docs/formats.md, docs/factorization.md). The table: form (parameterization, +d with a\n"
          "diffuse value, rK for rank K), texture memory and fetches per light (+ per fragment).\n"
          "Without an option naming the form, the forms of docs/factorization.md \"Choosing the\n"
          "form\" are tried and the one with the best rendered score is kept (--no-auto: mccool).\n"
          "Examples:\n"
          "  brdfit factor gold-paint.binary -o out\n"
          "  brdfit factor gold-paint.binary --diffuse --rank 2 -o out\n"
          "  brdfit factor mats/*.binary --param halfdiff --res 32 --lambda 1e-4 -o out\n"
          "  brdfit factor nbrdf:all --res 32 -o nbrdf-factors\n"
          "  brdfit factor nbrdf:all --shard 2/8 --no-timings -o factors-2");
      return [o] { return RunFactor(*o); };
    }};

// Demo step 30: both parameterizations of every synthetic table, side by side.
DemoStepRegistrar demo_step{30, "factor", [](DemoContext& ctx) {
                              std::vector<std::string> files;
                              for (const auto& t : ctx.tables) files.push_back(t.string());
                              if (files.empty()) return kExitOk;
                              int code = kExitOk;
                              for (const char* param : {"mccool", "halfdiff"}) {
                                FactorCliOptions o;
                                o.files = files;
                                o.out_dir = (ctx.out_dir / "factor").string();
                                o.param = param;
                                o.resolution = ctx.quick ? 32 : 64;
                                o.suffix = std::string(".") + param;
                                o.auto_form = false;
                                const int c = RunFactor(o, &ctx.outputs);
                                if (c != kExitOk) code = c;
                              }
                              return code;
                            }};

}  // namespace
}  // namespace brdfit::cli
