#include "io/atomic_file.h"

#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <system_error>

#include "core/error.h"
#include "io/temp_files.h"

namespace brdfit {

namespace fs = std::filesystem;

void WriteFileAtomically(const fs::path& dest,
                         const std::function<void(const fs::path& tmp)>& write) {
  std::error_code ec;
  if (fs::is_directory(dest, ec)) throw OutputError(dest, "is a directory");
  // Never rename over a FIFO, device or socket (io/output_policy.h checks this up front too).
  struct stat st {};
  if (::stat(dest.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    throw OutputError(dest, "is not a regular file; refusing to replace it");
  }
  const fs::path tmp = TemporaryFor(dest);
  BeginTemporary(tmp);
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    EndTemporary(tmp);
    throw;
  }
  fs::rename(tmp, dest, ec);
  if (ec) {
    fs::remove(tmp, ec);
    EndTemporary(tmp);
    throw OutputError(dest, "cannot rename temporary file into place: " + ec.message());
  }
  EndTemporary(tmp);
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
