// `brdfit synth`: a synthetic table from any registered model (or an NBRDF network) on any grid,
// with seeded multiplicative noise and holes, written as MERL or HDF5. Same options and seed ->
// same bytes. Also the demo's first step (order 10): a few built-in materials.
#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "core/error.h"
#include "core/model_params.h"
#include "core/suggest.h"
#include "core/synth.h"
#include "core/table_stats.h"
#include "io/atomic_file.h"
#include "io/nbrdf.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/inputs.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct SynthCliOptions {
  std::string model;
  std::vector<std::string> params;
  std::string nbrdf;
  std::string nbrdf_zip;
  bool list_nbrdf = false;
  std::string grid = "90,90,180";
  std::string mapping = "sqrt";
  double noise = 0;
  double missing = 0;
  std::string seed = "0";  // parsed by ParseSeed: CLI11 saturated -1 and 1e20 to 2^64 - 1
  std::string format;
  std::string out;
};

Grid ParseGrid(const std::string& text, const std::string& mapping) {
  Grid g;
  std::vector<long> n;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ',')) {
    char* end = nullptr;
    const long v = std::strtol(part.c_str(), &end, 10);
    if (part.empty() || *end != '\0' || v < 1 || v > 100000) {
      throw InputError(
          fmt::format("--grid '{}': expected three positive integers "
                      "n_theta_h,n_theta_d,n_phi_d (e.g. 90,90,180)",
                      text));
    }
    n.push_back(v);
  }
  if (n.size() != 3) {
    throw InputError(fmt::format("--grid '{}': expected three positive integers", text));
  }
  if (n[0] * n[1] * n[2] > (1l << 31)) throw InputError("--grid " + text + " is too large");
  g.n_theta_h = static_cast<int>(n[0]);
  g.n_theta_d = static_cast<int>(n[1]);
  g.n_phi_d = static_cast<int>(n[2]);
  g.theta_h_mapping = FromString<ThetaHMapping>(mapping);
  return g;
}

// Largest --noise: a log-normal factor of e^10 per standard deviation is already far beyond
// any measurement's noise, and with it no finite value overflows (z stays below ~9).
constexpr double kMaxNoise = 10;

// A seed is a decimal integer in [0, 2^64 - 1]; anything else (a sign, an exponent, overflow)
// is refused rather than saturated.
std::uint64_t ParseSeed(const std::string& text) {
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [at, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || at != end) {
    throw InputError(fmt::format("--seed '{}': expected an integer in [0, {}]", text,
                                 std::numeric_limits<std::uint64_t>::max()));
  }
  return v;
}

// Every valid value written must be finite (the noise multiplies values; a model can return
// huge ones): a non-finite one is refused before anything is written.
void CheckFinite(const Table& t, double noise) {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < t.valid.size(); ++i) {
    if (!t.valid[i]) continue;
    const double* v = t.Value(i);
    bad += !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]);
  }
  if (bad > 0) {
    throw InputError(fmt::format("{} cells would hold non-finite values (noise sigma {}); "
                                 "nothing written",
                                 bad, noise));
  }
}

std::string Grouped(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string s;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s += ',';
    s += digits[i];
  }
  return s;
}

struct SynthResult {
  Table table;
  SynthReport report;
  std::size_t clamped = 0;  // NBRDF: negative outputs set to 0
};

SynthResult SynthesizeFromModel(const ModelInfo& m, const std::vector<double>& p, const Grid& g,
                                const SynthOptions& so) {
  SynthResult r;
  r.table = SynthesizeTable(
      g, [&](const Geometry& geo, double rgb[3]) { m.eval(p.data(), geo, rgb); }, so, &r.report);
  r.table.provenance.model = m.name;
  r.table.provenance.parameters_json = ParamsToJson(m, p);
  return r;
}

SynthResult SynthesizeFromNbrdf(const fs::path& zip, const std::string& material, const Grid& g,
                                const SynthOptions& so) {
  // The table does not depend on the thread count (tested); use the cores there are.
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  NbrdfTabulation tab = TabulateNbrdf(ReadNbrdf(zip, material), g, threads);
  SynthResult r;
  r.report.below_horizon = tab.below_horizon;
  r.clamped = tab.clamped_values;
  ApplyNoiseAndHoles(tab.table, so, &r.report);
  r.table = std::move(tab.table);
  return r;
}

