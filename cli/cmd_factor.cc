// `brdfit factor FILES... -o DIR`: rank-1 homomorphic factorization of each table into two
// float32 OpenEXR textures plus a JSON sidecar (factor/factor.h, docs/factorization.md), scored
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
#include "pipeline/inputs.h"
#include "factor/factor.h"
#include "pipeline/factor_export.h"
#include "factor/factor_metrics.h"
#include "core/error.h"
#include "core/file_stem.h"
#include "io/factor_io.h"
#include "io/output_policy.h"
#include "io/input_file.h"
#include "io/metrics_json.h"
#include "io/nbrdf.h"
#include "report/report_inputs.h"
#include "io/table_io.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct FactorCliOptions {
  std::vector<std::string> files;
  std::string out_dir;
  std::string param = "mccool";
  int resolution = 64;
  double lambda = FactorOptions{}.lambda;
  std::string weighting = "solid-angle";
  double max_theta_deg = 90;
  double metric_cutoff_deg = SampleOptions{}.cutoff_deg;
  std::string suffix;  // appended to each output stem (the demo writes both forms)
  bool quiet = false;
};

nlohmann::json MetricsJson(const FitMetrics& m, const RenderedError& rendered, double ln_rmse) {
  nlohmann::json j = {{"ln_ratio_rmse", ln_rmse},
                      {"ln_ratio_rmse_definition",
                       "sqrt(mean over valid cells above the horizon with all channels > 0 of "
                       "(ln f_factored - ln f_table)^2), unweighted, cell centres"}};
  j["fit_metrics"] = {{"ok", m.ok},
                      {"log_rmse", m.log_rmse},
                      {"cbrt_rmse", m.cbrt_rmse},
                      {"rel_l2", m.rel_l2},
                      {"cells", m.cells},
                      {"weighting", m.weighting},
                      {"cutoff_deg", m.cutoff_deg},
                      {"definition", MetricsDefinition()}};
  if (!m.ok) j["fit_metrics"]["problem"] = m.problem;
  // The rendered-image metric, written as brdfit fit writes it (io/metrics_json.h).
  j["rendered"] = nlohmann::json(RenderedErrorJson(rendered));
  return j;
}

nlohmann::json SourceJson(const fs::path& file, const Table& t) {
  const Provenance& p = t.provenance;
  const std::string name = file.string();
  return {{"file", IsNbrdfInput(name) ? name : fs::absolute(file).string()},
          {"grid",
           {{"n_theta_h", t.grid.n_theta_h},
            {"n_theta_d", t.grid.n_theta_d},
            {"n_phi_d", t.grid.n_phi_d},
            {"theta_h_mapping", ToString(t.grid.theta_h_mapping)}}},
          {"provenance",
           {{"source", p.source},
            {"generator", p.generator},
            {"model", p.model},
            {"seed", p.seed},
            {"noise", p.noise},
            {"missing_fraction", p.missing_fraction}}}};
}

// The stem of a table's outputs: its material name, which may come from inside an archive,
// made one safe path component (core/file_stem.h).
std::string OutputStem(const std::string& file, const std::string& suffix) {
  return SafeFileStem(report::MaterialName(file) + suffix);
}

// Validates everything that can be checked before any work: options, inputs, output names.
FactorOptions CheckOptions(const FactorCliOptions& o) {
  FactorOptions f;
  f.param = FactorParamFromString(o.param);
  f.resolution = o.resolution;
  f.lambda = o.lambda;
  f.weighting = FromString<FactorWeighting>(o.weighting);
  if (!(o.max_theta_deg > 0 && o.max_theta_deg <= 90)) {
    throw InputError(fmt::format("--max-theta {} outside (0, 90]", o.max_theta_deg));
  }
  f.max_theta = o.max_theta_deg * kPi / 180;
  if (o.resolution < 4 || o.resolution > 1024) {
    throw InputError(fmt::format("--res {} outside [4, 1024]", o.resolution));
  }
  if (!(o.lambda > 0) || !std::isfinite(o.lambda)) {
    throw InputError(fmt::format("--lambda {} must be a positive number", o.lambda));
  }
  std::map<std::string, std::string> stems;
  const std::vector<std::string> inputs = pipeline::ExpandInputs(o.files);
  std::vector<PlannedOutput> outputs;
  for (const std::string& file : inputs) {
    if (!IsNbrdfInput(file)) CheckInputFile(file);
    const std::string stem = OutputStem(file, o.suffix);
    if (auto [it, fresh] = stems.emplace(stem, file); !fresh) {
      throw InputError(file, fmt::format("writes the same outputs ({}.*) as {}", stem, it->second));
    }
    const FactorPaths paths = FactorFilePaths(o.out_dir, stem);
    for (const fs::path& p : {paths.p, paths.q, paths.json}) outputs.push_back({p, "-o " + o.out_dir});
  }
  CheckOutputFolder(o.out_dir, "-o");
  CheckOutputs(pipeline::InputFiles(inputs), outputs);
  return f;
}

