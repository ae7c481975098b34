#include "io/output_policy.h"

#include <sys/stat.h>

#include <optional>

#include "core/error.h"
#include "io/temp_files.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

// What a path resolves to: (device, inode) when it exists, else its weakly canonical form.
struct Identity {
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string canonical;
  bool operator==(const Identity& o) const {
    if (exists != o.exists) return false;
    return exists ? dev == o.dev && ino == o.ino : canonical == o.canonical;
  }
};

Identity IdentityOf(const fs::path& p, struct stat* st_out = nullptr) {
  Identity id;
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
    if (st_out) *st_out = st;
  } else {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
    id.canonical = ec ? fs::absolute(p).lexically_normal().string() : c.string();
  }
  return id;
}

// The problem with an existing path of this type as an output file, or "".
std::string TypeProblem(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a folder, not a file";
  if (S_ISFIFO(st.st_mode)) return "is a FIFO (named pipe); outputs must be regular files";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
    return "is a device node; outputs must be regular files";
  }
  if (S_ISSOCK(st.st_mode)) return "is a socket; outputs must be regular files";
  return "is not a regular file";
}

}  // namespace

void CheckOutputs(const std::vector<fs::path>& inputs, const std::vector<PlannedOutput>& outputs) {
  std::vector<Identity> in_ids;
  for (const fs::path& in : inputs) {
    const Identity id = IdentityOf(in);
    if (id.exists) in_ids.push_back(id);
  }
  std::vector<std::pair<Identity, const PlannedOutput*>> seen;
  for (const PlannedOutput& out : outputs) {
    if (out.path.empty() || out.path == "-") continue;
    struct stat st {};
    const Identity id = IdentityOf(out.path, &st);
    if (id.exists) {
      if (const std::string problem = TypeProblem(st); !problem.empty()) {
        throw OutputError(out.path, out.option + " " + problem);
      }
    }
    for (const Identity& in : in_ids) {
      if (in == id) {
        throw OutputError(out.path, out.option +
                                        " is also an input of this run; refusing to overwrite "
                                        "it (choose another output)");
      }
    }
    for (const auto& [other_id, other] : seen) {
      if (other_id == id) {
        throw OutputError(out.path, out.option + " is the same file as " + other->option +
                                        " (" + other->path.string() +
                                        "); one would overwrite the other");
      }
    }
    seen.emplace_back(id, &out);
  }
  for (const PlannedOutput& out : outputs) {
    if (!out.path.empty() && out.path != "-") RemoveStaleTemporaries(out.path);
  }
}

void CheckOutputFolder(const fs::path& dir, const std::string& option) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) return;
  throw OutputError(dir, option + " must be a folder, and this exists as something else");
}

void MakeOutputFolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::create_directories(dir, ec) && ec) {
    throw OutputError(dir, "cannot create the folder: " + ec.message());
  }
}

}  // namespace brdfit
