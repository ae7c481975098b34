// Hand-made RGL .bsdf tensors for the tests: one with random (but valid) content, which
// exercises every interpolation path of a reader, and one whose content is a known microfacet
// BRDF (constant values on the warped grid), whose tabulation has a closed form.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "io/tensor_file.h"
#include "models/geometry.h"

namespace brdfit::test {

// GGX NDF (Walter et al. 2007, Eq. 33) and its projected area
// sigma(theta) = cos(theta) (1 + Lambda(theta)), Lambda = (-1 + sqrt(1 + a^2 tan^2)) / 2
// (Heitz 2014, "Understanding the Masking-Shadowing Function", Eqs. 2 and 72).
inline double GgxD(double theta_m, double a) {
  const double c = std::cos(theta_m), t2 = std::pow(std::tan(theta_m), 2);
  const double k = a * a + t2;
  return a * a / (kPi * std::pow(c, 4) * k * k);
}
inline double GgxSigma(double theta, double a) {
  const double t2 = std::pow(std::tan(theta), 2);
  return std::cos(theta) * 0.5 * (1 + std::sqrt(1 + a * a * t2));
}

struct BsdfSpec {
  int rows = 16, cols = 16;  // warped grid
  int n_theta = 6, n_phi = 2;
  double theta_max = 85 * kPi / 180;
};

inline std::vector<double> ThetaI(const BsdfSpec& s) {
  std::vector<double> t(static_cast<std::size_t>(s.n_theta));
  for (int i = 0; i < s.n_theta; ++i)
    t[static_cast<std::size_t>(i)] = s.theta_max * i / (s.n_theta - 1);
  return t;
}

// Fields common to both files; `values` is rgb [np, nt, 3, rows, cols].
inline TensorFile AssembleBsdf(const BsdfSpec& s, const std::vector<double>& ndf, int ndf_cols,
                               const std::vector<double>& sigma, int sigma_cols,
                               const std::vector<double>& vndf, const std::vector<double>& rgb,
                               const std::string& description) {
  const auto np = static_cast<std::uint64_t>(s.n_phi), nt = static_cast<std::uint64_t>(s.n_theta);
  const auto r = static_cast<std::uint64_t>(s.rows), c = static_cast<std::uint64_t>(s.cols);
  std::vector<double> phi =
      s.n_phi == 1 ? std::vector<double>{0.0} : std::vector<double>{-kPi, kPi};
  TensorFile f;
  f.fields.push_back(UInt8Field("description", {description.size()},
                                std::vector<std::uint8_t>(description.begin(), description.end())));
  f.fields.push_back(UInt8Field("jacobian", {1}, {1}));
  f.fields.push_back(Float32Field("theta_i", {nt}, ThetaI(s)));
  f.fields.push_back(Float32Field("phi_i", {np}, phi));
  f.fields.push_back(Float32Field("ndf", {2, static_cast<std::uint64_t>(ndf_cols)}, ndf));
  f.fields.push_back(Float32Field("sigma", {2, static_cast<std::uint64_t>(sigma_cols)}, sigma));
  f.fields.push_back(Float32Field("vndf", {np, nt, r, c}, vndf));
  f.fields.push_back(Float32Field("luminance", {np, nt, r, c}, vndf));
  f.fields.push_back(Float32Field("rgb", {np, nt, 3, r, c}, rgb));
  return f;
}

// Random positive content; the NDF and projected area are smooth but arbitrary.
inline TensorFile RandomBsdf(const BsdfSpec& s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  const std::size_t cells = static_cast<std::size_t>(s.rows) * s.cols;
  const std::size_t slices = static_cast<std::size_t>(s.n_phi) * s.n_theta;
  std::vector<double> ndf(2 * 24), sigma(2 * 24), vndf(slices * cells), rgb(3 * slices * cells);
  for (double& v : ndf) v = 0.5 + 3 * u(rng);
  for (double& v : sigma) v = 0.3 + u(rng);
  for (double& v : vndf) v = u(rng);
  for (double& v : rgb) v = u(rng);
  return AssembleBsdf(s, ndf, 24, sigma, 24, vndf, rgb, "random test tensor");
}

// A GGX microfacet BRDF with reflectance `c` stored as constant values on the warped grid:
// f_r cos(theta_o) = c D(wm) / (4 sigma(wi)), i.e. f_r = c D G1(wi) / (4 cos_i cos_o)
// whatever the warp (the VNDF here is uniform, which a constant value does not see).
inline TensorFile GgxBsdf(const BsdfSpec& s, double alpha, const double c[3]) {
  const int n = 96;  // NDF and sigma samples along theta (u = sqrt(theta / (pi/2)))
  std::vector<double> ndf(2 * n), sigma(2 * n);
  for (int row = 0; row < 2; ++row) {
    for (int j = 0; j < n; ++j) {
      const double uu = static_cast<double>(j) / (n - 1);
      const double theta = std::min(uu * uu * kPi / 2, kPi / 2 - 1e-4);
      ndf[static_cast<std::size_t>(row * n + j)] = GgxD(theta, alpha);
      sigma[static_cast<std::size_t>(row * n + j)] = std::max(GgxSigma(theta, alpha), 1e-3);
    }
  }
  const std::size_t cells = static_cast<std::size_t>(s.rows) * s.cols;
  const std::size_t slices = static_cast<std::size_t>(s.n_phi) * s.n_theta;
  std::vector<double> vndf(slices * cells, 1.0), rgb(3 * slices * cells);
  for (std::size_t sl = 0; sl < slices; ++sl) {
    for (int k = 0; k < 3; ++k) {
      for (std::size_t i = 0; i < cells; ++i)
        rgb[(sl * 3 + static_cast<std::size_t>(k)) * cells + i] = c[k];
    }
  }
  return AssembleBsdf(s, ndf, n, sigma, n, vndf, rgb, "GGX alpha test tensor");
}

}  // namespace brdfit::test
