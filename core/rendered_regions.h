// The regions of the rendered-image metric's domain (docs/accuracy.md, "Every light"). Under a
// directional light at angle a from the view, every pixel of the sphere is seen at the
// half-angle theta_d = a / 2 (wi and wo are the light and the view, whatever the normal), so a
// light's angle says which part of an isotropic BRDF's domain its image shows:
//   front  a <= 80 deg          theta_d <= 40 deg: the light near the camera, the highlight
//                               seen head-on (the studio's key light)
//   side   80 < a <= 125 deg    theta_d 40 - 62.5 deg: light from the side
//   rim    a > 125 deg          theta_d > 62.5 deg: light from behind, a crescent at the rim;
//                               grazing Fresnel, sheen and retro-reflection live here
// and a fourth region, the environment: the sphere lit by a sky and a sun from every direction
// at once (fit/rendered_environment.h), theta_d over its whole range in one image, weighted as a
// scene weighs it.
// The front is what the metric judged alone before (six lights at 0 - 80 deg); side and rim
// split the rest of theta_d's range, each lit by three lights (fit/rendered_error.h).
//
// Each region's numbers pool its lights' images (RenderedError::regions), as the whole metric
// pools every image: the front region's S is the metric's S before it had regions.
#pragma once

#include <array>

#include "core/metrics.h"

namespace brdfit {

enum class LightRegion : int { kFront = 0, kSide = 1, kRim = 2, kEnvironment = 3 };
inline constexpr int kLightRegions = kRenderedRegions;

// The region of a directional light: front, side or rim (never the environment).
LightRegion RegionOfLight(double light_deg);
const char* RegionName(LightRegion region);  // "front", "side", "rim", "environment"

struct RegionError {
  int lights = 0;  // lights of the metric in this region (0: not judged)
  double psnr_db = 0;
  double median_rel_error = 0;
  double score_db = 0;  // S of the region: min(psnr, 60) - 20 median (core/model_choice.h)
};

// The regions of a rendered error; all zero when it is not ok. From RenderedError::regions, or
// where a file did not hold them, the means of the region's lights' numbers.
std::array<RegionError, kLightRegions> RenderedRegions(const RenderedError& rendered);
// The same from the numbers held, whatever `ok` says (the score of core/model_choice.h; its
// callers check ok). All zero when neither regions nor lights are held.
std::array<RegionError, kLightRegions> RegionsOfNumbers(const RenderedError& rendered);

}  // namespace brdfit
