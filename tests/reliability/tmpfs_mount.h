// A small tmpfs mounted for one test (a full or read-only disk), unmounted when it goes out of
// scope, on every path out of the test. Needs CAP_SYS_ADMIN: where mounting is not permitted,
// mounted() is false and why() says so (the test skips with it).
#pragma once

#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

namespace brdfit::testing_cli {

class TmpfsMount {
 public:
  // size_kb of space (tmpfs rounds up to pages); read_only mounts it read-only (and empty).
  TmpfsMount(const std::filesystem::path& dir, int size_kb, bool read_only = false) : dir_(dir) {
    std::filesystem::create_directories(dir_);
    const std::string options = "size=" + std::to_string(size_kb) + "k";
    const unsigned long flags = read_only ? MS_RDONLY : 0;
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", flags, options.c_str()) == 0) {
      mounted_ = true;
    } else {
      why_ = "cannot mount a tmpfs on " + dir_.string() + " (" + std::strerror(errno) +
             "; needs root or CAP_SYS_ADMIN)";
    }
  }
  ~TmpfsMount() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    std::error_code ec;
    std::filesystem::remove(dir_, ec);
  }
  TmpfsMount(const TmpfsMount&) = delete;
  TmpfsMount& operator=(const TmpfsMount&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& why() const { return why_; }
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
  bool mounted_ = false;
  std::string why_;
};

}  // namespace brdfit::testing_cli
