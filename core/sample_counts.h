// What sample preparation (fit/samples.h) kept and dropped from a table, for reports.
#pragma once

#include <cstddef>

namespace brdfit {

struct SampleCounts {
  std::size_t cells = 0;          // cells in the grid
  std::size_t valid = 0;          // valid in the table
  std::size_t nonfinite = 0;      // valid but NaN/Inf in the table: dropped
  std::size_t negative = 0;       // kept, but some channel < 0 (log targets clamp m cos at 0)
  std::size_t beyond_cutoff = 0;  // valid but beyond the cut-off (or grazing): dropped
  std::size_t eligible = 0;       // valid, finite, inside the cut-off
  std::size_t selected = 0;       // cells kept by the budget (== observations)
  bool operator==(const SampleCounts&) const = default;
};

}  // namespace brdfit
