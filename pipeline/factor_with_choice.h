// `brdfit factor`'s default: try the candidate forms of factor/factor_choice.h on one table and
// keep the one the rendered-image metric prefers (docs/factorization.md §14). Shared by the
// factor command and the preview's factored materials with "form": "auto" (render --compare's
// factored panel), so that both show the same factorization.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "factor/factor.h"
#include "factor/factor_choice.h"

namespace brdfit::pipeline {

struct FactorWithChoice {
  Factorization kept;                      // the chosen candidate
  RenderedError rendered;                  // its rendered metric (factor_metrics.h)
  std::vector<FactorScore> scores;         // every candidate's, in kAutoFactorCandidates order
  std::vector<double> seconds;             // every candidate's Factor() time
  std::size_t chosen = 0;                  // index into kAutoFactorCandidates
  std::string reason;                      // why it was kept
};

// `base`: resolution, lambda, weighting, angle cut-off, refinement iterations; each candidate
// sets the form. With `drop_systems`, a parameterization's cached system is dropped once its
// candidates are done (the last table of a run: peak memory). Throws as Factor().
FactorWithChoice FactorChoosingForm(const Table& table, const FactorOptions& base,
                                    FactorSystemCache* cache, bool drop_systems);

// The rendered score of one candidate or rank for a sidecar: score_db (S), psnr_db,
// median_rel_error; null numbers where the metric failed.
nlohmann::json ScoreJson(const RenderedError& e);

// The sidecar's "choice" member (docs/formats.md): rule, chosen, reason, candidates.
nlohmann::json ChoiceJson(const FactorWithChoice& c, bool include_timings);

}  // namespace brdfit::pipeline
