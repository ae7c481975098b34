// A GPU render against the CPU reference renderer (preview/reference_render.h), for the parity
// tests of spheres, measured tables and meshes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/image.h"
#include "preview/reference_render.h"

namespace brdfit::preview::testing {

struct ReferenceComparison {
  double max_rel = 0;  // largest relative error over the compared pixels and channels
  long compared = 0;   // pixels compared
};

// Compares the pixels whose centre hits a surface seen at n.v >= 0.1 in the reference
// (silhouettes excluded: there a pixel's coverage, not the BRDF, decides). Reference values
// below floor_of_peak times the image peak (a lobe's tail in the float denormal range) are
// compared against that floor instead of themselves. interior_only: also skip pixels with a
// missed pixel among their 8 neighbours, and the image border (meshes' silhouettes).
inline ReferenceComparison CompareToReference(const Image& gpu, const Image& cpu,
                                              const ReferenceExtras& ex, double floor_of_peak,
                                              bool interior_only) {
  ReferenceComparison c;
  double peak = 0;
  for (float v : cpu.rgba) peak = std::max(peak, static_cast<double>(v));
  const int margin = interior_only ? 1 : 0;
  auto hit = [&](int x, int y) { return ex.hit[static_cast<std::size_t>(y) * cpu.width + x] != 0; };
  for (int y = margin; y + margin < cpu.height; ++y) {
    for (int x = margin; x + margin < cpu.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * cpu.width + x;
      if (!ex.hit[i] || ex.cos_view[i] < 0.1) continue;
      bool neighbours_hit = true;
      for (int dy = -margin; dy <= margin; ++dy) {
        for (int dx = -margin; dx <= margin; ++dx) neighbours_hit &= hit(x + dx, y + dy);
      }
      if (!neighbours_hit) continue;
      for (int ch = 0; ch < 3; ++ch) {
        const double g = gpu.At(x, y)[ch], r = cpu.At(x, y)[ch];
        const double denom = std::max(std::abs(r), floor_of_peak * peak);
        c.max_rel = std::max(c.max_rel, std::abs(g - r) / denom);
      }
      ++c.compared;
    }
  }
  return c;
}

}  // namespace brdfit::preview::testing
