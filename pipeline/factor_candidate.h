// A factorization as a candidate of `brdfit fit` (the pseudo-model "factorization" of
// `--model`; docs/accuracy.md, "Factorizations among the candidates"): the table factored
// as `brdfit factor` does by default (the forms of factor/factor_choice.h, the one the rendered
// metric prefers kept), its textures and sidecar written into a folder beside the fit report,
// and a fit report entry (io/fit_report.h NewFactorizationEntry) that carries its metrics
// — the same fit metrics and rendered-image metric as every fit of the table — so that the
// model choice (core/model_choice.h) weighs it against the analytic fits, its texture values
// counted as its parameters.
#pragma once

#include <filesystem>
#include <string>

#include "core/table.h"
#include "factor/factor_system.h"
#include "fit/samples.h"
#include "io/fit_report.h"

namespace brdfit::pipeline {

// The folder a fit report's factorizations are written to: "fits.h5" -> "fits.factors".
std::filesystem::path FactorizationFolder(const std::filesystem::path& report);

// The entry's options (its identity for resuming, io/fit_report.h): the factorization settings
// of `brdfit factor`'s default and the metric set's cut-off and weighting.
std::string FactorizationOptionsJson(const SampleOptions& samples);

struct FactorizationJob {
  const Table* table = nullptr;
  std::string source;            // the input as given
  std::string material;          // its material key (pipeline/material_keys.h): the files' stem
  std::string source_hash;       // core/provenance.h TableContentHash
  SampleOptions samples;         // the metric set's options, as the fits of the table use
  std::filesystem::path folder;  // FactorizationFolder(report)
  bool timings = true;           // false: the sidecar has nothing run-dependent
  // Factored systems reused from table to table (factor/factor_system.h); `last` drops them
  // once this table's candidates are done (peak memory).
  FactorSystemCache* cache = nullptr;
  bool last = true;
};

// Factors, scores, writes the textures (atomically, io/factor_io.h) and returns the entry.
// A solver failure or files that cannot be written make a failed entry (with no
// FactorizationRef) that says why; it never throws for either.
FitReportEntry FactorizationEntry(const FactorizationJob& job);

}  // namespace brdfit::pipeline
