// A small report with every section the HTML writer draws: two materials with fits (true and
// perturbed parameters of the generating model), a failed fit and a factorization-like entry,
// θh slices on a synthetic table, renders of the first material's best fit, bench points with several budgets, and one PNG render.
#pragma once

#include <cstddef>
#include <filesystem>

#include "report/report_model.h"

namespace brdfit::testing {

// Usable metrics (bin-measure weighting, 80° cut-off) with these errors.
inline FitMetrics Scored(double log_rmse, double cbrt_rmse, double rel_l2, std::size_t cells) {
  FitMetrics m;
  m.ok = true;
  m.log_rmse = log_rmse;
  m.cbrt_rmse = cbrt_rmse;
  m.rel_l2 = rel_l2;
  m.cells = cells;
  m.weighting = "bin-measure";
  m.cutoff_deg = 80;
  return m;
}

// Writes the render PNG (and nothing else) into `dir`.
report::Report MakeFixtureReport(const std::filesystem::path& dir);

}  // namespace brdfit::testing
