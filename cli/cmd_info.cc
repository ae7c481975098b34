// `brdfit info FILE [--json]`: format, grid and mapping, valid/invalid counts (below the
// horizon vs holes), per-channel min/median/max and a directional-albedo estimate
// (core/table_stats.h), plus the provenance a brdfit HDF5 table carries.
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/command.h"
#include "cli/terminal_text.h"
#include "core/table_stats.h"
#include "io/nbrdf.h"
#include "io/table_io.h"
#include "pipeline/inputs.h"

namespace brdfit::cli {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
};

// What `info` says the input is: a file format, or an NBRDF network tabulated on the MERL grid.
enum class InfoFormat { kMerl, kHdf5, kNbrdf, kRglBsdf };
const char* FormatName(InfoFormat f) {
  switch (f) {
    case InfoFormat::kMerl:
      return "MERL binary";
    case InfoFormat::kHdf5:
      return "brdfit HDF5 table";
    case InfoFormat::kNbrdf:
      return "NBRDF network, tabulated on the MERL grid";
    case InfoFormat::kRglBsdf:
      return "RGL .bsdf (Dupuy & Jakob 2018), tabulated on the MERL grid";
  }
  return "?";
}
const char* JsonName(InfoFormat f) {
  return f == InfoFormat::kNbrdf ? "nbrdf" : "?";
}

double Percent(std::size_t n, std::size_t of) {
  return of ? 100.0 * static_cast<double>(n) / static_cast<double>(of) : 0.0;
}

nlohmann::ordered_json ProvenanceJson(const Provenance& p) {
  nlohmann::ordered_json j;
  j["source"] = p.source;
  j["generator"] = p.generator;
  j["model"] = p.model;
  // Parameters are stored as JSON text: embed them as an object when they parse.
  const auto params = nlohmann::ordered_json::parse(p.parameters_json, nullptr, false);
  j["parameters"] = params.is_discarded() ? nlohmann::ordered_json(p.parameters_json) : params;
  j["seed"] = p.seed;
  j["noise"] = p.noise;
  j["missing_fraction"] = p.missing_fraction;
  return j;
}

void PrintText(const InfoOptions& o, const Table& t, InfoFormat format, const LoadReport& r,
               const TableStats& s) {
  const Grid& g = t.grid;
  const std::size_t above = s.cells - s.below_horizon;
  fmt::print("file        {}\n", TerminalSafe(o.path));
  fmt::print("format      {}\n", FormatName(format));
  fmt::print("grid        {} x {} x {} (theta_h x theta_d x phi_d), theta_h mapping {}\n",
             g.n_theta_h, g.n_theta_d, g.n_phi_d, ToString(g.theta_h_mapping));
  fmt::print("cells       {}\n", s.cells);
  fmt::print("valid       {} ({:.2f} %)\n", s.valid, Percent(s.valid, s.cells));
  fmt::print("invalid     {} ({:.2f} %)", s.cells - s.valid, Percent(s.cells - s.valid, s.cells));
  if (format == InfoFormat::kMerl) fmt::print(", negative in the file: {}", r.negative_cells);
  if (format == InfoFormat::kRglBsdf) {
    fmt::print(", not covered by the file: {}, not finite: {}", r.uncovered_cells,
               r.not_finite_cells);
  }
  fmt::print("\n");
  for (const std::string& note : r.notes) fmt::print("  note: {}\n", TerminalSafe(note));
  if (format == InfoFormat::kRglBsdf && r.clamped_cells) {
    fmt::print("  clamped to 0 (a channel below 0, outside the sRGB gamut): {} cells\n",
               r.clamped_cells);
  }
  fmt::print("  below the horizon at the cell centre   {} ({:.2f} % of cells)\n", s.below_horizon,
             Percent(s.below_horizon, s.cells));
  fmt::print("  holes above the horizon                {} ({:.2f} % of {} above-horizon cells)\n",
             s.masked_above_horizon, Percent(s.masked_above_horizon, above), above);
  if (s.valid_below_horizon) {
    fmt::print("  note: {} valid cells lie below the horizon at their centre\n",
               s.valid_below_horizon);
  }
  const Provenance& p = t.provenance;
  if (format != InfoFormat::kMerl) {
    fmt::print("provenance  source {}, generator {}\n",
               TerminalSafe(p.source.empty() ? "-" : p.source),
               TerminalSafe(p.generator.empty() ? "-" : p.generator));
    if (!p.model.empty()) fmt::print("  model       {}\n", TerminalSafe(p.model));
    if (!p.parameters_json.empty()) {
      fmt::print("  parameters  {}\n", TerminalSafe(p.parameters_json));
    }
    fmt::print("  noise sigma {}, missing fraction {}, seed {}\n", p.noise, p.missing_fraction,
               p.seed);
  }
  fmt::print("\nf_r (1/sr) over valid cells\n  {:<3} {:>12} {:>12} {:>12}\n", "", "min", "median",
             "max");
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const ChannelSummary& cs = s.channels[c];
    fmt::print("  {:<3} {:>12.5g} {:>12.5g} {:>12.5g}\n", names[c], cs.min, cs.median, cs.max);
  }
  fmt::print(
      "\ndirectional albedo  int f_r cos(theta_o) dwo, quadrature over the half vector with "
      "trilinear\nlookups; where coverage < 1 the value covers only that share of the "
      "hemisphere\n  {:>7} {:>9} {:>9} {:>9} {:>9}\n",
      "theta_i", "R", "G", "B", "coverage");
  for (const AlbedoEstimate& a : s.albedo) {
    fmt::print("  {:>5.0f}° {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f}\n", a.theta_i * 180 / kPi,
               a.albedo[0], a.albedo[1], a.albedo[2], a.coverage);
  }
}

