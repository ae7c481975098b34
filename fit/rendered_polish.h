// The rendered polish: a fit's last stage, Levenberg-Marquardt on the rendered-image metric's own
// pixels (fit/rendered_error.h, docs/accuracy.md "The rendered polish"). The table's loss fits
// every cell alike; the metric judges what a render shows — the highlight's absolute error (PSNR)
// and the body's relative error (median) — and the polish moves the parameters to what it judges.
//
// The score S (core/model_choice.h) weighs the regions' scores S_r = PSNR_r - 20 median_r
// (core/rendered_regions.h); it is not a sum of squares. Each round makes one that agrees with
// it to first order at the current parameters p0 (iteratively reweighted least squares, Holland
// & Welsch 1977), with w_r = d S / d S_r at p0 (RegionScoreWeights):
//   linear terms, per region r: w_r (10 / ln 10) SSE_r(p) / SSE_r(p0)
//                                             -- d PSNR_r = -(10 / ln 10) d SSE_r / SSE_r
//   luminance terms: sum_{i in r} w_r W / (n_r max(|e_i(p0)|, e_min))
//                    ln^2((Y_i + delta_i) / (Y_m,i + delta_i))
//                    ~ w_r W mean |e_i|, an L1 surrogate of W times region r's median error
// and runs a few LM iterations on it. The parameters kept are the best by S itself, the
// starting point included: the polish never lowers the score it is judged by.
#pragma once

#include <vector>

#include "core/metrics.h"
#include "fit/model_ops.h"
#include "fit/rendered_error.h"

namespace brdfit::internal {

struct RenderedPolishOptions {
  // Reweightings: at least two, at most `rounds`; after the second, a round that raises S by less
  // than min_round_gain_db ends the polish (S is reported to 0.01 dB). Up to 4 with the rule, not
  // a fixed 2: over the 100 MERL proxies held-out S +0.31 dB (55 materials better by > 0.1 dB,
  // none worse), 3-10 % more time per lambert+ggx command (docs/accuracy.md, "How many rounds").
  int rounds = 4;
  double min_round_gain_db = 0.01;
  // LM iterations per round, over the active set's rounds (fit/bounded_lm.h). 10, not 6: with
  // the active set an iteration costs one Jacobian; over the 100 MERL proxies the active set with
  // 10 raised the chosen fits' held-out S from 43.01 to 43.29 dB (docs/accuracy.md, "The polish's
  // active set").
  int max_iterations = 10;
  double function_tolerance = 1e-4;  // a round ends at this relative change of its cost
  double median_weight = 40;  // W (the score's own weight is 20; 40 trades 0.1 dB of S for
                              // a lower median error, docs/accuracy.md)
  double min_error = 0.02;    // e_min
  double delta_fraction = 1e-3;  // delta_i = this x the peak measured luminance of i's light
  // Polish on every k-th lit pixel of each light; S is always scored on all of them. 2 costs
  // half of 1 and scores the same on lights the polish never saw (docs/accuracy.md).
  int pixel_stride = 2;
  int threads = 1;
};

struct RenderedPolishOutcome {
  bool ran = false;       // the reference had pixels and the start was finite
  bool improved = false;  // x changed (S rose)
  int iterations = 0;
  std::vector<double> round_scores;  // S after each round run, dB (NaN where the metric failed)
  double score_before = 0, score_after = 0;  // S, dB
  RenderedError rendered;  // the rendered metric of the x returned (ok when ran)
};

// x: the fit's parameters in optimization space (fit/param_layout.h), updated in place when
// the polish improves S; within the layout's bounds.
RenderedPolishOutcome PolishOnRendered(const ModelOps& ops, const RenderedReference& reference,
                                       const RenderedPolishOptions& options,
                                       std::vector<double>& x);

}  // namespace brdfit::internal
