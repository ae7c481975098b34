#include "core/rgl_bsdf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/spectral_rgb.h"

namespace brdfit {

namespace {

constexpr double kHalfPi = kPi / 2;

// The paper's map of angles to the unit square: theta by its square root, phi linearly.
double ThetaToU(double theta) {
  return std::sqrt(std::max(theta, 0.0) / kHalfPi);
}
double PhiToU(double phi) {
  return (phi + kPi) / (2 * kPi);
}

// acos(d.z) computed as 2 asin(|d - z| / 2), accurate near the pole (as the authors' loader).
double Elevation(const Vec3& d) {
  const double r = std::sqrt(d.x * d.x + d.y * d.y + (d.z - 1) * (d.z - 1));
  return 2 * std::asin(std::min(0.5 * r, 1.0));
}

// Index i in [0, n - 2] of the interval [v[i], v[i+1]] holding x, clamped at the ends, and the
// weight of v[i+1] (clamped to [0, 1]): the loader's find_interval and parameter weights.
void Interval(const std::vector<double>& v, double x, int* i, double* w1) {
  const int n = static_cast<int>(v.size());
  int k = 0;
  while (k + 1 < n - 1 && v[static_cast<std::size_t>(k + 1)] <= x) ++k;
  *i = k;
  const double p0 = v[static_cast<std::size_t>(k)], p1 = v[static_cast<std::size_t>(k + 1)];
  *w1 = std::clamp((x - p0) / (p1 - p0), 0.0, 1.0);
}

// Bilinear position on a rows x cols grid of samples spanning [0, 1]^2: the cell (col, row)
// of its lower corner and the fractional offsets.
struct Patch {
  int col = 0, row = 0;
  double fx = 0, fy = 0;
};
Patch PatchAt(double ux, double uy, int rows, int cols) {
  Patch p;
  const double x = ux * (cols - 1), y = uy * (rows - 1);
  // Clamped in double first: the conversion to int of a value out of its range is undefined.
  p.col = static_cast<int>(std::clamp(std::floor(x), 0.0, cols - 2.0));
  p.row = static_cast<int>(std::clamp(std::floor(y), 0.0, rows - 2.0));
  p.fx = x - p.col;
  p.fy = y - p.row;
  return p;
}

double Bilinear(const double* a, int cols, const Patch& p) {
  const std::size_t i = static_cast<std::size_t>(p.row) * cols + p.col;
  const double c0 = (1 - p.fy) * a[i] + p.fy * a[i + cols];
  const double c1 = (1 - p.fy) * a[i + 1] + p.fy * a[i + 1 + cols];
  return (1 - p.fx) * c0 + p.fx * c1;
}

void Require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("RglBsdf: ") + what);
}

}  // namespace

