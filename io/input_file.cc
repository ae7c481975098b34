#include "io/input_file.h"

#include <fmt/core.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

#include "core/error.h"

namespace brdfit {

namespace fs = std::filesystem;

std::uintmax_t CheckInputFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) throw InputError(path, "no such file");
  if (ec) throw InputError(path, "cannot access: " + ec.message());
  if (st.type() == fs::file_type::directory) throw InputError(path, "is a directory");
  if (st.type() != fs::file_type::regular) throw InputError(path, "is not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot read size: " + ec.message());
  return size;
}

namespace {
struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

FilePtr OpenForReading(const fs::path& path) {
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  return f;
}
}  // namespace

std::vector<char> ReadFilePrefix(const fs::path& path, std::size_t max_bytes) {
  FilePtr f = OpenForReading(path);
  std::vector<char> buf(max_bytes);
  const std::size_t n = std::fread(buf.data(), 1, max_bytes, f.get());
  if (std::ferror(f.get())) throw InputError(path, "read error");
  buf.resize(n);
  return buf;
}

std::vector<char> ReadWholeFile(const fs::path& path) {
  const std::uintmax_t size = CheckInputFile(path);
  FilePtr f = OpenForReading(path);
  std::vector<char> buf(size);
  const std::size_t n = std::fread(buf.data(), 1, buf.size(), f.get());
  if (std::ferror(f.get())) throw InputError(path, "read error");
  buf.resize(n);
  return buf;
}

std::string PrintableExcerpt(std::string_view text, std::size_t max_bytes) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += fmt::format("\\x{:02x}", c);
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

}  // namespace brdfit
