#include "core/table_stats.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace brdfit {

AlbedoEstimate EstimateAlbedo(const Table& t, double theta_i, int n_t, int n_phi) {
  const Vec3 wi = FromSpherical(theta_i, 0.0);
  const double dt = 1.0 / n_t, dphi = kPi / n_phi;
  // The nodes' cos and sin of phi_h, the same for every theta_h: h below is FromSpherical's
  // products of the same values (models/geometry.h), computed once per node instead of per
  // direction.
  std::vector<double> cos_phi(static_cast<std::size_t>(n_phi)), sin_phi(cos_phi.size());
  for (int ip = 0; ip < n_phi; ++ip) {
    cos_phi[static_cast<std::size_t>(ip)] = std::cos((ip + 0.5) * dphi);
    sin_phi[static_cast<std::size_t>(ip)] = std::sin((ip + 0.5) * dphi);
  }
  std::array<double, 3> sum{0, 0, 0};
  double covered = 0, total = 0;
  for (int it = 0; it < n_t; ++it) {
    const double tt = (it + 0.5) * dt;
    const double theta_h = kPi / 2 * tt * tt;
    const double jac_t = kPi * tt * dt;  // d theta_h = pi t dt
    const double sin_h = std::sin(theta_h), cos_h = std::cos(theta_h);
    for (int ip = 0; ip < n_phi; ++ip) {
      const std::size_t k = static_cast<std::size_t>(ip);
      const Vec3 h{sin_h * cos_phi[k], sin_h * sin_phi[k], cos_h};
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

namespace {

// A key whose unsigned order is the numeric order of finite doubles: the IEEE 754 bits with the
// sign bit set for a non-negative value and every bit inverted for a negative one (-0 sorts just
// below +0; they compare equal as doubles). FromOrderKey inverts it bit for bit.
std::uint64_t OrderKey(double v) {
  const auto b = std::bit_cast<std::uint64_t>(v);
  return (b >> 63) ? ~b : b | (std::uint64_t{1} << 63);
}
double FromOrderKey(std::uint64_t k) {
  return std::bit_cast<double>((k >> 63) ? k & ~(std::uint64_t{1} << 63) : ~k);
}

// Where ranks lo and hi = lo or lo + 1 fall in a 16-bit histogram: the buckets b_lo <= b_hi
// holding them and `below`, the count in the buckets before b_lo.
struct RankBuckets {
  std::size_t b_lo = 0, b_hi = 0, below = 0;
};
RankBuckets FindRanks(const std::vector<std::uint32_t>& count, std::size_t lo, std::size_t hi) {
  RankBuckets r;
  while (r.below + count[r.b_lo] <= lo) r.below += count[r.b_lo++];
  std::size_t through = r.below + count[r.b_lo];
  r.b_hi = r.b_lo;
  while (through <= hi) through += count[++r.b_hi];
  return r;
}

// The keys of 0-based rank lo and hi = lo or lo + 1 among the valid keys `for_each_key` visits,
// by radix selection 16 bits at a time, given `count`, the first pass's histogram of the top
// digit: when the two ranks fall in different buckets, rank lo is the largest key of its bucket
// and rank hi the smallest of its own (one more pass); else the keys of their bucket are
// gathered and the next digit decides, down to a few thousand keys, which nth_element orders.
template <class ForEachKey>
std::array<std::uint64_t, 2> SelectRanks(std::vector<std::uint32_t>& count,
                                         const ForEachKey& for_each_key, std::size_t lo,
                                         std::size_t hi) {
  int shift = 48;
  const auto digit = [&](std::uint64_t k) { return (k >> shift) & 0xFFFF; };
  // The keys still in play: the source's, until a bucket's are gathered.
  std::vector<std::uint64_t> keys;
  bool gathered = false;
  const auto visit_keys = [&](const auto& visit) {
    if (!gathered) return for_each_key(visit);
    for (const std::uint64_t k : keys) visit(k, true);
  };
  for (;;) {
    const RankBuckets r = FindRanks(count, lo, hi);
    if (r.b_lo != r.b_hi) {
      std::uint64_t k_lo = 0, k_hi = ~std::uint64_t{0};
      visit_keys([&](std::uint64_t k, bool valid) {
        if (valid && digit(k) == r.b_lo) k_lo = std::max(k_lo, k);
        if (valid && digit(k) == r.b_hi) k_hi = std::min(k_hi, k);
      });
      return {k_lo, k_hi};
    }
    std::vector<std::uint64_t> bucket;
    bucket.reserve(count[r.b_lo]);
    visit_keys([&](std::uint64_t k, bool valid) {
      if (valid && digit(k) == r.b_lo) bucket.push_back(k);
    });
    keys = std::move(bucket);
    gathered = true;
    lo -= r.below;
    hi -= r.below;
    if (keys.size() <= 4096 || shift == 0) break;
    // The gathered keys share every digit down to `shift`: the next one orders them.
    shift -= 16;
    std::fill(count.begin(), count.end(), 0u);
    for (const std::uint64_t k : keys) ++count[digit(k)];
  }
  const auto at = [&](std::size_t rank) {
    const auto it = keys.begin() + static_cast<std::ptrdiff_t>(rank);
    std::nth_element(keys.begin(), it, keys.end());
    return *it;
  };
  const std::uint64_t k_lo = at(lo);
  return {k_lo, hi == lo ? k_lo : at(hi)};
}

// Channel c over the valid cells: min, max, and the median (the middle element, or the mean of
// the two middle ones for an even count n), the elements a full sort would put there. One pass
// gives the extremes and the top digit's histogram without branching on the mask (an invalid
// cell counts 0; its value, possibly NaN, is never compared), a second the median's bucket.
ChannelSummary SummarizeChannel(const Table& t, int c, std::size_t n) {
  const std::size_t cells = t.grid.NumCells();
  std::vector<std::uint32_t> count(std::size_t{1} << 16, 0);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ChannelSummary cs{kInf, 0, -kInf};
  for (std::size_t i = 0; i < cells; ++i) {
    const double v = t.Value(i)[c];
    const bool valid = t.valid[i] != 0;
    cs.min = std::min(cs.min, valid ? v : kInf);
    cs.max = std::max(cs.max, valid ? v : -kInf);
    count[OrderKey(v) >> 48] += valid;
  }
  const auto for_each_key = [&](const auto& visit) {
    for (std::size_t i = 0; i < cells; ++i) visit(OrderKey(t.Value(i)[c]), t.valid[i] != 0);
  };
  const std::size_t lo = n % 2 ? n / 2 : n / 2 - 1;
  const std::array<std::uint64_t, 2> k = SelectRanks(count, for_each_key, lo, n / 2);
  cs.median = n % 2 ? FromOrderKey(k[1]) : 0.5 * (FromOrderKey(k[1]) + FromOrderKey(k[0]));
  return cs;
}

}  // namespace

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
  const std::size_t n = s.valid;
  for (int c = 0; c < 3; ++c) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    s.channels[c] = n == 0 ? ChannelSummary{kNaN, kNaN, kNaN} : SummarizeChannel(t, c, n);
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
