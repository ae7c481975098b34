// Which of a table's fits to recommend: the rule behind `brdfit fit --model auto` and the
// "chosen" mark of fit reports (docs/accuracy.md, "Choosing the model").
//
// Every fit is judged by its rendered-image error (fit/rendered_error.h) through one score,
//
//   S = min(psnr_db, 60) - 20 * median_rel_error        (dB; 1 point of median error = 0.2 dB)
//
// A PSNR beyond 60 dB (an RMS error below 1/1000 of the peak, under the RMS error of 8-bit
// quantization, 58.9 dB) counts as 60: nothing a display shows tells such fits apart, and on a
// coarse table a fit can pass the measured images' own interpolation floor only by fitting that
// interpolation (a 30 x 30 x 60 table of lambert+ggx-f0: the exact model renders at 67 dB, a
// polished lambert+ggx+ggx at 73 dB; tests/pipeline/test_model_auto.cc). Then the median error
// and the parameter count decide.
//
// which weighs the two things a render shows: the linear PSNR, dominated by the highlight's
// absolute error, and the median relative luminance error, dominated by the body. (A fit
// (1 + s) times the measurement has PSNR = const - 20 log10 s and median error s: halving a
// uniform 10 % error gains 6 dB of PSNR and 1 dB through the median term.)
//
// The chosen fit is the one with the fewest parameters among those whose S is within
// `tolerance_db` of the best S (ties: the higher S, then the name): a model with more
// parameters must buy a visible improvement to be chosen. Fits that failed or have no
// rendered error take no part; if none has one, nothing is chosen.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

namespace brdfit {

inline constexpr double kScorePsnrCapDb = 60.0;

struct ModelChoiceOptions {
  double tolerance_db = 0.5;
};

struct ModelChoice {
  std::size_t index = 0;  // into the fits given
  double score_db = 0;    // S of the chosen fit
  std::string reason;     // one sentence: why it won, against the best-scoring fit
};

// S of a rendered error (not finite if the numbers are not).
double RenderedScoreDb(const RenderedError& rendered);
// S of one fit, or nullopt when it failed or has no rendered error.
std::optional<double> RenderedScoreDb(const FitResult& fit);

// One candidate of the choice: a fit, or a factorization scored as one (its FitResult holds the
// metrics, its parameters are its texture values: pipeline/batch_fit.h).
struct ChoiceCandidate {
  const FitResult* fit = nullptr;
  std::size_t parameters = 0;  // what "fewest parameters" counts
  std::string name;            // in the reason: the model, or the factorization's form
};

std::optional<ModelChoice> ChooseCandidate(const std::vector<ChoiceCandidate>& candidates,
                                           const ModelChoiceOptions& options = {});
// The same over fits: each counts its own parameters and is named by its model.
std::optional<ModelChoice> ChooseFit(const std::vector<const FitResult*>& fits,
                                     const ModelChoiceOptions& options = {});

}  // namespace brdfit
