#include "io/factor_io.h"

#include <fmt/core.h>

#include <utility>

#include "io/atomic_file.h"
#include "core/error.h"
#include "core/file_stem.h"
#include "io/input_file.h"

namespace brdfit {
namespace {

constexpr const char* kNames[2] = {"p", "q"};

std::string FormatTag() {
  return fmt::format("{} {}", kFactorFormat, kFactorFormatVersion);
}

}  // namespace

FactorPaths FactorFilePaths(const std::filesystem::path& dir, const std::string& stem) {
  if (SafeFileStem(stem) != stem) {  // a name from inside a file must not climb out of dir
    throw OutputError(dir / stem, "not a safe file name (core/file_stem.h SafeFileStem)");
  }
  return {dir / (stem + ".factor.json"), dir / (stem + ".p.exr"), dir / (stem + ".q.exr")};
}

void WriteFactorFiles(const FactorPaths& paths, FactorFiles files) {
  nlohmann::json& j = files.sidecar;
  if (!j.is_object() || !j.contains("parameterization") || !j["parameterization"].is_string()) {
    throw InputError(paths.json, "factorization sidecar needs a 'parameterization' string");
  }
  const std::string param = j["parameterization"].get<std::string>();
  j["format"] = kFactorFormat;
  j["format_version"] = kFactorFormatVersion;
  FactorTextureFile* tex[2] = {&files.p, &files.q};
  const std::filesystem::path* exr[2] = {&paths.p, &paths.q};
  for (int k = 0; k < 2; ++k) {
    ExrAttributes& a = tex[k]->attributes;
    a[kExrAttrFormat] = FormatTag();
    a[kExrAttrParameterization] = param;
    a[kExrAttrFactor] = kNames[k];
    WriteRgbExr(*exr[k], tex[k]->image, a);
    nlohmann::json& t = j["textures"][kNames[k]];
    t["file"] = exr[k]->filename().string();
    t["width"] = tex[k]->image.width;
    t["height"] = tex[k]->image.height;
  }
  WriteTextAtomically(paths.json, j.dump(2) + "\n");
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
  if (!j.contains("format_version") || !j["format_version"].is_number_integer() ||
      j["format_version"].get<int>() != kFactorFormatVersion) {
    throw InputError(json_path, fmt::format("unsupported format_version (this reader: {})",
                                            kFactorFormatVersion));
  }
  if (!j.contains("parameterization") || !j["parameterization"].is_string()) {
    throw InputError(json_path, "missing 'parameterization'");
  }
  const std::string param = j["parameterization"].get<std::string>();
  FactorTextureFile* tex[2] = {&f.p, &f.q};
  for (int k = 0; k < 2; ++k) {
    const auto t = j.contains("textures") && j["textures"].is_object()
                       ? j["textures"].value(kNames[k], nlohmann::json())
                       : nlohmann::json();
    if (!t.is_object() || !t.contains("file") || !t["file"].is_string() || !t.contains("width") ||
        !t.contains("height")) {
      throw InputError(json_path,
                       fmt::format("missing textures.{} (file, width, height)", kNames[k]));
    }
    const std::filesystem::path exr = json_path.parent_path() / t["file"].get<std::string>();
    tex[k]->image = ReadRgbExr(exr, &tex[k]->attributes);
    const ExrAttributes& a = tex[k]->attributes;
    auto attr = [&](const char* name) {
      auto it = a.find(name);
      return it == a.end() ? std::string("(missing)") : it->second;
    };
    if (attr(kExrAttrFactor) != kNames[k]) {
      throw InputError(exr, fmt::format("attribute {} is '{}', the sidecar {} names it factor {}",
                                        kExrAttrFactor, attr(kExrAttrFactor),
                                        json_path.filename().string(), kNames[k]));
    }
    if (attr(kExrAttrParameterization) != param) {
      throw InputError(
          exr, fmt::format("attribute {} is '{}', the sidecar says '{}'", kExrAttrParameterization,
                           attr(kExrAttrParameterization), param));
    }
    if (t["width"] != tex[k]->image.width || t["height"] != tex[k]->image.height) {
      throw InputError(
          exr, fmt::format("image is {} x {}, the sidecar says {} x {}", tex[k]->image.width,
                           tex[k]->image.height, t["width"].dump(), t["height"].dump()));
    }
  }
  return f;
}

}  // namespace brdfit
