// Reading back the JSON parameters of `brdfit fit --json` (io/fit_report.h FitParamsJson,
// docs/formats.md "JSON parameters"): the entries a fit report would hold, without the parts the
// JSON leaves out (timings, sample counts, the worst cell).
#pragma once

#include <filesystem>
#include <vector>

#include "io/fit_report.h"

namespace brdfit {

// Throws InputError naming the file and the problem: not JSON, not "brdfit-fit-params", a fit
// whose parameters are not its registered model's (names, order, bounds).
std::vector<FitReportEntry> ReadFitParamsJson(const std::filesystem::path& path);

// A fit report (HDF5) or the JSON parameters, told apart by content.
std::vector<FitReportEntry> ReadFitsAnyFormat(const std::filesystem::path& path);

}  // namespace brdfit
