// An isotropic measured BRDF in the adaptive parameterization of Dupuy & Jakob 2018, "An
// Adaptive Parameterization for Efficient Material Acquisition and Rendering" (ACM TOG 37(6)),
// the content of the RGL database's `.bsdf` files (io/rgl_bsdf_file.h reads them), and its
// evaluation as the paper and the authors' loader define it:
//
//   f_r(wi, wo) cos(theta_o) = R(u) D(wm) / (4 sigma(wi))
//
// (the microfacet form the paper stores its measurements in, evaluated as the authors' loader,
// rgl-epfl/brdf-loader's BRDF::eval, does),
//
// with wm = normalize(wi + wo), D the tabulated NDF, sigma the tabulated projected area, and
// R the values stored on the VNDF-warped grid, looked up at u = the inverse of the VNDF warp
// (conditioned on wi) applied to wm. Angles map to the unit square as
// u_theta = sqrt(theta / (pi/2)), u_phi = (phi + pi) / (2 pi); for isotropic files the half
// vector's azimuth is taken relative to wi's. Every 2D table is bilinear between its samples
// (sample j of n at u = j / (n - 1)), and the conditioned ones interpolate linearly between
// the neighbouring (phi_i, theta_i) slices, clamping outside them. The inverse warp is the
// marginal-conditional inversion of the bilinear VNDF (the loader's Marginal2D::invert).
// Everything here is evaluated in double (the loader uses float: they agree to ~1e-6 relative).
//
// Arrays are row-major in the file's order: theta of the 2D tables along the last axis.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/table.h"
#include "models/geometry.h"

namespace brdfit {

struct RglBsdf {
  std::string description;
  bool jacobian = true;            // the file's flag (not used by the evaluation)
  std::vector<double> theta_i;     // radians, strictly increasing, in [0, pi/2]
  std::vector<double> phi_i;       // radians; 1 or 2 values (isotropic)
  int ndf_rows = 0, ndf_cols = 0;  // ndf: rows along phi_m, cols along theta_m
  std::vector<double> ndf;
  int sigma_rows = 0, sigma_cols = 0;
  std::vector<double> sigma;
  int rows = 0, cols = 0;           // the warped grid of vndf and the values
  std::vector<double> vndf;         // [phi_i][theta_i][rows][cols]
  std::vector<double> luminance;    // as vndf: the sampling warp (not used by Eval)
  int channels = 0;                 // 3 (rgb) or the number of wavelengths
  std::vector<double> values;       // [phi_i][theta_i][channels][rows][cols]
  std::vector<double> wavelengths;  // nm; empty for an RGB file
  std::vector<std::uint8_t> valid;  // empty, or [phi_i][theta_i][rows][cols]: 0 = not measured
  std::vector<std::string> notes;   // what the reader read but did not use, and why
};

// The precomputed inverse warp of one RglBsdf (which must outlive it).
class RglBsdfEvaluator {
 public:
  // Throws std::invalid_argument if the arrays are inconsistent (io/ checks files first).
  explicit RglBsdfEvaluator(const RglBsdf& bsdf);

  struct Result {
    bool above = false;  // both directions above the horizon
    // theta_i within the file's range, every sample used measured, and the VNDF not zero
    // along wm's row. out is 0 below the horizon and where the inverse warp is undefined (that
    // row); beyond theta_i's range or on unmeasured samples it holds what the authors' loader
    // returns there (the last slice, the stored values).
    bool covered = false;
  };
  // out[channel] = f_r(wi, wo) cos(theta_o) per channel of the file (unclipped). wi: towards
  // the light, wo: towards the viewer, unit, local frame.
  Result Eval(const Vec3& wi, const Vec3& wo, double* out) const;

  // The forward warp of one (phi_i, theta_i) slice (the loader's Marginal2D::sample):
  // warped coordinates (sx, sy) in [0, 1]^2 -> the unit-square coordinates (u_theta, u_phi)
  // of wm. Eval inverts it.
  void Warp(int slice, double sx, double sy, double* u_theta, double* u_phi) const;
  // D(wm) / (4 sigma(wi)), the factor Eval applies to the values.
  double Scale(const Vec3& wi, const Vec3& wm) const;

 private:
  struct Slices {  // up to four (phi_i, theta_i) slices and their weights
    int count = 0;
    int slice[4] = {0, 0, 0, 0};
    double weight[4] = {0, 0, 0, 0};
  };
  Slices SlicesAt(double phi_i, double theta_i) const;
  double Lookup(const std::vector<double>& a, const Slices& s, std::size_t slice_size,
                std::size_t i) const;

  double ScaleAt(double um_x, double um_y, double ui_x, double ui_y) const;

  const RglBsdf& b_;
  std::vector<double> vndf_;         // each slice divided by its integral
  std::vector<double> conditional_;  // per slice, per row: cumulative along cols
  std::vector<double> marginal_;     // per slice: cumulative along rows
};

// Counts of a tabulation onto a grid.
struct RglTabulation {
  std::size_t below_horizon = 0;  // cells with a direction below the horizon (masked)
  std::size_t uncovered = 0;      // theta_i beyond the file's range or unmeasured (masked)
  std::size_t not_finite = 0;     // masked
  std::size_t clamped = 0;        // cells with a channel below zero, clamped to 0
  std::vector<std::string> notes;  // the file's (RglBsdf::notes)
};

// f_r at every cell centre of `grid` (wi = the light, as every brdfit table), in linear sRGB:
// RGB files as they are, spectral ones by core/spectral_rgb.h. Negative channels (out of the
// sRGB gamut) are clamped to zero as the authors' RGB loader clamps them, and counted.
Table TabulateRglBsdf(const RglBsdf& bsdf, const Grid& grid, RglTabulation* counts = nullptr);

}  // namespace brdfit
