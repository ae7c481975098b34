// Which factored form to keep: `brdfit factor`'s default tries a few forms of one table and
// keeps the one the rendered-image metric prefers, by the rule `brdfit fit --model auto` uses
// (core/model_choice.h, docs/accuracy.md "Choosing the model"):
//   S = psnr_db - 20 * median_rel_error;
// among the candidates whose S is within `tolerance_db` of the best, the one with the least
// texture memory (then the fewest fetches per light, then the higher S): more textures must
// buy a visible improvement. The candidates and the study that chose them:
// docs/factorization.md, "Choosing the form".
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/factor_form.h"
#include "core/result.h"
#include "factor/factor.h"

namespace brdfit {

struct FactorCandidate {
  const char* name;  // as bench_factor_accuracy's forms: "mccool+d+r2+lr"
  FactorParam param;
  bool diffuse, refine;
  int rank;
  RefineLoss loss;
};

// The candidates of the default, in the order they are tried (one parameterization after the
// other, so that a caller can drop a system it will not need again). Chosen over the 100 MERL
// proxies (docs/factorization.md §14): with these four, the kept form beats the best single
// analytic lobe on 95 materials (rendered score), mean S 41.7 dB. constexpr: usable during
// static initialization (bench_factor registers its cases from it).
inline constexpr std::array<FactorCandidate, 4> kAutoFactorCandidates{{
    {"mccool+ref", FactorParam::kMcCool, false, true, 1, RefineLoss::kRel},
    {"mccool+r2", FactorParam::kMcCool, false, true, 2, RefineLoss::kRel},
    {"mccool+d+r2+lr", FactorParam::kMcCool, true, true, 2, RefineLoss::kLogRatio},
    {"halfdiff", FactorParam::kHalfDiff, false, false, 1, RefineLoss::kRel},
}};

// `base` (resolution, lambda, weighting, angle cut-off, iterations) with a candidate's form.
FactorOptions CandidateOptions(const FactorOptions& base, const FactorCandidate& c);

struct FactorScore {
  RenderedError rendered;
  FactorCost cost;
};

struct FactorChoice {
  std::size_t index = 0;
  double score_db = 0;
  std::string reason;
};

// nullopt if no candidate has a rendered error.
std::optional<FactorChoice> ChooseFactorization(const std::vector<FactorScore>& scores,
                                                double tolerance_db = 0.5);

}  // namespace brdfit
