#include "pipeline/merge_factors.h"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/factor_io.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kSidecarSuffix = ".factor.json";

std::string ReadBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(p, "cannot be read");
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  if (in.bad()) throw InputError(p, "read error");
  return bytes;
}

// The files of a part: its sidecars and the textures they name, sorted by name.
std::vector<std::string> PartFiles(const fs::path& part) {
  std::error_code ec;
  if (!fs::is_directory(part, ec)) throw InputError(part, "not a folder of factorizations");
  std::vector<std::string> names;
  for (const fs::directory_entry& d : fs::directory_iterator(part, ec)) {
    const std::string name = d.path().filename().string();
    if (!d.is_regular_file() || name.size() <= kSidecarSuffix.size() ||
        !name.ends_with(kSidecarSuffix)) {
      continue;
    }
    names.push_back(name);
    // The whole factorization reads as the report, render and export will read it (format,
    // version, rank, diffuse, each EXR whole and finite, its attributes and size): a damaged
    // part is refused here, with the offending file named, not copied.
    ReadFactorFiles(d.path());
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(ReadBytes(d.path()));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(d.path(), std::string("not a factorization sidecar: ") + e.what());
    }
    if (!j.contains("textures") || !j["textures"].is_object()) {
      throw InputError(d.path(), "names no textures");
    }
    for (const auto& [k, t] : j["textures"].items()) {
      if (!t.is_object() || !t.contains("file") || !t["file"].is_string()) {
        throw InputError(d.path(), "texture '" + k + "' names no file");
      }
      const std::string file = t["file"].get<std::string>();
      if (fs::path(file).filename() != file || file.starts_with(".")) {
        throw InputError(d.path(), "texture file '" + file + "' is not a name in its folder");
      }
      if (!fs::is_regular_file(part / file, ec)) {
        throw InputError(part / file, "named by " + name + " but missing");
      }
      names.push_back(file);
    }
  }
  if (ec) throw InputError(part, "cannot be listed: " + ec.message());
  if (names.empty()) throw InputError(part, "holds no factorization (no *.factor.json)");
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

}  // namespace

MergedFactors MergeFactorFolders(const fs::path& out, const std::vector<fs::path>& parts) {
  if (parts.empty()) throw InputError("merge: no factorization folder to merge");
  // The output may not be a part or lie inside one: the merge would write into its input.
  std::error_code ec0;
  const fs::path out_abs = fs::weakly_canonical(fs::absolute(out), ec0);
  for (const fs::path& part : parts) {
    const fs::path part_abs = fs::weakly_canonical(fs::absolute(part), ec0);
    const auto [p_end, o_it] =
        std::mismatch(part_abs.begin(), part_abs.end(), out_abs.begin(), out_abs.end());
    if (p_end == part_abs.end()) {
      throw InputError(out, "is the part " + part.string() +
                                " or inside it: merge into a folder outside every part");
    }
  }
  std::map<std::string, std::size_t> from;  // file name -> part
  std::map<std::string, std::string> bytes;
  MergedFactors m;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    for (const std::string& name : PartFiles(parts[p])) {
      std::string b = ReadBytes(parts[p] / name);
      const auto it = from.find(name);
      if (it == from.end()) {
        from.emplace(name, p);
        bytes.emplace(name, std::move(b));
        continue;
      }
      if (bytes[name] != b) {
        throw InputError(fmt::format(
            "conflicting factorization files: {} differs between {} and {}; refusing to merge "
            "(drop one part, or factor that table again)",
            name, parts[it->second].string(), parts[p].string()));
      }
      ++m.duplicates;
    }
  }
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw OutputError(out, "cannot create the folder: " + ec.message());
  for (const auto& [name, b] : bytes) {
    WriteBytesAtomically(out / name, b.data(), b.size());
    ++m.files;
    m.sidecars += name.ends_with(kSidecarSuffix);
  }
  return m;
}

}  // namespace brdfit::pipeline
