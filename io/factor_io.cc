#include "io/factor_io.h"

#include <fmt/core.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/file_stem.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "models/geometry.h"

namespace brdfit {
namespace {

std::string FormatTag() {
  return fmt::format("{} {}", kFactorFormat, kFactorFormatVersion);
}

// "p", "q", "p7", "q12": a name of the factor-texture kind (canonical for some rank or not).
bool LooksLikeFactorTexture(const std::string& name) {
  if (name.empty() || (name[0] != 'p' && name[0] != 'q')) return false;
  for (std::size_t i = 1; i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
  }
  return true;
}

// Whether `name` is one of the textures of a rank-`rank` factorization.
bool IsTextureOfRank(const std::string& name, int rank) {
  for (int k = 0; k < rank; ++k) {
    if (name == FactorTextureName(k, false) || name == FactorTextureName(k, true)) return true;
  }
  return false;
}

std::string TextureList(int rank) {
  std::string s;
  for (int k = 0; k < rank; ++k) {
    s += (k ? ", " : "") + FactorTextureName(k, false) + ", " + FactorTextureName(k, true);
  }
  return s;
}

void CheckDiffuse(const std::array<double, 3>& d, const std::filesystem::path& file) {
  for (double v : d) {
    if (!std::isfinite(v) || v < 0) {
      throw InputError(file, fmt::format("diffuse value {} is negative or not finite", v));
    }
  }
}

// An integer member's value, when it is one that fits int64 (a huge value must not wrap onto a
// valid one through a narrowing get<int>()).
std::optional<std::int64_t> Integer(const nlohmann::json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) {
    return std::nullopt;
  }
  return v.get<std::int64_t>();
}

// The sidecar's format_version, checked: an integer this reader knows.
int ReadVersion(const nlohmann::json& j, const std::filesystem::path& json_path) {
  const auto it = j.find("format_version");
  const auto v = it == j.end() ? std::nullopt : Integer(*it);
  if (!v || *v < kFactorFormatOldestVersion || *v > kFactorFormatVersion) {
    throw InputError(json_path, fmt::format("unsupported format_version {} (this reader: {} to {})",
                                            it == j.end() ? std::string("(missing)") : it->dump(),
                                            kFactorFormatOldestVersion, kFactorFormatVersion));
  }
  return static_cast<int>(*v);
}

// Version 2's rank: an integer in [1, kFactorFileMaxRank].
int ReadRank(const nlohmann::json& j, const std::filesystem::path& json_path) {
  const auto it = j.find("rank");
  if (it == j.end()) throw InputError(json_path, "missing 'rank'");
  const auto r = Integer(*it);
  if (!r || *r < 1 || *r > kFactorFileMaxRank) {
    throw InputError(json_path, fmt::format("rank {} is not an integer in [1, {}]", it->dump(),
                                            kFactorFileMaxRank));
  }
  return static_cast<int>(*r);
}

// Version 2's diffuse value: three finite numbers >= 0 (1/sr).
std::array<double, 3> ReadDiffuse(const nlohmann::json& j, const std::filesystem::path& json_path) {
  const auto it = j.find("diffuse");
  if (it == j.end()) throw InputError(json_path, "missing 'diffuse'");
  if (!it->is_array() || it->size() != 3) {
    throw InputError(
        json_path,
        fmt::format("diffuse {} is not an array of three numbers (R, G, B in 1/sr)", it->dump()));
  }
  std::array<double, 3> d{};
  for (int c = 0; c < 3; ++c) {
    const nlohmann::json& v = (*it)[static_cast<std::size_t>(c)];
    if (!v.is_number()) {
      throw InputError(json_path,
                       fmt::format("diffuse {} is not an array of three numbers", it->dump()));
    }
    d[c] = v.get<double>();
  }
  CheckDiffuse(d, json_path);
  return d;
}

}  // namespace

FactorSidecarHeader ReadFactorSidecarHeader(const nlohmann::json& j,
                                            const std::filesystem::path& json_path) {
  if (!j.is_object()) throw InputError(json_path, "not a JSON object");
  FactorSidecarHeader h;
  h.version = ReadVersion(j, json_path);
  // Version 1 is rank 1 without a diffuse value, whatever else its sidecar holds.
  if (h.version >= 2) {
    h.rank = ReadRank(j, json_path);
    h.diffuse = ReadDiffuse(j, json_path);
  }
  return h;
}

