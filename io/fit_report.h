// Fit reports: every fit of `brdfit fit` in one HDF5 file (docs/formats.md, "Fit reports",
// format "brdfit-fits" v1), and the fitted parameters as JSON.
//
//   /                       attrs format = "brdfit-fits", format_version = 1,
//                           metrics_definition (how the metrics are computed)
//   /entries/NNNNN          one group per fit, ordered by (source, model, options)
//       attrs  source, material, model, options (canonical JSON, fit/options.h), status
//              (converged | no_convergence | failed), message, termination, iterations,
//              starts, init_cost, final_cost, fit_samples, fit_cells
//       params       float64 [P]   attr names: the qualified parameter names, in order
//       at_bound     uint8   [P]   1 where a parameter ended on a bound
//       metrics      group, attrs ok, problem, the error metrics (core/metrics.h
//                    kErrorMetrics), cells, total_weight, weighting, cutoff_deg
//       metrics/worst  group, attrs cell, theta_h, theta_d, phi_d (rad), theta_i_deg,
//                    theta_o_deg, log_error; datasets measured [3], predicted [3] (1/sr)
//       samples      group, attrs cells, valid, nonfinite, negative, beyond_cutoff, eligible,
//                    selected (fit/samples.h SampleCounts)
//       factorization  group, only in an entry of model "factorization" (a factorization among
//                    the candidates, pipeline/batch_fit.h): attrs form, sidecar (its
//                    .factor.json, as written), texture_bytes, values (the texture values: its
//                    parameter count for the choice)
//       timing       group (absent when written without timings), attrs load_ms,
//                    prepare_ms, init_ms, solve_ms, metrics_ms (wall), init_cpu_ms,
//                    solve_cpu_ms, metrics_cpu_ms (thread CPU time)
//
// Nothing else in the file depends on the run: no timestamps (object time tracking is off), so
// the same entries written without timings give byte-identical files. No NaN or Inf is ever
// written: FitResult holds none (core/result.h), and the writer refuses one (std::logic_error).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/result.h"

namespace brdfit {

inline constexpr const char* kFitReportFormat = "brdfit-fits";
inline constexpr int kFitReportVersion = 1;
// The version of the fitted parameters' JSON ("brdfit-fit-params", FitParamsJson).
inline constexpr int kFitParamsJsonVersion = 1;

// The model name of an entry that is a factorization (McCool et al. 2001; factor/factor.h)
// scored and chosen among the fits: it has no parameters, its textures are files.
inline constexpr const char* kFactorizationModel = "factorization";
inline bool IsFactorizationModel(std::string_view model) {
  return model == kFactorizationModel;
}

// What a factorization entry holds besides its metrics.
struct FactorizationRef {
  std::string form;     // the chosen form's label, e.g. "mccool r2" (factor/factor_form.h)
  std::string sidecar;  // its .factor.json (io/factor_io.h), as written: relative to the
                        // working directory of the run when the report path was
  std::uint64_t texture_bytes = 0;  // GPU memory of its textures (factor/factor_form.h)
  std::uint64_t values = 0;         // texture values and the diffuse value: its parameters
  bool operator==(const FactorizationRef&) const = default;
};

struct FitReportEntry {
  std::string source;    // input file as given
  std::string material;  // its stem, e.g. "gold-paint"
  std::string options;   // OptionsJson of the fit (fit/options.h)
  FitResult result;
  // The fit recommended for its source among the report's fits of that source
  // (core/model_choice.h; set by pipeline/batch_fit.h before writing), and why.
  bool chosen = false;
  std::string choice;  // the reason, for the chosen entry; empty otherwise
  // The table's content hash (core/provenance.h TableContentHash); empty in reports written
  // before brdfit 0.1.0 recorded it.
  std::string source_hash;
  bool timed = false;  // set by ReadFitReport: the entry had a /timing group
  // Set when result.model is kFactorizationModel, but for a failed factorization that
  // wrote no textures.
  std::optional<FactorizationRef> factorization;
  // The number of parameters the model choice weighs (core/model_choice.h): the fit's, or a
  // factorization's texture values.
  std::size_t ParameterCount() const {
    return factorization ? static_cast<std::size_t>(factorization->values) : result.params.size();
  }
};

// An entry for a factorization among the candidates, of model kFactorizationModel, not yet
// made (FitResult's defaults: failed, no parameters; the caller fills its result and
// FactorizationRef).
FitReportEntry NewFactorizationEntry(std::string source, std::string material, std::string options,
                                     std::string source_hash);

// Sorts entries by (source, model, options): the order of a report does not depend on the order
// in which fits finished.
void SortEntries(std::vector<FitReportEntry>& entries);

// Writes atomically, with the run's provenance (core/provenance.h) as root attributes:
// brdfit_version always; command_line and created unless include_timings is false, which also
// leaves out every /timing group (byte-identical reruns).
void WriteFitReport(std::vector<FitReportEntry> entries, const std::filesystem::path& path,
                    bool include_timings = true);

// Throws InputError naming the file and the problem.
std::vector<FitReportEntry> ReadFitReport(const std::filesystem::path& path);

// The first two entries chosen for one material (their indices), or nullopt. A report chooses
// at most one fit per material (pipeline::MarkChosenFits); with two, which one an export takes
// would depend on their order, so every reader of fits refuses such a file.
std::optional<std::pair<std::size_t, std::size_t>> TwoChosenOfOneMaterial(
    const std::vector<FitReportEntry>& entries);
// The brdfit version that wrote the report (its root attribute brdfit_version; "" in a report
// without one). Throws InputError as ReadFitReport.
std::string ReadFitReportWriterVersion(const std::filesystem::path& path);

// {"format": "brdfit-fit-params", "format_version": 1, "fits": [{"source", "material", "model",
//  "status", "message", "params": {"name": value, ...}, "metrics": {the error metrics
//  (core/metrics.h kErrorMetrics), "weighting", "cutoff_deg", "rendered": {kRenderedSummary's
//  numbers, "ok", "problem" if not ok, ...} (when computed, i.e. not for
//  a failed fit; io/metrics_json.h, docs/accuracy.md)}, "factorization": {"form", "sidecar",
//  "texture_bytes", "values"} (factorization entries only), "chosen": bool, "choice": "why" (chosen
//  fits only), "options": {...}, "source_hash" (when known)},
//  ...], "provenance": {"brdfit_version", "command_line", "created" (the last two only with
//  run_details)}} in report order, no timings: deterministic without run_details.
std::string FitParamsJson(std::vector<FitReportEntry> entries, bool run_details = false);

}  // namespace brdfit
