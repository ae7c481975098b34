// Fit metrics: computed for every fit on the same sample set (all valid cells inside the
// cut-off, whatever the fit's loss or budget), so that fits are comparable. Also used by the
// factorization: any predictor that yields RGB per observation can be scored.
//
// With w the cell weight (bin measure, fit/bin_measure.h), c = cos theta_i, f predicted and
// m measured f_r (1/sr), sums over cells and the three channels:
//   log_rmse  = sqrt( sum w (ln(1 + f c) - ln(1 + m c))^2 / (3 sum w) )
//               Löw, Kronander, Ynnerman, Unger 2012, "BRDF Models for Accurate and
//               Efficient Rendering of Glossy Surfaces" (TOG 31(1)), metric E2, with the solid
//               angle measure of the cells in place of its sin theta_i weight.
//   cbrt_rmse = sqrt( sum w (cbrt(f c) - cbrt(m c))^2 / (3 sum w) )
//               Fores, Ferwerda, Gu 2012, "Toward a Perceptually Based Metric for BRDF
//               Modeling" (CIC 20); applied to f cos theta_i like E2. The cube root is the
//               guarded one of fit/loss.h (differs from cbrt only for |f c| < 1e-5).
//   rel_l2    = sqrt( sum w c^2 (f - m)^2 / sum w c^2 m^2 )
//               cosine-weighted L2 (Ngan, Durand, Matusik 2005, "Experimental Analysis of BRDF
//               Models", EGSR), relative to the measured norm.
//   worst     = the cell with the largest |ln(1 + f c) - ln(1 + m c)| over channels (unweighted).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>

#include "models/geometry.h"

