#include "io/atomic_file.h"

#include <fcntl.h>
#include <fmt/core.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
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

namespace {

// Writes size bytes to tmp, every write and the close checked; errors name dest.
void WriteBytesTo(const fs::path& tmp, const fs::path& dest, const void* data, std::size_t size) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw OutputError(dest, fmt::format("cannot create temporary file {}: {}", tmp.string(),
                                        std::strerror(errno)));
  }
  const char* p = static_cast<const char*>(data);
  for (std::size_t left = size; left > 0;) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw OutputError(dest, fmt::format("write failed: {}", std::strerror(err)));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // Some file systems report a full disk or an I/O error only when the file is closed.
  if (::close(fd) != 0) {
    throw OutputError(dest, fmt::format("write failed at close: {}", std::strerror(errno)));
  }
}

}  // namespace

void WriteBytesAtomically(const fs::path& dest, const void* data, std::size_t size) {
  WriteFileAtomically(dest, [&](const fs::path& tmp) { WriteBytesTo(tmp, dest, data, size); });
}

void WriteTwoFilesAtomically(const fs::path& first, const std::string& first_bytes,
                             const fs::path& second, const void* second_data,
                             std::size_t second_size) {
  WriteFileAtomically(first, [&](const fs::path& tmp_first) {
    WriteBytesTo(tmp_first, first, first_bytes.data(), first_bytes.size());
    WriteFileAtomically(second, [&](const fs::path& tmp_second) {
      WriteBytesTo(tmp_second, second, second_data, second_size);
    });
  });
}

void WriteTextAtomically(const fs::path& dest, const std::string& contents) {
  WriteBytesAtomically(dest, contents.data(), contents.size());
}

}  // namespace brdfit
