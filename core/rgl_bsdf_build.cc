#include "core/rgl_bsdf_build.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/luminance.h"
#include "core/spectral_rgb.h"

namespace brdfit {

namespace {

constexpr double kHalfPi = kPi / 2;

// An isotropic NDF given at nodes u_j = j / (n - 1), theta = (pi/2) u^2, linear in u between
// them (as the file's bilinear lookup reads it).
class NodeNdf {
 public:
  explicit NodeNdf(std::vector<double> d) : d_(std::move(d)) {}
  double At(double u) const {
    const int n = static_cast<int>(d_.size());
    const double x = std::clamp(u, 0.0, 1.0) * (n - 1);
    const int j = std::min(static_cast<int>(x), n - 2);
    const double t = x - j;
    return (1 - t) * d_[static_cast<std::size_t>(j)] + t * d_[static_cast<std::size_t>(j + 1)];
  }
  const std::vector<double>& nodes() const { return d_; }

 private:
  std::vector<double> d_;
};

// int_0^{2 pi} max(0, a + b cos(phi)) dphi, b >= 0: the azimuthal part of <w, m>+ for
// w.m = cos(theta) cos(theta_m) + sin(theta) sin(theta_m) cos(phi).
double ClampedCosineOverAzimuth(double a, double b) {
  if (b <= std::abs(a)) return a > 0 ? 2 * kPi * a : 0.0;
  const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return 2 * (a * phi0 + b * std::sin(phi0));
}

// sigma(theta) = int D(m) <w, m>+ dm by the midpoint rule in u (theta_m = (pi/2) u^2,
// dtheta_m = pi u du), with the azimuth in closed form. sigma(0) = int D cos = 1 for a
// normalized D.
constexpr int kQuadrature = 2048;
double ProjectedArea(const NodeNdf& d, double theta) {
  const double ct = std::cos(theta), st = std::sin(theta);
  double sum = 0;
  for (int k = 0; k < kQuadrature; ++k) {
    const double u = (k + 0.5) / kQuadrature;
    const double tm = kHalfPi * u * u;
    const double ctm = std::cos(tm), stm = std::sin(tm);
    sum += d.At(u) * stm * ClampedCosineOverAzimuth(ct * ctm, st * stm) * kPi * u;
  }
  return sum / kQuadrature;
}

}  // namespace

RglBsdf BuildRglBsdf(const BrdfSource& f, const RglBuildOptions& o, RglBuildReport* report) {
  if (o.ndf_samples < 8 || o.ndf_samples > 4096 || o.warp_samples < 4 || o.warp_samples > 1024 ||
      o.theta_i_count < 2 || o.theta_i_count > 1024 ||
      !(o.theta_i_max_deg > 0 && o.theta_i_max_deg < 90) || o.power_iterations < 1) {
    throw std::invalid_argument(
        "RGL .bsdf resolutions out of range (ndf 8..4096, warp 4..1024, theta_i 2..1024 up "
        "to below 90 deg)");
  }
  RglBuildReport rep;
  const int n = o.ndf_samples;
  std::vector<double> theta_nodes(static_cast<std::size_t>(n)), retro(theta_nodes.size());
  for (int j = 0; j < n; ++j) {
    const double u = static_cast<double>(j) / (n - 1);
    theta_nodes[static_cast<std::size_t>(j)] = kHalfPi * u * u;
    // Retro-reflection wi = wo at the node's elevation (just above the horizon at the last).
    const double t = std::min(theta_nodes[static_cast<std::size_t>(j)], 89.5 * kPi / 180);
    const Vec3 w{std::sin(t), 0, std::cos(t)};
    double rgb[3] = {0, 0, 0};
    const double y = f(w, w, rgb) ? Rec709Luminance(rgb) : 0.0;
    retro[static_cast<std::size_t>(j)] = std::isfinite(y) ? std::max(y, 0.0) : 0.0;
  }
  if (*std::max_element(retro.begin(), retro.end()) <= 0) {
    throw std::runtime_error("the BRDF's retro-reflection is zero everywhere: no NDF to extract");
  }

  // 1. Power iteration (Dupuy et al. 2015): D <- f(w, w) cos(theta) sigma_D(w), normalized.
  NodeNdf d(std::vector<double>(static_cast<std::size_t>(n), 1.0));
  for (int it = 0; it < o.power_iterations; ++it) {
    std::vector<double> next(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
      const double t = theta_nodes[static_cast<std::size_t>(j)];
      next[static_cast<std::size_t>(j)] =
          retro[static_cast<std::size_t>(j)] * std::cos(t) * ProjectedArea(d, t);
    }
    // A floor keeps every density positive (the warp and R = ... / D need it).
    const double peak = *std::max_element(next.begin(), next.end());
    for (double& v : next) v = std::max(v, 1e-7 * peak);
    const double norm = ProjectedArea(NodeNdf(next), 0.0);
    double change = 0, biggest = 0;
    for (int j = 0; j < n; ++j) {
      next[static_cast<std::size_t>(j)] /= norm;
      change = std::max(change, std::abs(next[static_cast<std::size_t>(j)] -
                                         d.nodes()[static_cast<std::size_t>(j)]));
      biggest = std::max(biggest, next[static_cast<std::size_t>(j)]);
    }
    d = NodeNdf(std::move(next));
    rep.power_iterations = it + 1;
    rep.power_change = change / biggest;
    if (rep.power_change < 1e-9) break;
  }

  if (!(o.ndf_spread >= 0 && o.ndf_spread < 1)) {
    throw std::invalid_argument("the NDF spread must be in [0, 1)");
  }
  if (o.ndf_spread > 0) {
    std::vector<double> spread = d.nodes();
    for (double& v : spread) v = (1 - o.ndf_spread) * v + o.ndf_spread / kPi;
    d = NodeNdf(std::move(spread));
  }

  RglBsdf b;
  b.description = o.description;
  b.jacobian = true;
  b.phi_i = {-kPi, kPi};  // isotropic: two identical slices, as pbrt-v4's test file has
  for (int k = 0; k < o.theta_i_count; ++k) {
    b.theta_i.push_back(o.theta_i_max_deg * kPi / 180 * k / (o.theta_i_count - 1));
  }
  b.ndf_rows = b.sigma_rows = 2;
  b.ndf_cols = b.sigma_cols = n;
  std::vector<double> sigma_row(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    sigma_row[static_cast<std::size_t>(j)] =
        ProjectedArea(d, theta_nodes[static_cast<std::size_t>(j)]);
  }
  // Two identical rows (phi = -pi, pi) of each: isotropic.
  for (int row = 0; row < 2; ++row) {
    b.ndf.insert(b.ndf.end(), d.nodes().begin(), d.nodes().end());
    b.sigma.insert(b.sigma.end(), sigma_row.begin(), sigma_row.end());
  }

  // 3. The VNDF per slice, with the Jacobian of the unit square's map to the sphere.
  const int res = o.warp_samples;
  b.rows = b.cols = res;
  const std::size_t cells = static_cast<std::size_t>(res) * res;
  const std::size_t nt = b.theta_i.size(), slices = 2 * nt;
  b.vndf.resize(slices * cells);
  for (std::size_t k = 0; k < nt; ++k) {
    const double ti = b.theta_i[k];
    const Vec3 wi{std::sin(ti), 0, std::cos(ti)};
    for (int y = 0; y < res; ++y) {
      for (int x = 0; x < res; ++x) {
        const double ut = static_cast<double>(x) / (res - 1),
                     up = static_cast<double>(y) / (res - 1);
        const double tm = kHalfPi * ut * ut;
        const Vec3 m = FromSpherical(tm, (2 * up - 1) * kPi);
        const double v = std::max(Dot(wi, m), 0.0) * d.At(ut) * 2 * kPi * kPi * ut * std::sin(tm);
        for (std::size_t p = 0; p < 2; ++p) b.vndf[(p * nt + k) * cells + y * res + x] = v;
      }
    }
  }

  // 4. The values at the warped nodes.
  b.channels = 3;
  b.values.assign(slices * 3 * cells, 0.0);
  std::vector<std::uint8_t> valid(slices * cells, 1);
  std::vector<double> luminance(slices * cells, 0.0);
  const RglBsdfEvaluator eval(b);
  for (std::size_t k = 0; k < nt; ++k) {
    const double ti = b.theta_i[k];
    const Vec3 wi{std::sin(ti), 0, std::cos(ti)};
    for (int y = 0; y < res; ++y) {
      for (int x = 0; x < res; ++x) {
        double ut, up;
        eval.Warp(static_cast<int>(k), static_cast<double>(x) / (res - 1),
                  static_cast<double>(y) / (res - 1), &ut, &up);
        const Vec3 wm = FromSpherical(kHalfPi * ut * ut, (2 * up - 1) * kPi);
        const Vec3 wo = 2 * Dot(wi, wm) * wm - wi;
        double rgb[3] = {0, 0, 0};
        bool ok = true;
        if (wo.z > 1e-9 && Dot(wi, wm) > 0) {
          ok = f(wi, wo, rgb);
          const double scale = eval.Scale(wi, wm);
          for (double& c : rgb) c = ok && scale > 0 ? c * wo.z / scale : 0.0;
        }
        const std::size_t i = static_cast<std::size_t>(y) * res + x;
        bool negative = false;
        for (int c = 0; c < 3; ++c) {
          if (!std::isfinite(rgb[c])) {
            ok = false;
            rgb[c] = 0;
          }
          negative |= rgb[c] < 0;
          rgb[c] = std::max(rgb[c], 0.0);
        }
        rep.negative += negative;
        for (std::size_t p = 0; p < 2; ++p) {
          const std::size_t s = p * nt + k;
          for (int c = 0; c < 3; ++c) b.values[(s * 3 + c) * cells + i] = rgb[c];
          valid[s * cells + i] = ok;
          luminance[s * cells + i] = Rec709Luminance(rgb);
        }
        rep.unmeasured += !ok;
      }
    }
  }
  if (rep.unmeasured) b.valid = std::move(valid);
  b.luminance = std::move(luminance);
  if (o.spectral) {
    for (int l = 360; l <= 830; l += 10) b.wavelengths.push_back(l);
    const auto basis = SrgbBasisSpectra(b.wavelengths);
    const std::size_t nw = b.wavelengths.size();
    std::vector<double> spectra(slices * nw * cells);
    for (std::size_t s = 0; s < slices; ++s) {
      for (std::size_t i = 0; i < cells; ++i) {
        for (std::size_t k = 0; k < nw; ++k) {
          double v = 0;
          for (int c = 0; c < 3; ++c) v += b.values[(s * 3 + c) * cells + i] * basis[c][k];
          rep.spectral_clamped += v < 0;
          spectra[(s * nw + k) * cells + i] = std::max(v, 0.0);
        }
      }
    }
    b.values = std::move(spectra);
    b.channels = static_cast<int>(nw);
  }
  if (report) *report = rep;
  return b;
}

}  // namespace brdfit
