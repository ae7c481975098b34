// A small report with every section the HTML writer draws: two materials with fits (true and
// perturbed parameters of the generating model), a failed fit and a factorization-like entry,
// θh slices on a synthetic table, bench points with several budgets, and one PNG render.
#pragma once

#include <filesystem>

#include "report/report_model.h"

namespace brdfit::testing {

// Writes the render PNG (and nothing else) into `dir`.
report::Report MakeFixtureReport(const std::filesystem::path& dir);

}  // namespace brdfit::testing