RglBsdfEvaluator::RglBsdfEvaluator(const RglBsdf& b) : b_(b) {
  const std::size_t np = b.phi_i.size(), nt = b.theta_i.size();
  Require(np >= 1 && np <= 2 && nt >= 1, "phi_i / theta_i sizes");
  Require(b.rows >= 2 && b.cols >= 2 && b.ndf_rows >= 2 && b.ndf_cols >= 2 && b.sigma_rows >= 2 &&
              b.sigma_cols >= 2 && b.channels >= 1,
          "grid sizes");
  const std::size_t cells = static_cast<std::size_t>(b.rows) * b.cols, slices = np * nt;
  Require(b.vndf.size() == slices * cells, "vndf size");
  Require(b.values.size() == slices * cells * b.channels, "values size");
  Require(b.ndf.size() == static_cast<std::size_t>(b.ndf_rows) * b.ndf_cols, "ndf size");
  Require(b.sigma.size() == static_cast<std::size_t>(b.sigma_rows) * b.sigma_cols, "sigma size");
  Require(b.valid.empty() || b.valid.size() == slices * cells, "valid size");

  // The loader's Marginal2D construction (build_cdf, normalize): per slice, the cumulative
  // trapezoid sums along each row (conditional), then along the rows' totals (marginal); all
  // three divided by the slice's total.
  vndf_.resize(b.vndf.size());
  conditional_.resize(b.vndf.size());
  marginal_.resize(slices * b.rows);
  for (std::size_t s = 0; s < slices; ++s) {
    const double* d = &b.vndf[s * cells];
    double* cc = &conditional_[s * cells];
    double* mc = &marginal_[s * b.rows];
    for (int y = 0; y < b.rows; ++y) {
      const std::size_t r = static_cast<std::size_t>(y) * b.cols;
      double sum = 0;
      cc[r] = 0;
      for (int x = 0; x + 1 < b.cols; ++x) {
        sum += 0.5 * (d[r + x] + d[r + x + 1]);
        cc[r + x + 1] = sum;
      }
    }
    double sum = 0;
    mc[0] = 0;
    for (int y = 0; y + 1 < b.rows; ++y) {
      sum += 0.5 * (cc[(y + 1) * static_cast<std::size_t>(b.cols) - 1] +
                    cc[(y + 2) * static_cast<std::size_t>(b.cols) - 1]);
      mc[y + 1] = sum;
    }
    Require(sum > 0 && std::isfinite(sum), "a vndf slice integrates to zero");
    const double norm = 1 / sum;
    for (std::size_t i = 0; i < cells; ++i) {
      cc[i] *= norm;
      vndf_[s * cells + i] = d[i] * norm;
    }
    for (int y = 0; y < b.rows; ++y) mc[y] *= norm;
  }
}

RglBsdfEvaluator::Slices RglBsdfEvaluator::SlicesAt(double phi_i, double theta_i) const {
  int ip = 0, it = 0;
  double wp = 0, wt = 0;
  const int np = static_cast<int>(b_.phi_i.size()), nt = static_cast<int>(b_.theta_i.size());
  if (np > 1) Interval(b_.phi_i, phi_i, &ip, &wp);
  if (nt > 1) Interval(b_.theta_i, theta_i, &it, &wt);
  Slices s;
  for (int a = 0; a < (np > 1 ? 2 : 1); ++a) {
    for (int c = 0; c < (nt > 1 ? 2 : 1); ++c) {
      const double w = (np > 1 ? (a ? wp : 1 - wp) : 1.0) * (nt > 1 ? (c ? wt : 1 - wt) : 1.0);
      s.slice[s.count] = (ip + a) * nt + (it + c);
      s.weight[s.count] = w;
      ++s.count;
    }
  }
  return s;
}

double RglBsdfEvaluator::Lookup(const std::vector<double>& a, const Slices& s,
                                std::size_t slice_size, std::size_t i) const {
  double v = 0;
  for (int k = 0; k < s.count; ++k) v += s.weight[k] * a[s.slice[k] * slice_size + i];
  return v;
}

double RglBsdfEvaluator::ScaleAt(double um_x, double um_y, double ui_x, double ui_y) const {
  const double d =
      Bilinear(b_.ndf.data(), b_.ndf_cols, PatchAt(um_x, um_y, b_.ndf_rows, b_.ndf_cols));
  const double sigma =
      Bilinear(b_.sigma.data(), b_.sigma_cols, PatchAt(ui_x, ui_y, b_.sigma_rows, b_.sigma_cols));
  return d / (4 * sigma);
}

double RglBsdfEvaluator::Scale(const Vec3& wi, const Vec3& wm) const {
  const double phi_i = std::atan2(wi.y, wi.x);
  double um_y = PhiToU(std::atan2(wm.y, wm.x) - phi_i);
  um_y -= std::floor(um_y);
  return ScaleAt(ThetaToU(Elevation(wm)), um_y, ThetaToU(Elevation(wi)), PhiToU(phi_i));
}

