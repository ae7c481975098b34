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
#include "fit/rendered_environment.h"
#include "models/geometry.h"
#include "models/registry.h"

namespace brdfit {

// An approximation: RGB f_r (1/sr, no cosine) at (wi, wo) in the local frame (z = normal), both
// above the horizon. Analytic fits (ModelBrdf) and FactoredBrdf::Eval both fit this signature.
using BrdfFunction = std::function<std::array<double, 3>(const Vec3& wi, const Vec3& wo)>;

struct RenderedErrorOptions {
  int resolution = 64;  // N, in [1, 4096]
  // Angles between each light and the view direction, degrees in [0, 180) (beyond 90 the light
  // is behind the sphere and lights a crescent at its rim); 1 to
  // kRenderedMaxLights lights, one image each.
  // The defaults light the three regions of the domain (core/rendered_regions.h): front
  // (theta_d <= 40 deg), side (47.5 - 62.5) and rim (70 - 82.5, the light behind the sphere).
  std::vector<double> light_angles_deg = {0, 30, 45, 60, 70, 80, 95, 110, 125, 140, 152, 165};
  // A pixel is lit when n.l > min_cos and n.v > min_cos: the cos guard of fit/samples.h (its
  // 80-degree cut-off is not applied: the rendered sphere shows every angle).
  double min_cos = 1e-3;
  // The relative luminance error is taken where Y_m > luminance_floor * (peak Y_m of the same
  // light's image), as preview/comparison.cc's RelativeError.
  double luminance_floor = 1e-4;
  // The tone-mapped PSNR's exposure maps this percentile of the measured luminance (pooled
  // over the lit pixels of every image) to 1.
  double exposure_percentile = 99.0;
  // The image of the environment region (fit/rendered_environment.h): its own resolution and
  // directions; samples = 0 leaves it out. Not pooled into the whole metric's numbers (psnr_db,
  // the medians, the tone-mapped PSNR), which stay the directional lights'.
  EnvironmentOptions environment;
  bool operator==(const RenderedErrorOptions&) const = default;
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
  struct Masked {
    int light = 0, x = 0, y = 0;
  };
  RenderedError counts;                // resolution, lights, sphere/lit/masked pixel counts
  std::vector<Pixel> pixels;           // light after light
  std::vector<Masked> masked;          // lit pixels whose measured lookup is invalid
  std::vector<std::size_t> begin;      // light k: pixels [begin[k], begin[k + 1])
  // Light k's brightest measured pixel, Rec. 709 luminance of `measured` (0 for a light with no
  // pixel): what the luminance floor scales (luminance_floor * peak_y[k]) wherever the metric's
  // compared pixels are picked (the score, the body's pixels, the rendered polish).
  std::vector<double> peak_y;
  // Per region, the body's pixels (RenderedError::body_color_error): those compared (Y_m above
  // the floor of their light's image) at or below the region's median Y_m; empty for the rim.
  // Measured quantities only, so fixed per table.
  std::array<std::vector<std::size_t>, kRenderedRegions> body;
  // The environment's image: per pixel its measured radiance and its directions
  // env_samples[begin, end). A direction whose measured lookup is masked is left out of both
  // images (counted in env_masked_samples); a pixel left without one is left out.
  struct EnvSample {
    Vec3 wi;
    double weight = 0;  // EnvironmentSample::weight
  };
  struct EnvPixel {
    Vec3 wo;
    std::array<double, 3> measured;  // sum of f_m(wi, wo) weight over its directions
    std::size_t begin = 0, end = 0;
    int x = 0, y = 0;
  };
  std::vector<EnvPixel> env_pixels;
  std::vector<EnvSample> env_samples;
  double env_peak_y = 0;  // the environment image's brightest measured pixel, as peak_y
  std::size_t env_masked_samples = 0;
  double luminance_floor = 0, exposure_percentile = 0;
  bool Empty() const { return pixels.empty() && counts.num_lights == 0; }
};

// What a reference needs of the measured table's grid, not of its values: every
// lit pixel's directions and its measured lookup's taps (Grid::TrilinearTapsAt), light after
// light; made once for all tables of a grid (fit/prepare_cache.h). ~2 MB at the defaults.
struct RenderedPlan {
  struct Pixel {
    Vec3 wi, wo;       // local frame of the pixel's normal
    double cos_l = 0;  // n.l
    int light = 0, x = 0, y = 0;
    TrilinearTaps taps;  // of RenderedLookup(table, wi, wo)
  };
  Grid grid;
  RenderedErrorOptions options;
  RenderedError counts;  // resolution, lights and their angles, sphere pixels; nothing per table
  std::vector<Pixel> lit;
  // The environment's pixels and their directions (RenderedReference::EnvPixel).
  struct EnvSample {
    Vec3 wi;
    double weight = 0;
    TrilinearTaps taps;
  };
  struct EnvPixel {
    Vec3 wo;
    std::size_t begin = 0, end = 0;
    int x = 0, y = 0;
  };
  std::vector<EnvPixel> env_pixels;
  std::vector<EnvSample> env_samples;
  std::size_t Bytes() const;
};
// Throws std::invalid_argument on options outside the ranges above.
RenderedPlan MakeRenderedPlan(const Grid& grid, const RenderedErrorOptions& options = {});

// Throws std::invalid_argument on options outside the ranges above.
RenderedReference PrepareRenderedReference(const Table& measured,
                                           const RenderedErrorOptions& options = {});
// The same from the grid's plan, bit for bit. Throws std::invalid_argument if the plan is of
// another grid.
RenderedReference PrepareRenderedReference(const Table& measured, const RenderedPlan& plan);
// The metric of an approximation against a prepared reference; failures as below.
RenderedError ScoreRendered(const RenderedReference& reference, const BrdfFunction& approx);

// The images behind the metric (docs/accuracy.md, "Images"), one per light: N x N, row 0 at the
// top, from the same radiances ScoreRendered scores, so that they cannot disagree with it.
struct RenderedImage {
  enum class State : unsigned char {
    kOff,         // pixel centre off the sphere
    kUnlit,       // on the sphere, n.l or n.v at or below min_cos
    kMasked,      // lit, measured lookup invalid: excluded from the metric
    kBelowFloor,  // lit, Y_m at or below the luminance floor: no relative error
    kCompared,    // lit and above the floor
  };
  double light_deg = 0;
  int resolution = 0;
  std::vector<State> state;      // N * N
  std::vector<double> measured;  // 3 N^2 linear RGB radiance L_m; 0 unless lit
  std::vector<double> approx;    // 3 N^2 L_a; 0 unless lit
  // (Y_a - Y_m) / Y_m where kCompared (its magnitude is the metric's error), NaN elsewhere.
  std::vector<double> rel_error;
};
struct RenderedImages {
  RenderedError metric;               // ScoreRendered(reference, approx), identical
  std::vector<RenderedImage> lights;  // one per light; empty if the approximation is not finite
};
RenderedImages RenderImages(const RenderedReference& reference, const BrdfFunction& approx);

// The tone mapping of the sRGB PSNR, for display: OETF(clamp(exposure L, 0, 1)) with the sRGB
// OETF of IEC 61966-2-1 (RenderedError::exposure is 1 / Y_99 of the measured images).
double RenderedToneMap(double linear, double exposure);

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
// The angles RenderedLookup looks the table up at.
HalfDiffAngles RenderedLookupAngles(const Vec3& wi, const Vec3& wo);

}  // namespace brdfit
