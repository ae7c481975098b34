#include "pipeline/inputs.h"

#include <cstdlib>

#include "core/error.h"
#include "core/input_name.h"
#include "io/input_file.h"
#include "io/nbrdf.h"
#include "io/table_io.h"
#include "pipeline/cache_key.h"

namespace brdfit::pipeline {

namespace fs = std::filesystem;

fs::path NbrdfArchive(const std::string& given) {
  if (!given.empty()) return given;
  if (const char* env = std::getenv("BRDFIT_NBRDF_ZIP"); env && *env) return env;
  std::vector<fs::path> candidates = {fs::path("..") / "shared" / "data" / "merl_nbrdf.zip"};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (fs::path d = exe.parent_path(); !d.empty() && d != d.root_path(); d = d.parent_path()) {
      candidates.push_back(d.parent_path() / "shared" / "data" / "merl_nbrdf.zip");
    }
  }
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c, ec)) return c;
  }
  return candidates.front();
}

std::vector<std::string> ExpandInputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  for (const std::string& in : inputs) {
    if (in == std::string(kNbrdfInputPrefix) + "all") {
      const fs::path zip = NbrdfArchive();
      const std::vector<std::string> materials = ListNbrdfMaterials(zip);
      if (materials.empty()) throw InputError(zip, kNoNbrdfMaterials);
      for (const auto& m : materials) out.push_back(std::string(kNbrdfInputPrefix) + m);
    } else {
      out.push_back(in);
    }
  }
  return out;
}

std::vector<fs::path> InputFiles(const std::vector<std::string>& inputs) {
  std::vector<fs::path> out;
  for (const std::string& in : inputs) out.push_back(IsNbrdfInput(in) ? NbrdfArchive() : fs::path(in));
  return out;
}

Table LoadInput(const std::string& input) {
  // A NUL ends the path for the system: "t.h5\0x" would load t.h5 and record "t.h5\0x".
  if (input.find('\0') != std::string::npos) {
    throw InputError("input path contains a NUL byte: " + PrintableExcerpt(input));
  }
  if (!IsNbrdfInput(input)) return LoadTable(input);
  const NbrdfNetwork net = ReadNbrdf(NbrdfArchive(), MaterialName(input));
  Table t = TabulateNbrdf(net, Grid::Merl(), 1).table;
  t.provenance.source = input;
  return t;
}

std::string InputContentKey(const std::string& input) {
  if (!IsNbrdfInput(input)) return FileContentKey(input);
  return FileContentKey(NbrdfArchive()) + "|" + input;
}

}  // namespace brdfit::pipeline