// Marginal2D::sample of the authors' loader on one slice: the row by the marginal CDF, then the
// column by the row-interpolated conditional CDF, each inverted within its linear patch.
void RglBsdfEvaluator::Warp(int slice, double sx, double sy, double* u_theta, double* u_phi) const {
  const int rows = b_.rows, cols = b_.cols;
  const std::size_t cells = static_cast<std::size_t>(rows) * cols;
  const double* mc = &marginal_[static_cast<std::size_t>(slice) * rows];
  const double* cc = &conditional_[static_cast<std::size_t>(slice) * cells];
  const double* d = &vndf_[static_cast<std::size_t>(slice) * cells];
  constexpr double kEps = 1e-12;
  sx = std::clamp(sx, kEps, 1 - kEps);
  sy = std::clamp(sy, kEps, 1 - kEps);
  // The largest index in [0, n - 2] whose value is below x (find_interval).
  auto find = [](int n, const auto& below) {
    int k = 0;
    while (k + 1 <= n - 2 && below(k + 1)) ++k;
    return k;
  };
  // t in [0, 1] with a t + (b - a) t^2 / 2 = s: the inverse CDF of a linear density a..b.
  auto invert_linear = [](double a, double b, double s) {
    if (std::abs(a - b) < 1e-4 * (a + b)) return 2 * s / (a + b);
    return (a - std::sqrt(std::max(a * a - 2 * s * (a - b), 0.0))) / (a - b);
  };
  const int row = find(rows, [&](int k) { return mc[k] < sy; });
  sy -= mc[row];
  const std::size_t r = static_cast<std::size_t>(row) * cols;
  const double r0 = cc[r + cols - 1], r1 = cc[r + 2 * cols - 1];
  const double ty = r0 + r1 > 0 ? std::clamp(invert_linear(r0, r1, sy), 0.0, 1.0) : 0.5;
  sx *= (1 - ty) * r0 + ty * r1;
  auto conditional = [&](int k) { return (1 - ty) * cc[r + k] + ty * cc[r + cols + k]; };
  const int col = find(cols, [&](int k) { return conditional(k) < sx; });
  sx -= conditional(col);
  const std::size_t o = r + col;
  const double c0 = (1 - ty) * d[o] + ty * d[o + cols];
  const double c1 = (1 - ty) * d[o + 1] + ty * d[o + cols + 1];
  const double tx = c0 + c1 > 0 ? std::clamp(invert_linear(c0, c1, sx), 0.0, 1.0) : 0.5;
  *u_theta = (col + tx) / (cols - 1);
  *u_phi = (row + ty) / (rows - 1);
}