int RunFactor(const FactorCliOptions& o, std::vector<fs::path>* written = nullptr) {
  const FactorOptions options = CheckOptions(o);
  MakeOutputFolder(o.out_dir);
  SampleOptions metric_samples;
  metric_samples.cutoff_deg = o.metric_cutoff_deg;
  FactorSystemCache cache;
  int code = kExitOk;
  if (!o.quiet) {
    fmt::print("{:<28} {:<8} {:>4} {:>8} {:>7} {:>10} {:>9} {:>9} {:>7} {:>7} {:>8} {:>9}\n",
               "table", "param", "res", "cells", "f<=0", "ln-rmse", "E2-log", "cbrt", "psnr_dB",
               "med_lum", "system", "time");
  }
  for (const std::string& file : pipeline::ExpandInputs(o.files)) {
    try {
      const Table table = pipeline::LoadInput(file);
      Factorization r;
      try {
        r = Factor(table, options, &cache);
      } catch (const InputError& e) {
        throw InputError(file, e.what());
      }
      const double ln_rmse = FactorLnRatioRmse(table, r.brdf, options.max_theta);
      const FitMetrics m = ScoreFactorization(table, r.brdf, metric_samples);
      // What the preview draws from the textures written below (docs/accuracy.md).
      const RenderedError re = ScoreFactorizationRendered(table, r.brdf);
      const std::string stem = OutputStem(file, o.suffix);
      const FactorPaths paths = SaveFactorization(
          r, o.out_dir, stem,
          {{"source", SourceJson(file, table)}, {"metrics", MetricsJson(m, re, ln_rmse)}});
      if (written) {
        for (const fs::path& p : {paths.p, paths.q, paths.json}) written->push_back(p);
      }
      if (!o.quiet) {
        // As brdfit fit prints them: "-" when the metric failed (the sidecar says why).
        const std::string psnr = re.ok ? fmt::format("{:.1f}", re.psnr_db) : "-";
        const std::string lum = re.ok ? fmt::format("{:.1f}%", 100 * re.median_rel_error) : "-";
        fmt::print("{:<28} {:<8} {:>4} {:>8} {:>7} {:>10.4g} {:>9.4g} {:>9.4g} {:>7} {:>7} {:>8} "
                   "{:>8.1f}ms\n",
                   stem, o.param, options.resolution, r.stats.used_cells, r.stats.nonpositive_cells,
                   ln_rmse, m.log_rmse, m.cbrt_rmse, psnr, lum,
                   r.stats.system_rebuilt  ? "rebuilt"
                   : r.stats.system_reused ? "reused"
                                           : "built",
                   1e3 * r.stats.seconds);
        std::fflush(stdout);  // one line per table, visible as it finishes
      }
    } catch (const InputError& e) {
      fmt::print(stderr, "brdfit: error: {}\n", e.what());
      code = kExitBadInput;
    } catch (const OutputError& e) {
      // A read-only or full output folder is an output error (exit 2), not a failed solve, and
      // the next table would meet it too (issue 14 item 15).
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
    "factor", "Factor tables into two textures (McCool 2001 homomorphic factorization)",
    [](CLI::App& sub) {
      auto o = std::make_shared<FactorCliOptions>();
      sub.add_option("files", o->files,
                     "tables (MERL .binary or brdfit .h5); nbrdf:NAME or nbrdf:all tabulates the "
                     "NBRDF networks of ../shared/data/merl_nbrdf.zip on the MERL grid")
          ->required();
      sub.add_option("-o,--out", o->out_dir, "output folder")->required();
      sub.add_option("--param", o->param,
                     "mccool: f = p(wi) q(wh) p(wo); halfdiff: f = p(wh) q(theta_d, phi_d)")
          ->capture_default_str();
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
      sub.add_flag("-q,--quiet", o->quiet, "no table on stdout");
      sub.footer(
          "Exit codes: 0 ok, 1 a solve failed, 2 bad input (named, the other tables are still "
          "factored) or an output error (the run stops).\n"
          "Writes DIR/<stem>.p.exr, DIR/<stem>.q.exr (float32 RGB OpenEXR) and "
          "DIR/<stem>.factor.json per table\n(docs/formats.md, docs/factorization.md).\n"
          "Examples:\n"
          "  brdfit factor gold-paint.binary -o out\n"
          "  brdfit factor mats/*.binary --param halfdiff --res 32 --lambda 1e-4 -o out\n"
          "  brdfit factor nbrdf:all --res 32 -o nbrdf-factors");
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
                                const int c = RunFactor(o, &ctx.outputs);
                                if (c != kExitOk) code = c;
                              }
                              return code;
                            }};

}  // namespace
}  // namespace brdfit::cli
