// The comparison image: the scene drawn once per panel material — measured | fitted model(s) |
// factored | false-colour relative error of the first fit — tiled and labelled.
#pragma once

#include "preview/explain.h"
#include "core/image.h"
#include "preview/material.h"
#include "preview/renderer.h"
#include "preview/scene.h"

namespace brdfit::preview {

struct ComparisonStats {
  double median_error = 0, p95_error = 0, max_error = 0;  // relative, over lit pixels
  long pixels = 0;
};

// Display-referred comparison of size width x height. A factored panel whose material is not
// in `materials` (factorization unavailable) is drawn as a labelled "not available" panel.
Image RenderComparison(Renderer& renderer, const Scene& scene, const MaterialSet& materials,
                       int width, int height, ExplainLog* log, ComparisonStats* stats);

// Relative error |Y_f - Y_m| / Y_m of luminances (Rec. 709 weights), per pixel; negative where
// the measurement is not lit enough to compare (Y_m <= 1e-4 of its peak) or not covered.
std::vector<double> RelativeError(const Image& fitted, const Image& measured);

// False colour for a relative error: log10(e) in [-3, 0] (0.1 % to 100 %) through a five-stop
// ramp; display-referred RGB.
std::array<float, 3> ErrorColour(double e);

}  // namespace brdfit::preview
