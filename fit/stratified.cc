#include "fit/stratified.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <numeric>

namespace brdfit {

namespace {

// Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom Number Generators" (SplitMix64).
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t Next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, n); the modulo bias (n / 2^64) is negligible for table sizes.
  std::size_t Below(std::size_t n) { return static_cast<std::size_t>(Next() % n); }
};

}  // namespace

Selection SelectStratified(const std::vector<int>& stratum, const std::vector<double>& weight,
                           std::size_t n, std::uint64_t seed, double allocation_power) {
  assert(stratum.size() == weight.size());
  Selection sel;
  const std::size_t total = stratum.size();
  if (n >= total) {
    sel.kept.resize(total);
    std::iota(sel.kept.begin(), sel.kept.end(), std::size_t{0});
    sel.factor.assign(total, 1.0);
    return sel;
  }
  std::map<int, std::vector<std::size_t>> members;
  std::map<int, double> w_sum;
  for (std::size_t u = 0; u < total; ++u) {
    members[stratum[u]].push_back(u);
    w_sum[stratum[u]] += weight[u];
  }
  double norm = 0;
  for (const auto& [s, w] : w_sum) norm += std::pow(std::max(w, 0.0), allocation_power);

  std::vector<std::pair<std::size_t, double>> picked;  // (unit, factor)
  picked.reserve(n + kMinPerStratum * members.size());
  for (auto& [s, units] : members) {
    const double share =
        norm > 0 ? std::pow(std::max(w_sum[s], 0.0), allocation_power) / norm : 0.0;
    std::size_t ns = static_cast<std::size_t>(std::llround(share * static_cast<double>(n)));
    ns = std::clamp(ns, std::min(units.size(), kMinPerStratum), units.size());
    // Partial Fisher-Yates: the first ns entries become a uniform sample without replacement.
    SplitMix64 rng{seed * 0x2545f4914f6cdd1dULL + static_cast<std::uint64_t>(s) + 1};
    for (std::size_t i = 0; i < ns; ++i) {
      std::swap(units[i], units[i + rng.Below(units.size() - i)]);
    }
    double kept_w = 0;
    for (std::size_t i = 0; i < ns; ++i) kept_w += weight[units[i]];
    const double factor = kept_w > 0 ? w_sum[s] / kept_w : 0.0;
    for (std::size_t i = 0; i < ns; ++i) picked.emplace_back(units[i], factor);
  }
  std::sort(picked.begin(), picked.end());
  for (const auto& [u, f] : picked) {
    sel.kept.push_back(u);
    sel.factor.push_back(f);
  }
  return sel;
}

}  // namespace brdfit
