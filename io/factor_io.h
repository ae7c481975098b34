// A factorization on disk (docs/formats.md, "Factorization files"): three files in one folder,
//   <stem>.p.exr        factor p, float32 RGB OpenEXR (io/exr_texture.h)
//   <stem>.q.exr        factor q, float32 RGB OpenEXR
//   <stem>.factor.json  sidecar: format, parameterization, formula, maps, units, gauge, solver
//                       options, source, statistics, metrics; names the two EXR files.
// Each EXR header repeats what is needed to use it alone (string attributes "brdfit:*").
// The sidecar is written last: a complete sidecar means complete textures.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/exr_texture.h"

namespace brdfit {

inline constexpr const char* kFactorFormat = "brdfit-factorization";
inline constexpr int kFactorFormatVersion = 1;

// EXR attribute names this layer owns (the rest are the caller's, see pipeline/factor_export.h).
inline constexpr const char* kExrAttrFormat = "brdfit:format";
inline constexpr const char* kExrAttrParameterization = "brdfit:parameterization";
inline constexpr const char* kExrAttrFactor = "brdfit:factor";

struct FactorTextureFile {
  RgbImage image;
  ExrAttributes attributes;
};

struct FactorFiles {
  nlohmann::json sidecar;  // must hold "parameterization" (string)
  FactorTextureFile p, q;
};

struct FactorPaths {
  std::filesystem::path json, p, q;
};

// Throws OutputError if `stem` is not one safe path component (core/file_stem.h).
FactorPaths FactorFilePaths(const std::filesystem::path& dir, const std::string& stem);

// Writes p and q, then the sidecar, each atomically. Adds "format", "format_version" and
// "textures": {"p": {"file", "width", "height"}, "q": {...}} to the sidecar (keeping other
// members of "textures"), and the attributes brdfit:format, brdfit:parameterization and
// brdfit:factor to each EXR. Throws InputError if the sidecar has no parameterization.
void WriteFactorFiles(const FactorPaths& paths, FactorFiles files);

// Reads a sidecar and the two EXRs it names (paths relative to the sidecar's folder). Throws
// InputError naming the offending file: not JSON, wrong format or version, missing member,
// EXR missing or damaged, EXR attributes disagreeing with the sidecar (factor name,
// parameterization), size different from the sidecar's.
FactorFiles ReadFactorFiles(const std::filesystem::path& json_path);

}  // namespace brdfit
