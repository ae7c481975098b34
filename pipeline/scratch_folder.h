// A folder of its own under the system's temporary directory, removed with everything in it
// when the object goes: for files a command needs for a moment and never shows (entries
// written to be compared, a report of fits made on the spot).
#pragma once

#include <fmt/core.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace brdfit::pipeline {

class ScratchFolder {
 public:
  // /tmp/brdfit-PURPOSE-PID-N
  explicit ScratchFolder(const std::string& purpose) {
    static std::atomic<int> counter{0};
    dir_ = std::filesystem::temp_directory_path() /
           fmt::format("brdfit-{}-{}-{}", purpose, static_cast<long>(::getpid()), counter++);
    std::filesystem::create_directories(dir_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace brdfit::pipeline
