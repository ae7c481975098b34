#include "core/spectral_rgb.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brdfit {

namespace {

// Wyman et al. 2013, Eq. 2: a piecewise Gaussian with separate widths below and above the mean.
double G(double x, double mu, double sigma_lo, double sigma_hi) {
  const double t = (x - mu) / (x < mu ? sigma_lo : sigma_hi);
  return std::exp(-0.5 * t * t);
}

// IEC 61966-2-1 (sRGB), XYZ -> linear RGB.
constexpr double kXyzToSrgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                     {-0.9692660, 1.8760108, 0.0415560},
                                     {0.0556434, -0.2040259, 1.0572252}};

}  // namespace

std::array<double, 3> Cie1931Xyz(double l) {
  return {1.056 * G(l, 599.8, 37.9, 31.0) + 0.362 * G(l, 442.0, 16.0, 26.7) -
              0.065 * G(l, 501.1, 20.4, 26.2),
          0.821 * G(l, 568.8, 46.9, 40.5) + 0.286 * G(l, 530.9, 16.3, 31.1),
          1.217 * G(l, 437.0, 11.8, 36.0) + 0.681 * G(l, 459.0, 26.0, 13.8)};
}

std::array<std::vector<double>, 3> SrgbWeights(const std::vector<double>& wl) {
  const std::size_t n = wl.size();
  if (n < 2) throw std::invalid_argument("SrgbWeights: fewer than two wavelengths");
  for (std::size_t k = 1; k < n; ++k) {
    if (!(wl[k] > wl[k - 1])) throw std::invalid_argument("SrgbWeights: not increasing");
  }
  std::array<std::vector<double>, 3> w;
  for (auto& c : w) c.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    // Trapezoid rule: half of each neighbouring interval.
    const double dl =
        0.5 * ((k + 1 < n ? wl[k + 1] - wl[k] : 0.0) + (k > 0 ? wl[k] - wl[k - 1] : 0.0));
    const std::array<double, 3> xyz = Cie1931Xyz(wl[k]);
    for (int c = 0; c < 3; ++c) {
      w[c][k] =
          dl * (kXyzToSrgb[c][0] * xyz[0] + kXyzToSrgb[c][1] * xyz[1] + kXyzToSrgb[c][2] * xyz[2]);
    }
  }
  for (int c = 0; c < 3; ++c) {
    double white = 0;
    for (double v : w[c]) white += v;
    if (!(white > 0)) {
      throw std::invalid_argument("SrgbWeights: the wavelengths miss the visible range");
    }
    for (double& v : w[c]) v /= white;
  }
  return w;
}

std::array<std::vector<double>, 3> SrgbBasisSpectra(const std::vector<double>& wl) {
  const auto w = SrgbWeights(wl);
  const std::size_t n = wl.size();
  auto ramp = [](double l, double a, double b) { return std::clamp((l - a) / (b - a), 0.0, 1.0); };
  std::array<std::vector<double>, 3> band;  // R, G, B
  for (auto& b : band) b.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    band[2][k] = 1 - ramp(wl[k], 490, 510);
    band[0][k] = ramp(wl[k], 580, 600);
    band[1][k] = 1 - band[0][k] - band[2][k];
  }
  // a[c][j] = channel c of band j; the basis is band * inverse(a).
  double a[3][3];
  for (int c = 0; c < 3; ++c) {
    for (int j = 0; j < 3; ++j) {
      a[c][j] = 0;
      for (std::size_t k = 0; k < n; ++k) a[c][j] += w[c][k] * band[j][k];
    }
  }
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (!(std::abs(det) > 1e-6)) {
    throw std::invalid_argument("SrgbBasisSpectra: the wavelengths cannot separate R, G and B");
  }
  double inv[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // Cofactor of a[j][i] over the determinant (the adjugate's transpose).
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      inv[i][j] = (a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / det;
    }
  }
  std::array<std::vector<double>, 3> basis;
  for (int c = 0; c < 3; ++c) {
    basis[c].assign(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      for (int j = 0; j < 3; ++j) basis[c][k] += band[j][k] * inv[j][c];
    }
  }
  return basis;
}

}  // namespace brdfit
