// A factorization on disk (docs/formats.md, "Factorization files"): in one folder,
//   <stem>.p.exr, <stem>.q.exr      term 1's factors p and q, float32 RGB OpenEXR
//   <stem>.p2.exr, <stem>.q2.exr    term 2 (rank >= 2), and so on up to the rank
//   <stem>.factor.json              sidecar: format, parameterization, formula, rank, diffuse
//                                   value, maps, units, gauge, solver options, source,
//                                   statistics, metrics; names every EXR file.
// Each EXR header repeats what is needed to use it alone (string attributes "brdfit:*").
// The sidecar is written last: a complete sidecar means complete textures.
//
// Format version 2 (rank and diffuse); version 1 (rank 1, no diffuse: its sidecar has neither
// member) is still read.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/exr_texture.h"

namespace brdfit {

inline constexpr const char* kFactorFormat = "brdfit-factorization";
inline constexpr int kFactorFormatVersion = 2;
inline constexpr int kFactorFormatOldestVersion = 1;  // rank 1, no diffuse
// The highest rank the files hold (factor/factor.h kMaxFactorRank; pipeline/factor_export.cc
// checks they agree).
inline constexpr int kFactorFileMaxRank = 4;

// EXR attribute names this layer owns (the rest are the caller's, see pipeline/factor_export.h).
inline constexpr const char* kExrAttrFormat = "brdfit:format";
inline constexpr const char* kExrAttrParameterization = "brdfit:parameterization";
inline constexpr const char* kExrAttrFactor = "brdfit:factor";

// The name of term k's factor (k from 0): "p", "q" for term 0, then "p2", "q2", "p3", ...; the
// member of the sidecar's "textures", the EXR's brdfit:factor and the middle of its file name.
std::string FactorTextureName(int term, bool q);

struct FactorTextureFile {
  RgbImage image;
  ExrAttributes attributes;
};

struct FactorTermFiles {
  FactorTextureFile p, q;
};

struct FactorFiles {
  nlohmann::json sidecar;  // must hold "parameterization" (string)
  // d = kd / pi, 1/sr, linear RGB, finite and >= 0 (zero: the pure homomorphic form).
  std::array<double, 3> diffuse{0, 0, 0};
  std::vector<FactorTermFiles> terms;  // rank K = terms.size(), in [1, kFactorFileMaxRank]
};

struct FactorTermPaths {
  std::filesystem::path p, q;
};
struct FactorPaths {
  std::filesystem::path json;
  std::vector<FactorTermPaths> terms;
  // Every file, the textures first and the sidecar last (the order they are written in).
  std::vector<std::filesystem::path> All() const;
};

// The files of a rank-`rank` factorization. Throws OutputError if `stem` is not one safe path
// component (core/file_stem.h) or the rank is outside [1, kFactorFileMaxRank].
FactorPaths FactorFilePaths(const std::filesystem::path& dir, const std::string& stem,
                            int rank = 1);

// Writes every term's p and q, then the sidecar, each atomically. `paths` must have one entry
// per term. Adds "format", "format_version", "rank", "diffuse" (and "kd" = pi * diffuse, for
// people: readers use "diffuse") and "textures": {"p": {"file", "width", "height"}, "q": ...,
// "p2": ...} to the sidecar (keeping other members of "textures"), and the attributes
// brdfit:format, brdfit:parameterization and brdfit:factor to each EXR. Throws InputError if
// the sidecar has no parameterization, the rank is outside [1, kFactorFileMaxRank] or differs
// from the paths', or the diffuse value is negative or not finite.
void WriteFactorFiles(const FactorPaths& paths, FactorFiles files);

// The members of a parsed sidecar that define its form, checked as ReadFactorFiles checks them
// (InputError naming json_path): format_version in [kFactorFormatOldestVersion,
// kFactorFormatVersion]; version 2's rank (an integer in [1, kFactorFileMaxRank]) and diffuse
// (three finite numbers >= 0); version 1 is rank 1 with a zero diffuse value. The format member
// is the caller's to check.
struct FactorSidecarHeader {
  int version = kFactorFormatVersion;
  int rank = 1;
  std::array<double, 3> diffuse{0, 0, 0};
};
FactorSidecarHeader ReadFactorSidecarHeader(const nlohmann::json& sidecar,
                                            const std::filesystem::path& json_path);

// Reads a sidecar and the EXRs it names (paths relative to the sidecar's folder). Throws
// InputError naming the offending file: not JSON, wrong format or version, missing member,
// rank outside [1, kFactorFileMaxRank], diffuse not three finite numbers >= 0, a texture of the
// rank missing from "textures" or one named beyond it, EXR missing or damaged, EXR attributes
// disagreeing with the sidecar (factor name, parameterization), size different from the
// sidecar's.
FactorFiles ReadFactorFiles(const std::filesystem::path& json_path);

}  // namespace brdfit
