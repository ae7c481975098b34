// `brdfit export`: one fit of a report (or of the JSON parameters) written for a target
// renderer (docs/exports.md), atomically.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "export/targets.h"
#include "io/fit_report.h"

namespace brdfit::exports {

enum class Format { kGltf, kGlb, kMitsuba, kPbrt, kBlender };

// "gltf" | "glb" | "mitsuba" | "pbrt" | "blender"; throws InputError otherwise.
Format FormatFromString(const std::string& s);

// The entry to export among `entries`: those of `material` (any when empty and there is one
// material), of `model` when given, else the exportable one the target expresses exactly
// (lambert+ggx for Mitsuba and Blender, lambert+ggx-hc for the others), else the chosen fit, else the
// exportable fit with the lowest log_rmse. Throws InputError naming what is available.
const FitReportEntry& SelectEntry(const std::vector<FitReportEntry>& entries,
                                  const std::string& material, const std::string& model,
                                  Format format);

struct ExportOutcome {
  std::vector<std::filesystem::path> written;
  Fidelity fidelity;
};

// Writes `out` (and, for kGltf, OUT_STEM.bin next to it).
ExportOutcome WriteExport(const FitReportEntry& entry, const std::string& fits_path, Format format,
                          const std::filesystem::path& out);

}  // namespace brdfit::exports