namespace brdfit {

struct WorstCell {
  std::uint32_t cell = 0;  // table index
  HalfDiffAngles angles;   // cell centre
  double theta_i_deg = 0, theta_o_deg = 0;
  std::array<double, 3> measured{}, predicted{};
  double log_error = 0;  // max over channels of |ln(1 + f c) - ln(1 + m c)|
};

// The rendered-image metric (fit/rendered_error.h; definitions in docs/accuracy.md, "Rendered-image
// metric"): a unit sphere seen orthographically along +z under one directional light per image,
// the measured table against an approximation. Plain data, every number finite (when the
// metric cannot be computed: ok = false, a problem, zeros).
inline constexpr int kRenderedMaxLights = 16;
// PSNR of identical images (MSE = 0) and any PSNR above it are reported as this cap (dB).
inline constexpr double kRenderedPsnrCapDb = 200.0;

struct RenderedLightError {
  double light_deg = 0;         // angle between the light and the view direction
  double psnr_db = 0;           // linear PSNR of this image, peak = max of its measured image
  double median_rel_error = 0;  // |Y_a - Y_m| / Y_m over its compared pixels
  double p95_rel_error = 0;
  std::size_t lit_pixels = 0;       // n.l and n.v above the cut-off, measured lookup valid
  std::size_t masked_pixels = 0;    // n.l and n.v above the cut-off, measured lookup invalid
  std::size_t compared_pixels = 0;  // lit, and Y_m above the floor
};

// The metric over one region of the domain (core/rendered_regions.h): its lights' images
// pooled, as the whole metric pools every image; the environment region is the image lit by the
// metric's environment (fit/rendered_environment.h), which the pooled numbers leave out.
inline constexpr int kRenderedRegions = 4;
inline constexpr const char* kRenderedRegionNames[kRenderedRegions] = {"front", "side", "rim",
                                                                       "environment"};
struct RenderedRegionError {
  int lights = 0;               // images of the region (0: not judged); 1 for the environment
  double psnr_db = 0;           // linear PSNR over the region's lit pixels, peak over its images
  double median_rel_error = 0;  // over the region's compared pixels
};

struct RenderedError {
  bool ok = false;  // false: see problem; the numbers are then zeros
  std::string problem;
  double psnr_db = 0;           // linear PSNR over all lit pixels of all directional-light images
  double psnr_srgb_db = 0;      // tone-mapped (exposure, clamp, sRGB OETF) PSNR, peak 1
  double median_rel_error = 0;  // relative luminance error over all compared pixels
  double p95_rel_error = 0;
  double peak = 0;                     // max measured radiance over pixels, channels and lights
  double exposure = 0;                 // 1 / (99th percentile of the measured luminance)
  int resolution = 0;                  // N: the images are N x N
  int num_lights = 0;                  // entries of `lights` in use
  std::size_t sphere_pixels = 0;       // pixel centres on the sphere (per image)
  std::size_t lit_pixels = 0;          // sum over the images
  std::size_t masked_pixels = 0;       // excluded: measured lookup invalid (never read as 0)
  std::size_t compared_pixels = 0;     // lit and Y_m above the floor
  std::size_t below_floor_pixels = 0;  // lit but Y_m at or below the floor: no relative error
  // The body's colour (docs/accuracy.md, "The body's colour"): in the front and side regions,
  // the RGB sums of the compared pixels at or below the region's median measured luminance, each
  // divided by its luminance, approximation against measurement; the largest relative difference
  // of a channel (a channel under 10 % of the brightest measured against that 10 %). A fit that
  // zeroes a channel the body has scores ~1, one 3 times too bright ~2; brightness alone, 0. NaN
  // in results read from files that predate it (not computed; never written).
  double body_color_error = 0;
  std::array<RenderedLightError, kRenderedMaxLights> lights{};
  // Per region, pooled; lights == 0 everywhere in results read from files that predate them
  // (core/rendered_regions.h RenderedRegions then derives them from the lights).
  std::array<RenderedRegionError, kRenderedRegions> regions{};
};

struct FitMetrics {
  bool ok = false;  // false: no samples or non-finite predictions (see problem)
  std::string problem;
  double log_rmse = 0;
  double cbrt_rmse = 0;
  double rel_l2 = 0;
  WorstCell worst;
  std::size_t cells = 0;  // observations scored
  double total_weight = 0;
  // How the metrics were computed (a report states metric, weighting and cut-off: errors are
  // not comparable without them).
  std::string weighting;  // "bin-measure" or "uniform"
  double cutoff_deg = 0;
  // Not computed by the fitter yet (ok = false, problem empty) and not written by any report.
  RenderedError rendered;
};

// ---- The record's schema -------------------------------------------------------------------
// Every reader and writer of results iterates these tables instead of naming the members: fit
// reports (io/fit_report.h, HDF5 and JSON), factorization sidecars (pipeline/factor_sidecar.h),
// bench CSVs (report/bench_csv.h), `compare` (report/compare.h), the HTML report's columns and
// charts, the CLI's tables and the Python dicts. Adding an error metric is a member of
// FitMetrics, one row of kErrorMetrics and its computation (fit/metrics.cc); adding a number of
// the rendered summary is a member of RenderedError, one row of kRenderedSummary and its
// computation (fit/rendered_error.cc). The entry's other numbers have their tables in
// core/result.h (kFitNumbers, kSampleCountFields, kFitTimeFields), the bench CSV's row in
// report/bench_csv.cc (kBenchColumns).

// An error metric of FitMetrics over the table's cells: a number >= 0, lower is better,
// required in a result whose metrics are ok (a reader refuses one without it) and read as 0 when
// the metrics are not ok and it is absent.
struct ErrorMetricField {
  const char* name;        // its key in every format, its column, and `compare --metric`'s value
  const char* unit;        // "" when dimensionless
  const char* definition;  // the formula, as the files' metrics_definition states it
  double FitMetrics::*value;
};
inline constexpr ErrorMetricField kErrorMetrics[] = {
    {"log_rmse", "", "sqrt(sum w (ln(1+f cos_i) - ln(1+m cos_i))^2 / (3 sum w)) (Low 2012 E2)",
     &FitMetrics::log_rmse},
    {"cbrt_rmse", "sr^-1/3", "sqrt(sum w (cbrt(f cos_i) - cbrt(m cos_i))^2 / (3 sum w))",
     &FitMetrics::cbrt_rmse},
    {"rel_l2", "", "sqrt(sum w cos_i^2 (f-m)^2 / sum w cos_i^2 m^2)", &FitMetrics::rel_l2},
};
inline constexpr std::size_t kNumErrorMetrics = std::size(kErrorMetrics);
// The metric that ranks fits when no rendered score decides (the HTML report, compare's default).
inline constexpr std::size_t kPrimaryErrorMetric = 0;

// A number of the rendered-image metric's summary (RenderedError; docs/accuracy.md): finite,
// >= min_value, required when the summary is ok.
struct RenderedSummaryField {
  const char* name;  // its key in JSON and HDF5, its bench CSV column
  const char* unit;
  const char* doc;
  double RenderedError::*value;
  double min_value;
  bool higher_is_better;
  // Required when the summary is ok. An optional number absent from a file is read as NaN
  // ("not computed") and a NaN one is not written (a column left empty).
  bool required = true;
  // An optional number that e does not hold: every writer leaves it out.
  bool NotComputed(const RenderedError& e) const { return !required && std::isnan(e.*value); }
};
inline constexpr RenderedSummaryField kRenderedSummary[] = {
    {"psnr_db", "dB", "linear PSNR over all lit pixels of all light images",
     &RenderedError::psnr_db, -HUGE_VAL, true},
    {"psnr_srgb_db", "dB", "tone-mapped (exposure, clamp, sRGB OETF) PSNR, peak 1",
     &RenderedError::psnr_srgb_db, -HUGE_VAL, true},
    {"median_rel_error", "", "median relative luminance error over all compared pixels",
     &RenderedError::median_rel_error, 0, false},
    {"p95_rel_error", "", "95th percentile of the relative luminance error",
     &RenderedError::p95_rel_error, 0, false},
    {"body_color_error", "",
     "largest relative error of a channel of the body's colour (front and side regions: the "
     "pixels at or below the region's median measured luminance, summed per channel, over "
     "their luminance)",
     &RenderedError::body_color_error, 0, false, false},
};

// The metric definitions in one line, for reports (fit reports' metrics_definition, sidecars,
// the HTML report): "NAME: DEFINITION; " per error metric, then the weights and the worst cell.
inline const std::string& MetricsDefinition() {
  static const std::string text = [] {
    std::string s;
    for (const ErrorMetricField& f : kErrorMetrics) {
      s += std::string(f.name) + ": " + f.definition + "; ";
    }
    return s +
           "sums over cells and RGB; w = cell weight; worst: max over cells of "
           "|ln(1+f cos_i) - ln(1+m cos_i)|";
  }();
  return text;
}

// The error metrics' names joined by sep ("log_rmse, cbrt_rmse, rel_l2"), for help texts.
inline std::string ErrorMetricNames(const char* sep = ", ") {
  std::string s;
  for (const ErrorMetricField& f : kErrorMetrics) s += (s.empty() ? "" : sep) + std::string(f.name);
  return s;
}

}  // namespace brdfit
