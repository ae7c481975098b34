// An advisory lock on an output that a run rewrites many times (brdfit fit's report): flock(2)
// on ".<name>.lock" beside it, holding the holder's pid for the message of a second writer.
// The lock file is removed on release (and on interrupt, io/temp_files.h); one left by a
// killed process is harmless: the kernel released its lock.
#pragma once

#include <filesystem>

namespace brdfit {

class OutputLock {
 public:
  // Takes the lock of `output` without waiting. Throws OutputError naming `output` (and the
  // other process's pid when it can be read) if another process holds it.
  explicit OutputLock(const std::filesystem::path& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  const std::filesystem::path& path() const { return lock_path_; }

 private:
  std::filesystem::path lock_path_;
  int fd_ = -1;
};

// ".<name>.lock" beside `output`.
std::filesystem::path LockPathFor(const std::filesystem::path& output);

}  // namespace brdfit
