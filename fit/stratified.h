// Stratified selection of a subset of weighted units (samples), shared by the random budget,
// the initializer's subset and the coarse solve.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace brdfit {

struct Selection {
  std::vector<std::size_t> kept;  // indices into the units, ascending
  std::vector<double> factor;     // per kept unit: weight multiplier (stratum total / kept sum)
};

// Units are grouped by stratum (any integer key). Each stratum s with N_s units of total weight
// W_s gets n_s = clamp(round(n * W_s^p / sum W^p), min(N_s, kMinPerStratum), N_s) units drawn
// uniformly without replacement (p = allocation_power: 1 is proportional allocation, smaller
// values spread samples towards light strata such as the highlight's tiny theta_h bins).
// Kept weights are scaled so that every stratum keeps its total weight (ratio estimator).
// Deterministic: SplitMix64 seeded by (seed, stratum), no std:: distributions.
Selection SelectStratified(const std::vector<int>& stratum, const std::vector<double>& weight,
                           std::size_t n, std::uint64_t seed, double allocation_power);

inline constexpr std::size_t kMinPerStratum = 2;

}  // namespace brdfit