void PrintSummary(const fs::path& out, TableFormat f, const SynthResult& r) {
  const Table& t = r.table;
  const Provenance& p = t.provenance;
  fmt::print("wrote {} ({}, grid {}x{}x{} {})\n", out.string(),
             f == TableFormat::kMerl ? "MERL binary" : "brdfit HDF5 table", t.grid.n_theta_h,
             t.grid.n_theta_d, t.grid.n_phi_d, ToString(t.grid.theta_h_mapping));
  fmt::print("  model {}  parameters {}\n", p.model, p.parameters_json);
  fmt::print("  cells {}: valid {}, below the horizon {}, holes {} (missing fraction {})\n",
             Grouped(t.grid.NumCells()), Grouped(t.CountValid()), Grouped(r.report.below_horizon),
             Grouped(r.report.removed), p.missing_fraction);
  fmt::print("  noise sigma {} (log-normal), seed {}\n", p.noise, p.seed);
  if (r.clamped) fmt::print("  clamped {} negative network outputs to 0\n", Grouped(r.clamped));
  if (r.report.negative || r.report.non_finite) {
    fmt::print("  masked {} negative and {} non-finite model values\n", r.report.negative,
               r.report.non_finite);
  }
  if (f == TableFormat::kMerl) {
    fmt::print("  (MERL files do not store the model, parameters or seed; use .h5 to keep them)\n");
  }
}

int RunSynth(const SynthCliOptions& o) {
  if (o.list_nbrdf) {
    const fs::path zip = pipeline::NbrdfArchive(o.nbrdf_zip);
    const std::vector<std::string> materials = ListNbrdfMaterials(zip);
    if (materials.empty()) throw InputError(zip, kNoNbrdfMaterials);  // not an empty list, exit 0
    for (const auto& m : materials) fmt::print("{}\n", m);
    return kExitOk;
  }
  if (o.model.empty() == o.nbrdf.empty()) {
    throw InputError("give exactly one of --model M or --nbrdf MATERIAL (models: " + ModelNames() +
                     ")");
  }
  if (o.out.empty()) throw InputError("--out FILE is required");
  if (!o.nbrdf.empty() && !o.params.empty()) {
    throw InputError("--param applies to --model, not to --nbrdf");
  }
  const fs::path out = o.out;
  std::vector<fs::path> inputs;
  if (!o.nbrdf.empty()) inputs.push_back(pipeline::NbrdfArchive(o.nbrdf_zip));
  CheckOutputs(inputs, {{out, "-o"}});
  const TableFormat format = OutputTableFormat(out, o.format);
  const Grid grid = ParseGrid(o.grid, o.mapping);
  CheckFormatHoldsGrid(format, grid, out);
  if (!(o.noise >= 0 && o.noise <= kMaxNoise)) {
    throw InputError(fmt::format("--noise {}: expected a sigma in [0, {}] (log-normal)", o.noise,
                                 kMaxNoise));
  }
  if (!(o.missing >= 0 && o.missing <= 1)) {
    throw InputError(fmt::format("--missing {}: expected a fraction in [0, 1]", o.missing));
  }
  const SynthOptions so{o.noise, o.missing, ParseSeed(o.seed)};

  SynthResult r;
  if (!o.model.empty()) {
    const ModelInfo* m = FindModel(o.model);
    if (!m) {
      throw InputError("unknown model '" + o.model + "'" +
                       SuggestionAfter(o.model, AllModelNames()) +
                       "; known models: " + ModelNames());
    }
    r = SynthesizeFromModel(*m, ResolveModelParams(*m, o.params), grid, so);
  } else {
    r = SynthesizeFromNbrdf(pipeline::NbrdfArchive(o.nbrdf_zip), o.nbrdf, grid, so);
  }
  CheckFinite(r.table, o.noise);
  SaveTable(r.table, out, format);
  PrintSummary(out, format, r);
  return kExitOk;
}

