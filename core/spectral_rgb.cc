#include "core/spectral_rgb.h"

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

}  // namespace brdfit
