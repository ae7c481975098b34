#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <system_error>

#include "core/error.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {
fs::path TemporarySibling(const fs::path& dest) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
  std::string name = ".";
  name += dest.filename().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter++);
  return dir / name;
}
}  // namespace

void WriteFileAtomically(const fs::path& dest,
                         const std::function<void(const fs::path& tmp)>& write) {
  std::error_code ec;
  if (fs::is_directory(dest, ec)) throw OutputError(dest, "is a directory");
  const fs::path tmp = TemporarySibling(dest);
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, dest, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw OutputError(dest, "cannot rename temporary file into place: " + ec.message());
  }
}

void WriteTextAtomically(const fs::path& dest, const std::string& contents) {
  WriteFileAtomically(dest, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw OutputError(dest, "cannot create temporary file " + tmp.string());
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) throw OutputError(dest, "write failed (disk full?)");
  });
}

}  // namespace brdfit