RglBsdfEvaluator::Result RglBsdfEvaluator::Eval(const Vec3& wi, const Vec3& wo, double* out) const {
  Result r;  // not covered until the end
  for (int c = 0; c < b_.channels; ++c) out[c] = 0;
  if (!(wi.z > 0 && wo.z > 0)) return r;
  r.above = true;
  const Vec3 wm = Normalize(wi + wo);
  const double theta_i = Elevation(wi), phi_i = std::atan2(wi.y, wi.x);
  const double theta_m = Elevation(wm), phi_m = std::atan2(wm.y, wm.x);
  const double ui_x = ThetaToU(theta_i), ui_y = PhiToU(phi_i);
  const double um_x = ThetaToU(theta_m);
  // Isotropic: the half vector's azimuth relative to the incident one.
  double um_y = PhiToU(phi_m - phi_i);
  um_y -= std::floor(um_y);

  const Slices s = SlicesAt(phi_i, theta_i);
  const int rows = b_.rows, cols = b_.cols;
  const std::size_t cells = static_cast<std::size_t>(rows) * cols;

  // Marginal2D::invert: the warped coordinates of wm under the VNDF conditioned on wi.
  const Patch p = PatchAt(um_x, um_y, rows, cols);
  const std::size_t off = static_cast<std::size_t>(p.row) * cols + p.col;
  const double v00 = Lookup(vndf_, s, cells, off), v10 = Lookup(vndf_, s, cells, off + 1);
  const double v01 = Lookup(vndf_, s, cells, off + cols);
  const double v11 = Lookup(vndf_, s, cells, off + cols + 1);
  const double c0 = (1 - p.fy) * v00 + p.fy * v01, c1 = (1 - p.fy) * v10 + p.fy * v11;
  double sx = p.fx * (c0 + 0.5 * p.fx * (c1 - c0));
  sx += (1 - p.fy) * Lookup(conditional_, s, cells, off) +
        p.fy * Lookup(conditional_, s, cells, off + cols);
  const std::size_t row0 = static_cast<std::size_t>(p.row) * cols;
  const double r0 = Lookup(conditional_, s, cells, row0 + cols - 1);
  const double r1 = Lookup(conditional_, s, cells, row0 + 2 * cols - 1);
  const double row_total = (1 - p.fy) * r0 + p.fy * r1;
  // A VNDF of zero density all along wm's row: the file holds no sample there (the loader's
  // division by zero); reported as not covered.
  if (!(row_total > 0)) return r;
  sx /= row_total;
  double sy = p.fy * (r0 + 0.5 * p.fy * (r1 - r0));
  sy += Lookup(marginal_, s, static_cast<std::size_t>(rows), static_cast<std::size_t>(p.row));
  if (!(std::isfinite(sx) && std::isfinite(sy))) return r;

  // The values at the warped coordinates, bilinear within each slice and channel.
  const Patch q = PatchAt(sx, sy, rows, cols);
  for (int c = 0; c < b_.channels; ++c) {
    double v = 0;
    for (int k = 0; k < s.count; ++k) {
      const double* a =
          &b_.values[(static_cast<std::size_t>(s.slice[k]) * b_.channels + c) * cells];
      v += s.weight[k] * Bilinear(a, cols, q);
    }
    out[c] = v;
  }
  const double scale = ScaleAt(um_x, um_y, ui_x, ui_y);
  for (int c = 0; c < b_.channels; ++c) out[c] *= scale;

  r.covered = theta_i <= b_.theta_i.back() + 1e-6;
  if (!b_.valid.empty()) {
    const std::size_t qi = static_cast<std::size_t>(q.row) * cols + q.col;
    for (int k = 0; k < s.count; ++k) {
      if (s.weight[k] == 0) continue;
      const std::uint8_t* m = &b_.valid[static_cast<std::size_t>(s.slice[k]) * cells];
      if (!m[qi] || !m[qi + 1] || !m[qi + cols] || !m[qi + cols + 1]) r.covered = false;
    }
  }
  return r;
}

Table TabulateRglBsdf(const RglBsdf& b, const Grid& grid, RglTabulation* counts) {
  const RglBsdfEvaluator eval(b);
  const bool spectral = !b.wavelengths.empty();
  std::array<std::vector<double>, 3> weights;
  if (spectral) weights = SrgbWeights(b.wavelengths);
  RglTabulation n;
  n.notes = b.notes;
  Table t = Table::Empty(grid);
  std::vector<double> ch(static_cast<std::size_t>(b.channels));
  for (std::size_t idx = 0; idx < grid.NumCells(); ++idx) {
    Vec3 wi, wo;
    FromHalfDiff(grid.CellCentre(idx), 0.0, &wi, &wo);
    const RglBsdfEvaluator::Result r = eval.Eval(wi, wo, ch.data());
    if (!r.above) {
      ++n.below_horizon;
      continue;
    }
    if (!r.covered) {
      ++n.uncovered;
      continue;
    }
    std::array<double, 3> rgb{};
    for (int c = 0; c < 3; ++c) {
      if (spectral) {
        for (int k = 0; k < b.channels; ++k) rgb[c] += weights[c][k] * ch[k];
      } else {
        rgb[c] = ch[c];
      }
      rgb[c] /= wo.z;  // the file holds f_r cos(theta_o)
    }
    if (!(std::isfinite(rgb[0]) && std::isfinite(rgb[1]) && std::isfinite(rgb[2]))) {
      ++n.not_finite;
      continue;
    }
    if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0) ++n.clamped;
    double* v = t.Value(idx);
    for (int c = 0; c < 3; ++c) v[c] = std::max(rgb[c], 0.0);
    t.valid[idx] = 1;
  }
  if (counts) *counts = n;
  return t;
}

}  // namespace brdfit