int RunInfo(const InfoOptions& o) {
  LoadReport report;
  const bool nbrdf = IsNbrdfInput(o.path);
  const Table t = nbrdf ? pipeline::LoadInput(o.path) : LoadTable(o.path, &report);
  const InfoFormat format = nbrdf                                    ? InfoFormat::kNbrdf
                            : report.format == TableFormat::kMerl    ? InfoFormat::kMerl
                            : report.format == TableFormat::kRglBsdf ? InfoFormat::kRglBsdf
                                                                     : InfoFormat::kHdf5;
  const TableStats s = ComputeTableStats(t);
  if (!o.json) {
    PrintText(o, t, format, report, s);
    return kExitOk;
  }
  nlohmann::ordered_json j;
  j["file"] = o.path;
  j["format"] = nbrdf ? JsonName(format) : ToString(report.format);
  j["grid"] = {{"n_theta_h", t.grid.n_theta_h},
               {"n_theta_d", t.grid.n_theta_d},
               {"n_phi_d", t.grid.n_phi_d},
               {"theta_h_mapping", ToString(t.grid.theta_h_mapping)}};
  j.update(TableStatsToJson(s));
  if (format == InfoFormat::kMerl) j["negative_in_file"] = report.negative_cells;
  if (format == InfoFormat::kRglBsdf) {
    j["not_covered_by_file"] = report.uncovered_cells;
    j["not_finite_in_file"] = report.not_finite_cells;
    j["clamped_to_zero"] = report.clamped_cells;
    j["notes"] = report.notes;
  }
  if (format != InfoFormat::kMerl) j["provenance"] = ProvenanceJson(t.provenance);
  fmt::print("{}\n", j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace));
  return kExitOk;
}

Registrar reg{"info", "Describe a table: format, grid, valid cells, value ranges, albedo",
              [](CLI::App& sub) {
                auto opts = std::make_shared<InfoOptions>();
                sub.add_option("file", opts->path,
                               "MERL .binary, brdfit .h5 or RGL .bsdf table, or nbrdf:NAME (an "
                               "NBRDF network "
                               "of ../shared/data/merl_nbrdf.zip)")
                    ->required();
                sub.add_flag("--json", opts->json, "machine-readable output");
                sub.footer(
                    "Exit codes: 0 ok, 2 bad input (the file and the problem are named).\n"
                    "The format is detected from the content, not the name.\n"
                    "Examples:\n  brdfit info gold-paint.binary\n  brdfit info t.h5 --json");
                return [opts] { return RunInfo(*opts); };
              }};

}  // namespace
}  // namespace brdfit::cli
