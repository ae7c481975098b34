// An isotropic BRDF given as a function, put into the adaptive parameterization of Dupuy &
// Jakob 2018 (core/rgl_bsdf.h) so that it can be written as an RGL `.bsdf` file:
//
//  1. The NDF by power iteration on the retro-reflection (Dupuy et al. 2015, "Extracting
//     Microfacet-based BRDF Parameters from Arbitrary Materials with Power Iterations", CGF
//     34(4); Dupuy & Jakob 2018, Sec. 4): with the backscattering form
//     f(w, w) = F D(w) G1(w) / (4 cos^2 theta) and G1(w) = cos theta / sigma(w),
//        D_{k+1}(w) = f(w, w) cos(theta) sigma_k(w),   sigma_k(w) = int D_k(m) <w, m>+ dm,
//     normalized so that int D(m) cos(theta_m) dm = 1, from D_0 = 1, on the luminance of f.
//  2. sigma(w_i) from that D, in closed form over the azimuth (see the .cc).
//  3. Per incident elevation, the VNDF D_wi(m) = <wi, m>+ D(m) / sigma(wi) (Heitz & d'Eon 2014)
//     times the Jacobian 2 pi^2 u_theta sin(theta_m) of the unit square's map to the sphere,
//     stored on the (phi_m, theta_m) grid.
//  4. The values R = f(wi, wo) cos(theta_o) 4 sigma(wi) / D(wm) at the VNDF-warped grid's
//     nodes: the node's coordinates pushed through the warp (the loader's Marginal2D::sample)
//     give wm, then wo = reflect(wi, wm). Reading the file back at those directions returns f
//     exactly; elsewhere it interpolates.
//
// Resolutions (RglBuildOptions) are the user's trade-off between file size and accuracy.
#pragma once

#include <functional>
#include <string>

#include "core/rgl_bsdf.h"
#include "models/geometry.h"

namespace brdfit {

// f_r(wi, wo) in 1/sr per linear-sRGB channel, without the cosine; false where the source has
// no value (a masked table cell): that warped sample is then stored as unmeasured (`valid`).
using BrdfSource = std::function<bool(const Vec3& wi, const Vec3& wo, double rgb[3])>;

struct RglBuildOptions {
  int ndf_samples = 128;   // NDF and sigma samples along theta (u = sqrt(theta / (pi/2)))
  int warp_samples = 64;   // the warped grid, warp_samples x warp_samples per theta_i
  int theta_i_count = 23;  // incident elevations, uniform in [0, theta_i_max]
  double theta_i_max_deg = 88;
  int power_iterations = 32;  // at most; stops when D changes by less than 1e-9 (relative)
  // The NDF stored (and warped by) is (1 - w) D + w / pi, D from the power iteration and 1/pi
  // the cosine-distributed one: a sharp peak would otherwise take nearly every warped sample
  // and leave the rest of the hemisphere to interpolation across a few. The values divide by
  // the stored NDF, so the file stays exact at its samples whatever w is.
  double ndf_spread = 0.1;
  // Spectral values (fields `spectra`, `wavelengths`: 360-830 nm every 10 nm) instead of
  // `rgb`: what pbrt-v4's `measured` material reads. Each RGB value becomes
  // sum_c rgb_c B_c(lambda) with core/spectral_rgb.h's SrgbBasisSpectra, which brdfit's reader
  // converts back to the same RGB; a grey is a flat spectrum.
  bool spectral = false;
  std::string description;
};

struct RglBuildReport {
  int power_iterations = 0;    // iterations the NDF took
  double power_change = 0;     // the last relative change of D
  std::size_t unmeasured = 0;  // warped samples the source had no value for (valid = 0)
  std::size_t negative = 0;    // samples with a channel below zero, clamped to 0
  std::size_t spectral_clamped = 0;  // spectral values below zero (saturated colours), set to 0
};

// Throws std::invalid_argument for options out of range, std::runtime_error if the source's
// retro-reflection is zero or not finite everywhere (no NDF can be extracted).
RglBsdf BuildRglBsdf(const BrdfSource& f, const RglBuildOptions& options,
                     RglBuildReport* report = nullptr);

}  // namespace brdfit