std::string FactorTextureName(int term, bool q) {
  const std::string base = q ? "q" : "p";
  return term == 0 ? base : base + std::to_string(term + 1);
}

std::vector<std::filesystem::path> FactorPaths::All() const {
  std::vector<std::filesystem::path> out;
  for (const FactorTermPaths& t : terms) {
    out.push_back(t.p);
    out.push_back(t.q);
  }
  out.push_back(json);
  return out;
}

FactorPaths FactorFilePaths(const std::filesystem::path& dir, const std::string& stem, int rank) {
  if (SafeFileStem(stem) != stem) {  // a name from inside a file must not climb out of dir
    throw OutputError(dir / stem, "not a safe file name (core/file_stem.h SafeFileStem)");
  }
  if (rank < 1 || rank > kFactorFileMaxRank) {
    throw OutputError(dir / stem, fmt::format("rank {} outside [1, {}]", rank, kFactorFileMaxRank));
  }
  FactorPaths paths;
  paths.json = dir / (stem + ".factor.json");
  for (int k = 0; k < rank; ++k) {
    paths.terms.push_back({dir / (stem + "." + FactorTextureName(k, false) + ".exr"),
                           dir / (stem + "." + FactorTextureName(k, true) + ".exr")});
  }
  return paths;
}

void WriteFactorFiles(const FactorPaths& paths, FactorFiles files) {
  nlohmann::json& j = files.sidecar;
  if (!j.is_object() || !j.contains("parameterization") || !j["parameterization"].is_string()) {
    throw InputError(paths.json, "factorization sidecar needs a 'parameterization' string");
  }
  const int rank = static_cast<int>(files.terms.size());
  if (rank < 1 || rank > kFactorFileMaxRank) {
    throw InputError(paths.json, fmt::format("rank {} outside [1, {}]", rank, kFactorFileMaxRank));
  }
  if (paths.terms.size() != files.terms.size()) {
    throw InputError(paths.json,
                     fmt::format("{} terms for the file names of {}", rank, paths.terms.size()));
  }
  CheckDiffuse(files.diffuse, paths.json);
  const std::string param = j["parameterization"].get<std::string>();
  j["format"] = kFactorFormat;
  j["format_version"] = kFactorFormatVersion;
  j["rank"] = rank;
  j["diffuse"] = files.diffuse;
  j["kd"] = {kPi * files.diffuse[0], kPi * files.diffuse[1], kPi * files.diffuse[2]};
  if (!j.contains("textures") || !j["textures"].is_object())
    j["textures"] = nlohmann::json::object();
  // Textures of a higher rank the caller's sidecar may name are not this factorization's.
  for (auto it = j["textures"].begin(); it != j["textures"].end();) {
    it = LooksLikeFactorTexture(it.key()) && !IsTextureOfRank(it.key(), rank)
             ? j["textures"].erase(it)
             : std::next(it);
  }
  for (int k = 0; k < rank; ++k) {
    for (const bool is_q : {false, true}) {
      FactorTextureFile& tex = is_q ? files.terms[k].q : files.terms[k].p;
      const std::filesystem::path& exr = is_q ? paths.terms[k].q : paths.terms[k].p;
      const std::string name = FactorTextureName(k, is_q);
      tex.attributes[kExrAttrFormat] = FormatTag();
      tex.attributes[kExrAttrParameterization] = param;
      tex.attributes[kExrAttrFactor] = name;
      WriteRgbExr(exr, tex.image, tex.attributes);
      nlohmann::json& t = j["textures"][name];
      t["file"] = exr.filename().string();
      t["width"] = tex.image.width;
      t["height"] = tex.image.height;
    }
  }
  // Invalid UTF-8 in a name (a file or HDF5 attribute) becomes U+FFFD rather than an exception.
  WriteTextAtomically(paths.json,
                      j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

FactorFiles ReadFactorFiles(const std::filesystem::path& json_path) {
  const std::vector<char> bytes = ReadWholeFile(json_path);
  FactorFiles f;
  f.sidecar = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
  const nlohmann::json& j = f.sidecar;
  if (j.is_discarded() || !j.is_object()) throw InputError(json_path, "not a JSON object");
  // Type-checked: json::value() throws json::type_error for a non-string member
  // (fuzz/regressions/factor_sidecar/crafted-format-not-string.json).
  if (!j.contains("format") || !j["format"].is_string() ||
      j["format"].get<std::string>() != kFactorFormat) {
    throw InputError(json_path, fmt::format("not a {} sidecar (format member)", kFactorFormat));
  }
  const FactorSidecarHeader header = ReadFactorSidecarHeader(j, json_path);
  if (!j.contains("parameterization") || !j["parameterization"].is_string()) {
    throw InputError(json_path, "missing 'parameterization'");
  }
  const std::string param = j["parameterization"].get<std::string>();
  const int version = header.version, rank = header.rank;
  f.diffuse = header.diffuse;
  const nlohmann::json textures =
      j.contains("textures") && j["textures"].is_object() ? j["textures"] : nlohmann::json();
  if (version >= 2 && textures.is_object()) {
    for (const auto& [name, value] : textures.items()) {
      if (LooksLikeFactorTexture(name) && !IsTextureOfRank(name, rank)) {
        throw InputError(json_path,
                         fmt::format("textures.{}: not a texture of a rank-{} factorization ({})",
                                     name, rank, TextureList(rank)));
      }
    }
  }
  f.terms.resize(static_cast<std::size_t>(rank));
  for (int k = 0; k < rank; ++k) {
    for (const bool is_q : {false, true}) {
      const std::string name = FactorTextureName(k, is_q);
      FactorTextureFile& tex = is_q ? f.terms[k].q : f.terms[k].p;
      const auto t =
          textures.is_object() ? textures.value(name, nlohmann::json()) : nlohmann::json();
      if (!t.is_object() || !t.contains("file") || !t["file"].is_string() || !t.contains("width") ||
          !t.contains("height")) {
        throw InputError(json_path, fmt::format("missing textures.{} (file, width, height) of "
                                                "the rank-{} factorization",
                                                name, rank));
      }
      // A name in the sidecar's own folder: a path ("../x.exr", "/etc/...") would read a file
      // the factorization does not own.
      const std::string file = t["file"].get<std::string>();
      if (file.empty() || std::filesystem::path(file).filename() != file || file.starts_with(".")) {
        throw InputError(json_path, fmt::format("textures.{}.file '{}' is not a file name in the "
                                                "sidecar's folder",
                                                name, file));
      }
      const std::filesystem::path exr = json_path.parent_path() / file;
      tex.image = ReadRgbExr(exr, &tex.attributes);
      // A NaN or Inf texel would be drawn as such; the solver never writes one.
      for (std::size_t i = 0; i < tex.image.rgb.size(); ++i) {
        if (!std::isfinite(tex.image.rgb[i])) {
          const std::size_t pixel = i / 3;
          throw InputError(exr, fmt::format("texel ({}, {}) channel {} is {}",
                                            pixel % static_cast<std::size_t>(tex.image.width),
                                            pixel / static_cast<std::size_t>(tex.image.width),
                                            "RGB"[i % 3], tex.image.rgb[i]));
        }
      }
      auto attr = [&](const char* key) {
        auto it = tex.attributes.find(key);
        return it == tex.attributes.end() ? std::string("(missing)") : it->second;
      };
      if (attr(kExrAttrFactor) != name) {
        throw InputError(exr, fmt::format("attribute {} is '{}', the sidecar {} names it factor {}",
                                          kExrAttrFactor, attr(kExrAttrFactor),
                                          json_path.filename().string(), name));
      }
      if (attr(kExrAttrParameterization) != param) {
        throw InputError(
            exr, fmt::format("attribute {} is '{}', the sidecar says '{}'",
                             kExrAttrParameterization, attr(kExrAttrParameterization), param));
      }
      if (t["width"] != tex.image.width || t["height"] != tex.image.height) {
        throw InputError(
            exr, fmt::format("image is {} x {}, the sidecar {} says {} x {}", tex.image.width,
                             tex.image.height, json_path.filename().string(), t["width"].dump(),
                             t["height"].dump()));
      }
    }
  }
  return f;
}

}  // namespace brdfit