Registrar reg{
    "synth", "Synthetic table from a model or an NBRDF network, with noise and holes",
    [](CLI::App& sub) {
      auto o = std::make_shared<SynthCliOptions>();
      sub.add_option("-m,--model", o->model, "registered model (see `brdfit models`)");
      sub.add_option("-p,--param", o->params,
                     "name=value; qualified (ggx.alpha) or bare when unambiguous (alpha); "
                     "repeatable; unset parameters keep their defaults")
          ->allow_extra_args(false);
      sub.add_option("--nbrdf", o->nbrdf, "MERL material from the NBRDF archive (e.g. gold-paint)");
      sub.add_option("--nbrdf-zip", o->nbrdf_zip,
                     "NBRDF archive (default: $BRDFIT_NBRDF_ZIP or ../shared/data/merl_nbrdf.zip)");
      sub.add_flag("--list-nbrdf", o->list_nbrdf, "list the archive's materials and exit");
      sub.add_option("--grid", o->grid, "n_theta_h,n_theta_d,n_phi_d")->capture_default_str();
      sub.add_option("--mapping", o->mapping, "theta_h mapping: sqrt (MERL) or linear")
          ->capture_default_str();
      sub.add_option("--noise", o->noise, "sigma of log-normal multiplicative noise")
          ->capture_default_str();
      sub.add_option("--missing", o->missing, "fraction of valid cells removed (holes)")
          ->capture_default_str();
      sub.add_option("--seed", o->seed, "seed for noise and holes, an integer in [0, 2^64 - 1]")
          ->capture_default_str();
      sub.add_option("--format", o->format, "merl or h5 (default: from the extension)");
      sub.add_option("-o,--out", o->out, "output file (.binary = MERL, .h5 = HDF5)");
      sub.footer(
          "Exit codes: 0 written, 2 bad model, parameter or output.\n"
          "Cells are evaluated at their centres; cells below the horizon are masked.\n"
          "Examples:\n"
          "  brdfit synth --model lambert+ggx --param ggx.alpha=0.1 --param kd_r=0.6 -o t.binary\n"
          "  brdfit synth --model ggx --grid 45,45,90 --mapping linear --noise 0.05 \\\n"
          "      --missing 0.3 --seed 7 -o t.h5\n"
          "  brdfit synth --nbrdf gold-metallic-paint -o gold.binary\n"
          "  brdfit synth --list-nbrdf");
      return [o] { return RunSynth(*o); };
    }};

// ---- demo step: built-in materials --------------------------------------------------------

struct DemoMaterial {
  const char* name;
  std::vector<std::string> params;  // for lambert+ggx
  double noise, missing;
};

int DemoSynth(DemoContext& ctx) {
  const ModelInfo* m = FindModel("lambert+ggx");
  if (!m) throw InputError("demo: model lambert+ggx is not registered");
  const std::vector<DemoMaterial> materials = {
      {"red-plastic",
       {"kd_r=0.45", "kd_g=0.06", "kd_b=0.05", "ks_r=0.04", "ks_g=0.04", "ks_b=0.04", "alpha=0.08"},
       0.0,
       0.0},
      {"blue-rough",
       {"kd_r=0.05", "kd_g=0.12", "kd_b=0.40", "ks_r=0.03", "ks_g=0.03", "ks_b=0.03", "alpha=0.35"},
       0.0,
       0.0},
      {"gold-noisy-holes",
       {"kd_r=0.02", "kd_g=0.015", "kd_b=0.005", "ks_r=0.95", "ks_g=0.65", "ks_b=0.25",
        "alpha=0.12"},
       0.03,
       0.2},
  };
  // Quick (tests): a small HDF5 grid; otherwise MERL files on the MERL grid.
  const Grid grid = ctx.quick ? Grid{30, 30, 60, ThetaHMapping::kSqrt} : Grid::Merl();
  const std::string ext = ctx.quick ? ".h5" : ".binary";
  auto emit = [&](const std::string& name, const SynthResult& r) {
    const fs::path table = ctx.out_dir / (name + ext);
    CheckOutputs({}, {{table, "demo table"}, {ctx.out_dir / (name + ".info.json"), "demo info"}});
    SaveTable(r.table, table);
    fmt::print("  {}: {} valid cells of {}\n", table.string(), Grouped(r.table.CountValid()),
               Grouped(r.table.grid.NumCells()));
    nlohmann::ordered_json info = TableStatsToJson(ComputeTableStats(r.table));
    info["provenance"] = {{"model", r.table.provenance.model},
                          {"parameters", r.table.provenance.parameters_json},
                          {"noise", r.table.provenance.noise},
                          {"missing_fraction", r.table.provenance.missing_fraction},
                          {"seed", r.table.provenance.seed}};
    const fs::path info_path = ctx.out_dir / (name + ".info.json");
    WriteTextAtomically(info_path,
                        info.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    ctx.tables.push_back(table);
    ctx.outputs.push_back(table);
    ctx.outputs.push_back(info_path);
  };
  for (const auto& mat : materials) {
    emit(mat.name, SynthesizeFromModel(*m, ResolveModelParams(*m, mat.params), grid,
                                       {mat.noise, mat.missing, 1}));
  }
  const fs::path zip = pipeline::NbrdfArchive("");
  if (fs::is_regular_file(zip)) {
    emit("nbrdf-gold-metallic-paint", SynthesizeFromNbrdf(zip, "gold-metallic-paint", grid, {}));
  } else {
    fmt::print("  {} not found: skipping the NBRDF material\n", zip.string());
  }
  return kExitOk;
}

DemoStepRegistrar demo_step{10, "synthesize tables", DemoSynth};

}  // namespace
}  // namespace brdfit::cli
