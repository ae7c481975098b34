// `brdfit export`: one fit of a report (or of the JSON parameters) written for a target
// renderer (docs/exports.md), atomically.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "export/targets.h"
#include "io/factor_io.h"
#include "io/fit_report.h"

namespace brdfit::exports {

enum class Format { kGltf, kGlb, kMitsuba, kPbrt, kBlender, kThreejs };

// "gltf" | "glb" | "mitsuba" | "pbrt" | "blender" | "threejs"; throws InputError otherwise.
Format FormatFromString(const std::string& s);
// The name --format takes for `format`: "gltf", "glb", ...
const char* FormatName(Format format);

// What exporting `fit` in `format` approximates (each target's own check, export/targets.h):
// empty when exact; a model export cannot read gives one entry. kThreejs evaluates every
// analytic model exactly.
Fidelity FidelityOf(const FitResult& fit, Format format);

// The entry to export among `entries`: those of `material` (any when empty and there is one
// material), of `model` when given; else the chosen fit when the format expresses it exactly,
// else the best fit the format expresses exactly, else among the exportable fits: the fewest
// lobes left out (Fidelity::dropped_lobes), then the chosen fit, then the best. "Best" is the
// rendered score of the model choice (core/model_choice.h, RenderedScoreDb), then the lowest
// log_rmse for fits without one.
// kThreejs evaluates every analytic model exactly: `model`, else the chosen fit, else the best.
// A factorization entry (io/fit_report.h) is never selected: its sidecar exports (threejs).
// Throws InputError naming what is available.
const FitReportEntry& SelectEntry(const std::vector<FitReportEntry>& entries,
                                  const std::string& material, const std::string& model,
                                  Format format);

// When `selected` is not its material's chosen analytic fit: which fit brdfit chose, why the
// format does not take it (not exportable, or only approximately) and how far the exported fit's
// rendered score is below it (dB). Empty when the chosen fit is exported or there is none.
std::string SelectionNote(const std::vector<FitReportEntry>& entries,
                          const FitReportEntry& selected, Format format);

// The file extension of a format's main output: ".gltf", ".glb", ".xml" (Mitsuba 3), ".pbrt",
// ".py" (Blender), ".mjs" (three.js).
const char* FormatExtension(Format format);

// The materials of `entries` in the order they first appear.
std::vector<std::string> MaterialsOf(const std::vector<FitReportEntry>& entries);

// One file name per material for `export -o DIR`: the name with every character outside
// [A-Za-z0-9._-] replaced by '_' (no path separator, no shell or markup character), a leading
// '.' or '-' replaced too (no hidden file, no option), at most 96 characters, "material" when
// nothing is left; a name already given (case-insensitively: the file systems that fold case)
// gets "-2", "-3", ...; then the format's extension. In the order given.
std::vector<std::string> MaterialFileNames(const std::vector<std::string>& materials,
                                           Format format);

struct ExportOutcome {
  std::vector<std::filesystem::path> written;
  Fidelity fidelity;
};

// Writes `out` (and, for kGltf, OUT_STEM.bin next to it). kThreejs needs `brdf_glsl`, the
// preview's GLSL of the model (preview::AnalyticBrdfSource, composed by the caller: export/
// does not include preview/).
ExportOutcome WriteExport(const FitReportEntry& entry, const std::string& fits_path, Format format,
                          const std::filesystem::path& out, const std::string& brdf_glsl = {});

// A factorization (`brdfit factor`'s sidecar `json` and its textures, read by ReadFactorFiles)
// as a three.js ShaderMaterial module; `brdf_glsl` = preview::FactoredBrdfSource of its
// parameterization and rank.
ExportOutcome WriteFactoredThreejs(const FactorFiles& files, const std::filesystem::path& json,
                                   const std::string& brdf_glsl, const std::filesystem::path& out);

}  // namespace brdfit::exports
