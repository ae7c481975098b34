// One table factored and saved as `brdfit factor` does it (docs/factorization.md): the form the
// options name, or the forms of factor/factor_choice.h with the one the rendered metric prefers
// kept; the lower ranks met on the way scored like the result; the fit metrics; the textures
// and the sidecar (pipeline/factor_sidecar.h) written. The factor command and Python's
// callers print what it returns; the factorization candidate of `brdfit fit`
// (pipeline/factor_candidate.h) writes its sidecar with WriteFactorFiles too.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/factor_form.h"
#include "core/metrics.h"
#include "core/table.h"
#include "factor/factor.h"
#include "factor/factor_system.h"
#include "fit/samples.h"
#include "io/factor_io.h"
#include "pipeline/factor_with_choice.h"

namespace brdfit::pipeline {

struct FactorTableRequest {
  std::string file;      // the input as given (the sidecar's source.file)
  std::string material;  // its material key (pipeline/material_keys.h)
  std::string stem;      // the outputs' stem, a safe file name (core/file_stem.h)
  FactorOptions options;
  bool auto_form = true;         // try the forms and keep the best (options: their settings)
  SampleOptions metric_samples;  // the fit metrics' cut-off and weighting
  std::filesystem::path out_dir;
  bool timings = true;                 // false: nothing run-dependent in the files
  FactorSystemCache* cache = nullptr;  // systems reused from table to table
  bool last = true;                    // the run's last table: the systems go once it is solved
};

// A lower rank met on the way to the result (or the result), scored like it.
struct RankScore {
  int rank = 0;
  RenderedError rendered;
  FactorCost cost;
};

// A candidate form of the choice and its score.
struct FormScore {
  std::string name;  // factor/factor_choice.h kAutoFactorCandidates
  RenderedError rendered;
  bool chosen = false;
};

struct FactoredTable {
  Factorization result;
  RenderedError rendered;        // the result's rendered-image metric (docs/accuracy.md)
  FitMetrics metrics;            // its fit metrics on the request's metric set
  double ln_rmse = 0;            // factor/factor_metrics.h FactorLnRatioRmse
  std::vector<FormScore> forms;  // with auto_form: every form tried
  std::vector<RankScore> ranks;  // when the result has lower ranks: each, then the result
  FactorPaths paths;             // the files written
};

// Throws InputError naming the file for a table the factorization cannot use, OutputError for
// files that cannot be written, and std::runtime_error for a failed solve.
FactoredTable FactorTable(const Table& table, const FactorTableRequest& request);

// Writes r's textures and sidecar into folder/stem.*: the sidecar's "material", "source",
// "metrics" (ln_rmse: factor/factor_metrics.h FactorLnRatioRmse), "provenance" and, when not
// null, "choice" and "ranks"
// (pipeline/factor_sidecar.h). Both writers of factorizations call it, so that a table gives the
// same sidecar from `brdfit factor` and from `brdfit fit --model factorization`.
FactorPaths WriteFactorFiles(const Factorization& r, const Table& table,
                             const std::filesystem::path& folder, const std::string& stem,
                             const std::string& material, const std::string& file,
                             const FitMetrics& metrics, const RenderedError& rendered,
                             double ln_rmse, const nlohmann::json& choice,
                             const nlohmann::json& ranks, bool timings);

}  // namespace brdfit::pipeline
