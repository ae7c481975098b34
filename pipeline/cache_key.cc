#include "pipeline/cache_key.h"

#include <cstdio>
#include <fstream>
#include <vector>

#include "core/error.h"

namespace brdfit::pipeline {

std::string Fnv1a64::Hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

std::string FileContentKey(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open");
  Fnv1a64 h;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h.Add(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())));
  }
  return h.Hex();
}

}  // namespace brdfit::pipeline
