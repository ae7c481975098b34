#include "core/table_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace brdfit {

AlbedoEstimate EstimateAlbedo(const Table& t, double theta_i, int n_t, int n_phi) {
  const Vec3 wi = FromSpherical(theta_i, 0.0);
  const double dt = 1.0 / n_t, dphi = kPi / n_phi;
  std::array<double, 3> sum{0, 0, 0};
  double covered = 0, total = 0;
  for (int it = 0; it < n_t; ++it) {
    const double tt = (it + 0.5) * dt;
    const double theta_h = kPi / 2 * tt * tt;
    const double jac_t = kPi * tt * dt;  // d theta_h = pi t dt
    const double sin_h = std::sin(theta_h);
    for (int ip = 0; ip < n_phi; ++ip) {
      const Vec3 h = FromSpherical(theta_h, (ip + 0.5) * dphi);
      const double wi_h = Dot(wi, h);
      if (wi_h <= 0) continue;
      const Vec3 wo = 2.0 * wi_h * h - wi;
      if (wo.z <= 0) continue;
      // cos(theta_o) dwo = cos(theta_o) 4 (wi.h) sin(theta_h) dtheta_h dphi_h, x2 for phi_h < 0.
      const double w = 2.0 * wo.z * 4.0 * wi_h * sin_h * jac_t * dphi;
      total += w;
      const auto f = t.LookupTrilinear(wi, wo);
      if (!f) continue;
      covered += w;
      for (int c = 0; c < 3; ++c) sum[c] += w * (*f)[c];
    }
  }
  AlbedoEstimate a;
  a.theta_i = theta_i;
  a.albedo = sum;
  a.coverage = total > 0 ? covered / total : 0.0;
  return a;
}

TableStats ComputeTableStats(const Table& t, const std::vector<double>& incidence_deg) {
  TableStats s;
  const Grid& g = t.grid;
  s.cells = g.NumCells();
  const std::vector<std::uint8_t> above_horizon = g.AboveHorizonMask();
  for (std::size_t i = 0; i < s.cells; ++i) {
    const bool above = above_horizon[i];
    s.below_horizon += !above;
    if (!t.valid[i]) {
      s.masked_above_horizon += above;
      continue;
    }
    ++s.valid;
    s.valid_below_horizon += !above;
  }
  // One channel at a time through one buffer (a third of the memory of three copies), left
  // uninitialised: every element is written before it is read.
  const std::size_t n = s.valid;
  const auto buffer = std::make_unique_for_overwrite<double[]>(n);
  double* const v = buffer.get();
  for (int c = 0; c < 3; ++c) {
    ChannelSummary& cs = s.channels[c];
    if (n == 0) {
      cs.min = cs.median = cs.max = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    std::size_t k = 0;
    for (std::size_t i = 0; i < s.cells; ++i) {
      if (t.valid[i]) v[k++] = t.Value(i)[c];
    }
    const auto [lo, hi] = std::minmax_element(v, v + n);
    cs.min = *lo;
    cs.max = *hi;
    // Median: the middle element, or the mean of the two middle ones for an even count.
    const std::size_t mid = n / 2;
    std::nth_element(v, v + mid, v + n);
    cs.median = v[mid];
    if (n % 2 == 0) cs.median = 0.5 * (cs.median + *std::max_element(v, v + mid));
  }
  for (double deg : incidence_deg) s.albedo.push_back(EstimateAlbedo(t, deg * kPi / 180.0));
  return s;
}

nlohmann::ordered_json TableStatsToJson(const TableStats& s) {
  nlohmann::ordered_json j;
  j["cells"] = s.cells;
  j["valid"] = s.valid;
  j["invalid"] = s.cells - s.valid;
  j["below_horizon"] = s.below_horizon;
  j["masked_above_horizon"] = s.masked_above_horizon;
  const std::size_t above = s.cells - s.below_horizon;
  j["missing_fraction_above_horizon"] =
      above ? static_cast<double>(s.masked_above_horizon) / static_cast<double>(above) : 0.0;
  j["valid_below_horizon"] = s.valid_below_horizon;
  const char* names[3] = {"R", "G", "B"};
  nlohmann::ordered_json ch;
  for (int c = 0; c < 3; ++c) {
    const ChannelSummary& cs = s.channels[c];
    auto num = [](double v) {
      return std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v);
    };
    ch[names[c]] = {{"min", num(cs.min)}, {"median", num(cs.median)}, {"max", num(cs.max)}};
  }
  j["channels_1_per_sr"] = ch;
  nlohmann::ordered_json al = nlohmann::ordered_json::array();
  for (const auto& a : s.albedo) {
    al.push_back({{"theta_i_deg", a.theta_i * 180.0 / kPi},
                  {"albedo", {a.albedo[0], a.albedo[1], a.albedo[2]}},
                  {"coverage", a.coverage}});
  }
  j["directional_albedo"] = al;
  return j;
}

}  // namespace brdfit
