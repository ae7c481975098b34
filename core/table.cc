#include "core/table.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/prefault.h"

namespace brdfit {

namespace {
constexpr double kHalfPi = kPi / 2;
}

void Grid::Unindex(std::size_t idx, int* ih, int* id, int* ip) const {
  *ip = static_cast<int>(idx % n_phi_d);
  idx /= n_phi_d;
  *id = static_cast<int>(idx % n_theta_d);
  *ih = static_cast<int>(idx / n_theta_d);
}

// MERL (Matusik et al. 2003, BRDFRead.cpp): theta_h index = 90 sqrt(theta_h / (pi/2)).
double Grid::ThetaHCoord(double theta_h) const {
  const double t = std::max(theta_h, 0.0) / kHalfPi;
  return n_theta_h * (theta_h_mapping == ThetaHMapping::kSqrt ? std::sqrt(t) : t);
}
double Grid::ThetaDCoord(double theta_d) const { return n_theta_d * theta_d / kHalfPi; }
double Grid::PhiDCoord(double phi_d) const { return n_phi_d * phi_d / kPi; }

double Grid::ThetaHAt(double u) const {
  const double t = u / n_theta_h;
  return kHalfPi * (theta_h_mapping == ThetaHMapping::kSqrt ? t * t : t);
}
double Grid::ThetaDAt(double u) const { return kHalfPi * u / n_theta_d; }
double Grid::PhiDAt(double u) const { return kPi * u / n_phi_d; }

HalfDiffAngles Grid::CellCentre(int ih, int id, int ip) const {
  return {ThetaHAt(ih + 0.5), ThetaDAt(id + 0.5), PhiDAt(ip + 0.5)};
}
HalfDiffAngles Grid::CellCentre(std::size_t idx) const {
  int ih, id, ip;
  Unindex(idx, &ih, &id, &ip);
  return CellCentre(ih, id, ip);
}

std::size_t Grid::CellOf(const HalfDiffAngles& a) const {
  auto bin = [](double u, int n) {
    return std::clamp(static_cast<int>(std::floor(u)), 0, n - 1);
  };
  double phi = std::fmod(a.phi_d, kPi);
  if (phi < 0) phi += kPi;
  return Index(bin(ThetaHCoord(a.theta_h), n_theta_h), bin(ThetaDCoord(a.theta_d), n_theta_d),
               bin(PhiDCoord(phi), n_phi_d));
}

bool Grid::CellAboveHorizon(std::size_t idx) const {
  Vec3 wi, wo;
  FromHalfDiff(CellCentre(idx), 0.0, &wi, &wo);
  return wi.z > 0 && wo.z > 0;
}

std::vector<std::uint8_t> Grid::AboveHorizonMask() const {
  // CellAboveHorizon's FromHalfDiff(centre, phi_h = 0) spelt out (models/geometry.h): with
  // d = (sin td cos pd, sin td sin pd, cos td) and (s, c) = (sin th, cos th),
  //   wi = RotateY(d, th):  wi.x = c d.x + s d.z,  wi.z = -s d.x + c d.z
  //   h = (s, 0, c),  wo.z = 2 (wi.h) c - wi.z,  wi.h = wi.x s + wi.z c
  // in the same order of operations (the rotation by phi_h = 0 and the products with h's zero
  // y component add zeros only), so each cell's answer is CellAboveHorizon's.
  std::vector<double> sin_h(n_theta_h), cos_h(n_theta_h), sin_d(n_theta_d), cos_d(n_theta_d),
      cos_p(n_phi_d);
  for (int i = 0; i < n_theta_h; ++i) {
    const double t = CellCentre(i, 0, 0).theta_h;
    sin_h[i] = std::sin(t);
    cos_h[i] = std::cos(t);
  }
  for (int i = 0; i < n_theta_d; ++i) {
    const double t = CellCentre(0, i, 0).theta_d;
    sin_d[i] = std::sin(t);
    cos_d[i] = std::cos(t);
  }
  for (int i = 0; i < n_phi_d; ++i) cos_p[i] = std::cos(CellCentre(0, 0, i).phi_d);
  std::vector<std::uint8_t> mask(NumCells());
  for (int ih = 0; ih < n_theta_h; ++ih) {
    const double s = sin_h[ih], c = cos_h[ih];
    for (int id = 0; id < n_theta_d; ++id) {
      std::uint8_t* row = &mask[Index(ih, id, 0)];
      const double dz = cos_d[id];
      for (int ip = 0; ip < n_phi_d; ++ip) {
        const double dx = sin_d[id] * cos_p[ip];
        const double wi_x = c * dx + s * dz;
        const double wi_z = -s * dx + c * dz;
        const double wo_z = 2.0 * (wi_x * s + wi_z * c) * c - wi_z;
        row[ip] = wi_z > 0 && wo_z > 0;
      }
    }
  }
  return mask;
}

Table Table::Empty(const Grid& grid) {
  Table t = ForOverwrite(grid);
  std::fill(t.rgb.begin(), t.rgb.end(), 0.0);
  std::fill(t.valid.begin(), t.valid.end(), std::uint8_t{0});
  return t;
}

Table Table::ForOverwrite(const Grid& grid) {
  Table t;
  t.grid = grid;
  // The value array (35 MB for MERL) faulted in by one system call (the kernel zeroes the
  // pages), not written.
  t.rgb.reserve(3 * grid.NumCells());
  PrefaultForWrite(t.rgb.data(), 3 * grid.NumCells() * sizeof(double));
  t.rgb.resize(3 * grid.NumCells());
  t.valid.resize(grid.NumCells());
  return t;
}

std::size_t Table::CountValid() const {
  return static_cast<std::size_t>(std::count(valid.begin(), valid.end(), std::uint8_t{1}));
}

std::optional<std::array<double, 3>> Table::LookupNearest(const HalfDiffAngles& a) const {
  const std::size_t idx = grid.CellOf(a);
  if (!valid[idx]) return std::nullopt;
  return std::array<double, 3>{rgb[3 * idx], rgb[3 * idx + 1], rgb[3 * idx + 2]};
}

TrilinearTaps Grid::TrilinearTapsAt(const HalfDiffAngles& a) const {
  double phi = std::fmod(a.phi_d, kPi);
  if (phi < 0) phi += kPi;
  // Coordinates relative to cell centres.
  const double uh = std::clamp(ThetaHCoord(a.theta_h) - 0.5, 0.0, n_theta_h - 1.0);
  const double ud = std::clamp(ThetaDCoord(a.theta_d) - 0.5, 0.0, n_theta_d - 1.0);
  const double up = PhiDCoord(phi) - 0.5;  // periodic
  const int h0 = std::min(static_cast<int>(uh), n_theta_h - 1);
  const int d0 = std::min(static_cast<int>(ud), n_theta_d - 1);
  const int p0 = static_cast<int>(std::floor(up));
  const double fh = uh - h0, fd = ud - d0, fp = up - p0;
  TrilinearTaps taps;
  for (int a_h = 0; a_h < 2; ++a_h) {
    const int ih = std::min(h0 + a_h, n_theta_h - 1);
    const double wh = a_h ? fh : 1 - fh;
    for (int a_d = 0; a_d < 2; ++a_d) {
      const int id = std::min(d0 + a_d, n_theta_d - 1);
      const double wd = a_d ? fd : 1 - fd;
      for (int a_p = 0; a_p < 2; ++a_p) {
        const int ip = ((p0 + a_p) % n_phi_d + n_phi_d) % n_phi_d;
        const double w = wh * wd * (a_p ? fp : 1 - fp);
        if (w <= 0) continue;
        taps.cell[taps.count] = static_cast<std::uint32_t>(Index(ih, id, ip));
        taps.weight[taps.count] = w;
        ++taps.count;
      }
    }
  }
  return taps;
}

std::optional<std::array<double, 3>> Table::LookupTaps(const TrilinearTaps& taps) const {
  std::array<double, 3> acc{0, 0, 0};
  double wsum = 0;
  for (int k = 0; k < taps.count; ++k) {
    const std::size_t idx = taps.cell[k];
    if (!valid[idx]) continue;
    const double w = taps.weight[k];
    for (int c = 0; c < 3; ++c) acc[c] += w * rgb[3 * idx + c];
    wsum += w;
  }
  if (wsum <= 0) return std::nullopt;
  for (double& v : acc) v /= wsum;
  return acc;
}

std::optional<std::array<double, 3>> Table::LookupTrilinear(const HalfDiffAngles& a) const {
  return LookupTaps(grid.TrilinearTapsAt(a));
}

std::optional<std::array<double, 3>> Table::LookupTrilinear(const Vec3& wi, const Vec3& wo) const {
  return LookupTrilinear(ToHalfDiff(wi, wo));
}

}  // namespace brdfit
