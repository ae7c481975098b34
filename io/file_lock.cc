#include "io/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fmt/core.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.h"
#include "io/temp_files.h"

namespace brdfit {

namespace fs = std::filesystem;

fs::path LockPathFor(const fs::path& output) {
  const fs::path dir = output.has_parent_path() ? output.parent_path() : fs::path(".");
  std::string name = output.filename().string();
  name.insert(0, 1, '.');
  name += ".lock";
  return dir / name;
}

namespace {

std::string HolderOf(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string s = n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.find_first_not_of("0123456789") == std::string::npos ? s : "";
}

}  // namespace

OutputLock::OutputLock(const fs::path& output) : lock_path_(LockPathFor(output)) {
  // Retry when the file we locked was unlinked by its previous holder in between.
  for (int attempt = 0; attempt < 100; ++attempt) {
    // O_NOFOLLOW: a symbolic link planted under the lock's name would have the pid written
    // through it into whatever it points to (an input, another user's file).
    const int fd = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) {
      const int err = errno;
      throw OutputError(output, "cannot create lock file " + lock_path_.string() + ": " +
                                    (err == ELOOP ? std::string("it is a symbolic link (remove it)")
                                                  : std::strerror(err)));
    }
    // Only a file of its own: a hard link to another file would be truncated by the pid.
    struct stat own {};
    if (::fstat(fd, &own) != 0 || !S_ISREG(own.st_mode) || own.st_nlink != 1) {
      ::close(fd);
      throw OutputError(output, "the lock file " + lock_path_.string() +
                                    " is not a regular file of its own (a hard link or a special "
                                    "file); remove it");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string pid = HolderOf(fd);
      ::close(fd);
      if (err == EWOULDBLOCK) {
        throw OutputError(output, fmt::format("is being written by another brdfit process{}; "
                                              "wait for it to finish or choose another -o "
                                              "(lock {})",
                                              pid.empty() ? "" : " (pid " + pid + ")",
                                              lock_path_.string()));
      }
      throw OutputError(output, "cannot lock " + lock_path_.string() + ": " + std::strerror(err));
    }
    struct stat a {}, b {};
    if (::fstat(fd, &a) == 0 && ::stat(lock_path_.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
        a.st_ino == b.st_ino) {
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
        // The pid is only for the message of a second writer; the lock holds without it.
      }
      fd_ = fd;
      RemoveOnInterrupt(lock_path_);
      return;
    }
    ::close(fd);  // the lock file we hold was replaced: take the new one
  }
  throw OutputError(output, "cannot take the lock " + lock_path_.string());
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ForgetOnInterrupt(lock_path_);
  ::unlink(lock_path_.c_str());  // while still holding it: a waiter retries on the new file
  ::close(fd_);
}

}  // namespace brdfit
