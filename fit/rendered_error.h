// The rendered-image metric (docs/accuracy.md, "Rendered-image metric"): what a fit looks like
// rendered, where log_rmse (Löw et al. 2012 E2) is blind to dark parts (ln(1 + x) ~ x).
//
// Scene: a unit sphere seen orthographically along +z (v = (0, 0, 1)), N x N pixel centres over
// its bounding square, one image per directional light of unit irradiance at normal incidence,
// the lights in the x-z plane at the given angles from v. Per pixel L = f(wi, wo) max(0, n.l)
// with wi = l, wo = v in the Duff et al. 2017 frame of n. The measured images use
// Table::LookupTrilinear (as preview/reference_render.cc; RenderedLookup below); masked lookups
// are excluded and counted. Double precision, one thread, deterministic; no GL and no file I/O.
#pragma once

#include <array>
#include <functional>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/metrics.h"
#include "core/table.h"
#include "models/geometry.h"
#include "models/registry.h"

namespace brdfit {

// An approximation: RGB f_r (1/sr, no cosine) at (wi, wo) in the local frame (z = normal), both
// above the horizon. Analytic fits (ModelBrdf) and FactoredBrdf::Eval both fit this signature.
using BrdfFunction = std::function<std::array<double, 3>(const Vec3& wi, const Vec3& wo)>;

struct RenderedErrorOptions {
  int resolution = 64;  // N, in [1, 4096]
  // Angles between each light and the view direction, degrees in [0, 90); 1 to
  // kRenderedMaxLights lights, one image each.
  std::vector<double> light_angles_deg = {0, 30, 45, 60, 70, 80};
  // A pixel is lit when n.l > min_cos and n.v > min_cos: the cos guard of fit/samples.h (its
  // 80-degree cut-off is not applied: the rendered sphere shows every angle).
  double min_cos = 1e-3;
  // The relative luminance error is taken where Y_m > luminance_floor * (peak Y_m of the same
  // light's image), as preview/comparison.cc's RelativeError.
  double luminance_floor = 1e-4;
  // The tone-mapped PSNR's exposure maps this percentile of the measured luminance (pooled
  // over the lit pixels of every image) to 1.
  double exposure_percentile = 99.0;
};

// The measured side of the metric, computed once per table: the lit pixels' directions and
// measured radiances (masked lookups counted and left out). Scoring an approximation then
// costs one evaluation per lit pixel (~20,000 at the defaults), so every fit of a table can be
// scored without the table (fit/fitter.h keeps one in PreparedTable).
struct RenderedReference {
  struct Pixel {
    Vec3 wi, wo;                    // local frame of the pixel's normal
    double cos_l = 0;               // n.l
    std::array<double, 3> measured; // L_m = f_m(wi, wo) n.l
    int x = 0, y = 0;
  };
  RenderedError counts;                // resolution, lights, sphere/lit/masked pixel counts
  std::vector<Pixel> pixels;           // light after light
  std::vector<std::size_t> begin;      // light k: pixels [begin[k], begin[k + 1])
  double luminance_floor = 0, exposure_percentile = 0;
  bool Empty() const { return pixels.empty() && counts.num_lights == 0; }
};

// Throws std::invalid_argument on options outside the ranges above.
RenderedReference PrepareRenderedReference(const Table& measured,
                                           const RenderedErrorOptions& options = {});
// The metric of an approximation against a prepared reference; failures as below.
RenderedError ScoreRendered(const RenderedReference& reference, const BrdfFunction& approx);

// PrepareRenderedReference + ScoreRendered. Throws std::invalid_argument on options outside the
// ranges above. Failures of the inputs (no
// lit pixel, black measurement, non-finite approximation) give ok = false and a problem.
RenderedError ComputeRenderedError(const Table& measured, const BrdfFunction& approx,
                                   const RenderedErrorOptions& options = {});

// A registered model at fixed parameters as an approximation (copies the parameters).
BrdfFunction ModelBrdf(const ModelInfo& model, std::vector<double> params);

// A table as an approximation, through the measured images' own lookup (RenderedLookup): a
// table compared with itself gives identical images. Masked lookups give NaN, so that a hole in
// the approximation fails the metric (ok = false) instead of being scored as black. The table
// must outlive the function.
BrdfFunction TableBrdf(const Table& table);

// The measured images' lookup: Table::LookupTrilinear at ToHalfDiff(wi, wo), with phi_d = 0
// where theta_d < 1e-6 rad. There phi_d is undefined (ToHalfDiff returns 0 at exact
// retro-reflection) and what ToHalfDiff returns is rounding noise (theta_d ~ 1.5e-8 for wi == wo
// up to rounding: every pixel of the 0-degree light), yet the trilinear lookup between the
// cells of the theta_d = 0 ring still depends on it.
std::optional<std::array<double, 3>> RenderedLookup(const Table& table, const Vec3& wi,
                                                    const Vec3& wo);

}  // namespace brdfit
