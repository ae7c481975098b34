// Peaks narrower than the rendered judge's pixels (docs/accuracy.md, "Narrow peaks").
//
// The judge (fit/rendered_error.h) samples each image at N x N pixel centres. A lobe narrower
// than a pixel renders as a spike that one pixel lattice can miss entirely and another hits:
// a near-delta second GGX lobe (alpha ~ 1e-4, weight ~ 1) scores ~30 dB at 64 x 64 and below
// -10 dB at an odd resolution, where a pixel centre falls on the front light's mirror
// highlight. In a renderer it is a firefly. A fit with such a peak is scored at a second,
// offset pixel lattice as well and keeps the worse of the two scores, so it is chosen only if
// it renders well at both.
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "fit/rendered_error.h"
#include "models/registry.h"

namespace brdfit {

// The second lattice: odd, so that a pixel centre falls on the sphere's centre (the mirror
// highlight of the light along the view, which the even default's lattice straddles), and
// coprime with 64 so that the other lights' highlights fall at other offsets too.
inline constexpr int kRenderedCheckResolution = 47;

// A peak is narrow when the fit's luminance at theta_h = theta_d = 0 is more than this times
// its luminance one pixel away (theta_h = 2 / N rad, theta_d = 0: the sphere's radius is N / 2
// pixels, so one pixel at its centre turns the normal by 2 / N rad). For one GGX lobe
// (Walter et al. 2007, Eqs. 20 and 33) the ratio is cos^6 t (1 + tan^2 t / alpha^2)^2 / G(t),
// which exceeds 4 for alpha below ~tan t (0.031 at N = 64); a diffuse body under the lobe lowers
// the ratio, as it lowers the spike's share of the pixel.
inline constexpr double kNarrowPeakRatio = 4.0;

// The ratio above for a model at its parameters, Rec. 709 luminance of f_r. Infinity when f_r
// one pixel away is 0 and at the peak is not; 1 when both are 0.
double PeakSharpness(const ModelInfo& model, const std::vector<double>& params, int resolution);

// What CheckNarrowPeak found.
enum class NarrowPeak {
  kNone,     // no narrow peak (or nothing to check)
  kKept,     // a narrow peak that the second lattice scores no worse
  kLowered,  // a narrow peak, now scored by the second lattice's worse image
};

// Scores a fit of a narrow peak (PeakSharpness > kNarrowPeakRatio at the judge's resolution) at
// the second lattice `check` too: when that scores lower (core/model_choice.h RenderedScoreDb)
// or fails, fit->metrics.rendered becomes the second lattice's and fit->message says so. Does
// nothing to a failed fit, one without a rendered error, or when `check` is empty.
NarrowPeak CheckNarrowPeak(const ModelInfo& model, const RenderedReference& check, FitResult* fit);

}  // namespace brdfit
