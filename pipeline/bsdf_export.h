// `brdfit export X --format bsdf`: a fit, a factorization or a table (a measurement converted)
// written as an RGL `.bsdf` file (core/rgl_bsdf_build.h builds it, io/rgl_bsdf_file.h writes
// it), the format pbrt-v4's and Mitsuba's `measured` material read (docs/exports.md).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/rgl_bsdf_build.h"
#include "core/table.h"
#include "io/fit_report.h"

namespace brdfit::pipeline {

struct BsdfExport {
  std::string source;  // what was written, in words ("lambert+ggx fit of gold", "table t.binary")
  RglBuildReport build;
};

// The fits an input of `export --format bsdf` holds, read once, or nullopt when it is a table
// (a measurement converted): nbrdf:NAME, a MERL or .bsdf file, or an HDF5 file that is not a
// fit report. A JSON file is fits; a damaged fit report's error is rethrown.
std::optional<std::vector<FitReportEntry>> BsdfInputFits(const std::string& input);

// The fit of a report entry (an analytic model at its parameters). InputError if its model is
// unknown or its parameters do not match.
BsdfExport ExportFitAsBsdf(const FitReportEntry& entry, RglBuildOptions options,
                           const std::filesystem::path& out);
// A factorization from its sidecar (and textures beside it).
BsdfExport ExportFactorAsBsdf(const std::filesystem::path& sidecar, RglBuildOptions options,
                              const std::filesystem::path& out);
// A table by trilinear lookups (Table::LookupTrilinear); a direction whose eight neighbours are
// all masked becomes an unmeasured sample (the file's `valid` field).
BsdfExport ExportTableAsBsdf(const Table& table, const std::string& name, RglBuildOptions options,
                             const std::filesystem::path& out);

}  // namespace brdfit::pipeline
