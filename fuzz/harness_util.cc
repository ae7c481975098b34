#include "fuzz/harness_util.h"

#include <unistd.h>
#include <zip.h>

#include <cstdio>
#include <cstdlib>
#include <system_error>

namespace brdfit::fuzz {

namespace fs = std::filesystem;

namespace {
fs::path MakeScratchDir() {
  fs::path parent;
  if (const char* env = std::getenv("BRDFIT_FUZZ_TMP"); env && *env) {
    parent = env;
  } else if (std::error_code ec; fs::is_directory("/dev/shm", ec)) {
    parent = "/dev/shm";
  } else {
    parent = fs::temp_directory_path();
  }
  fs::path dir = parent / ("brdfit-fuzz-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

struct ScratchOwner {
  fs::path dir = MakeScratchDir();
  ~ScratchOwner() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};
}  // namespace

const fs::path& ScratchDir() {
  static const ScratchOwner owner;
  return owner.dir;
}

std::size_t OpenFdCount(const fs::path& dir) {
  const std::string prefix = fs::weakly_canonical(dir).string() + "/";
  std::size_t n = 0;
  std::error_code ec;
  for (fs::directory_iterator it("/proc/self/fd", ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code ec2;
    const fs::path target = fs::read_symlink(it->path(), ec2);
    n += !ec2 && target.string().starts_with(prefix);
  }
  return n;
}

fs::path WriteScratch(std::string_view name, const void* data, std::size_t size) {
  const fs::path path = ScratchDir() / std::string(name);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot create scratch file " + path.string());
  const bool ok = size == 0 || std::fwrite(data, 1, size, f) == size;
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path.string());
  return path;
}

std::string ReadAllBytes(const fs::path& path) {
  std::string out;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    char buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) out.append(buf, n);
    std::fclose(f);
  }
  return out;
}

fs::path WriteNbrdfZip(std::string_view name, std::string_view image) {
  const fs::path path = ScratchDir() / std::string(name);
  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (!z) throw std::runtime_error("zip_open failed on " + path.string());
  zip_source_t* src = zip_source_buffer(z, image.data(), image.size(), 0);
  const zip_int64_t idx = src ? zip_file_add(z, "merl_nbrdf/m.h5", src, ZIP_FL_OVERWRITE) : -1;
  if (idx < 0 || zip_set_file_compression(z, static_cast<zip_uint64_t>(idx), ZIP_CM_STORE, 0) ||
      zip_close(z) != 0) {
    if (idx < 0 && src) zip_source_free(src);
    zip_discard(z);
    throw std::runtime_error("cannot build the archive " + path.string());
  }
  return path;
}

}  // namespace brdfit::fuzz
