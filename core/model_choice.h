// Which of a table's fits to recommend: the rule behind `brdfit fit --model auto` and the
// "chosen" mark of fit reports (docs/accuracy.md, "Choosing the model").
//
// Every fit is judged by its rendered-image error (fit/rendered_error.h) through one score,
//
//   S_r = min(psnr_db, 60) - 20 * median_rel_error      (dB; 1 point of median error = 0.2 dB)
//
// per region r of the domain the lights show (core/rendered_regions.h), its images pooled, the
// regions then weighted with an extra share for the worst (RenderedScoreDb below).
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
// rendered error take no part; if none has one, nothing is chosen. Fits whose body colour is
// off (BodyColorHolds below) take part only when no fit's holds: the score weighs luminance,
// and a body that lost a channel can score well where that channel is dim.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/metrics.h"
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

// S of a rendered error over the whole domain (docs/accuracy.md, "Every light"): the regions'
// scores S_r (core/rendered_regions.h) weighted by the share of what a camera sees lit from
// each region under light from every direction (kRegionWeights), and a share for the worst
// region (kWorstRegionWeight), so that no region can be given away for another:
//   S = (1 - m) sum_r a_r S_r / sum_r a_r + m min_r S_r        (over the judged regions)
// With the front region alone (a report of the front-light metric) S is its S_r, the score of
// that metric. Not finite if the numbers are not.
double RenderedScoreDb(const RenderedError& rendered);
// a_r: the share of a region in what a camera sees of a sphere lit by one directional light
// from a uniformly random direction. A light at angle a from the view lights the fraction
// (1 + cos a) / 2 of the sphere's orthographic image (half the disc, plus or minus half the
// ellipse its terminator projects to), and a is distributed as sin a da / 2, so a_r = integral over
// r of sin a (1 + cos a) / 4 da, which with u = cos a is [(u + u^2 / 2) / 2] over [cos a_hi, cos
// a_lo]: front (0 - 80 deg) 0.6557, side (80 - 125) 0.2989, rim (125 - 180) 0.0455; they sum to 1.
// An environment map weighs the regions as this does on average; a studio key light sees the front
// alone. The environment region (core/rendered_regions.h) is such a scene, judged as one image
// of the same domain: a_env = 0.07 (6.5 % of the weighted sum, and the worst region's share when
// it is the worst) held out every region best over the 100 MERL proxies of docs/accuracy.md
// ("The environment"); 0.15 and 1/3 gave up front light for side and rim, 1 gave up 2 dB.
inline constexpr double kRegionWeights[kRenderedRegions] = {0.6557, 0.2989, 0.0455, 0.07};
// m: the worst region's extra share. 0.1 over the 25-proxy study of docs/accuracy.md ("Every
// light"): 0.25 gave up 2.8 dB of front PSNR for 1.3 dB of rim; 0 let the rim drift.
inline constexpr double kWorstRegionWeight = 0.1;
// d S / d S_r for each region at this rendered error (the weights the rendered polish gives each
// region's terms, fit/rendered_polish.h); the worst region's includes m.
std::array<double, kRenderedRegions> RegionScoreWeights(const RenderedError& rendered);
// The body's colour (RenderedError::body_color_error): a fit whose body is off by more than this
// in a channel takes part in the choice only when every fit's is (a zeroed channel scores 1, a
// colour cast a user sees from about 0.25). True when within it or not computed.
inline constexpr double kBodyColorTolerance = 0.25;
bool BodyColorHolds(const RenderedError& rendered);
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
