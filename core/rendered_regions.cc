#include "core/rendered_regions.h"

#include <algorithm>

#include "core/model_choice.h"

namespace brdfit {

LightRegion RegionOfLight(double light_deg) {
  if (light_deg <= 80) return LightRegion::kFront;
  if (light_deg <= 125) return LightRegion::kSide;
  return LightRegion::kRim;
}

const char* RegionName(LightRegion region) {
  return kRenderedRegionNames[static_cast<int>(region)];
}

std::array<RegionError, kLightRegions> RenderedRegions(const RenderedError& rendered) {
  return rendered.ok ? RegionsOfNumbers(rendered) : std::array<RegionError, kLightRegions>{};
}

std::array<RegionError, kLightRegions> RegionsOfNumbers(const RenderedError& rendered) {
  std::array<RegionError, kLightRegions> out{};
  bool pooled = false;
  for (const RenderedRegionError& r : rendered.regions) pooled = pooled || r.lights > 0;
  if (pooled) {
    for (int r = 0; r < kLightRegions; ++r) {
      const RenderedRegionError& in = rendered.regions[static_cast<std::size_t>(r)];
      RegionError& o = out[static_cast<std::size_t>(r)];
      o.lights = in.lights;
      o.psnr_db = in.psnr_db;
      o.median_rel_error = in.median_rel_error;
    }
  } else {
    for (int k = 0; k < rendered.num_lights && k < kRenderedMaxLights; ++k) {
      const RenderedLightError& l = rendered.lights[static_cast<std::size_t>(k)];
      RegionError& r = out[static_cast<std::size_t>(RegionOfLight(l.light_deg))];
      ++r.lights;
      r.psnr_db += l.psnr_db;
      r.median_rel_error += l.median_rel_error;
    }
    for (RegionError& r : out) {
      if (r.lights == 0) continue;
      r.psnr_db /= r.lights;
      r.median_rel_error /= r.lights;
    }
  }
  for (RegionError& r : out) {
    if (r.lights > 0) r.score_db = std::min(r.psnr_db, kScorePsnrCapDb) - 20.0 * r.median_rel_error;
  }
  return out;
}

}  // namespace brdfit
