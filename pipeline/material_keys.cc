#include "pipeline/material_keys.h"

#include <sys/stat.h>

#include <fmt/core.h>

#include <cstddef>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "core/input_name.h"
#include "io/nbrdf.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;

// The deepest folder that is an ancestor of every path (absolute, lexically normal).
fs::path CommonRoot(const std::vector<fs::path>& files) {
  fs::path root = files.front().parent_path();
  for (const fs::path& f : files) {
    fs::path common;
    auto a = root.begin();
    const fs::path dir = f.parent_path();
    for (auto b = dir.begin(); a != root.end() && b != dir.end() && *a == *b; ++a, ++b) {
      common /= *a;
    }
    root = common;
  }
  return root;
}

}  // namespace

std::vector<std::string> MaterialKeys(const std::vector<std::string>& inputs) {
  std::vector<std::string> keys(inputs.size());
  std::vector<fs::path> files;     // absolute, normal
  std::vector<std::size_t> index;  // input of each file
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (IsNbrdfInput(inputs[i])) {
      keys[i] = MaterialName(inputs[i]);
      continue;
    }
    files.push_back(fs::absolute(fs::path(inputs[i])).lexically_normal());
    index.push_back(i);
  }
  std::vector<fs::path> relative(files.size());
  if (!files.empty()) {
    const fs::path root = CommonRoot(files);
    for (std::size_t k = 0; k < files.size(); ++k) {
      relative[k] = files[k].lexically_relative(root);
      keys[index[k]] = (relative[k].parent_path() / relative[k].stem()).generic_string();
    }
  }
  // Keys shared by two inputs: the files among them keep their extension.
  std::map<std::string, int> count;
  for (const std::string& k : keys) ++count[k];
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (count[keys[index[k]]] > 1) keys[index[k]] = relative[k].generic_string();
  }
  // The same file under two names (a symbolic or hard link): one table, not two materials.
  std::map<std::pair<dev_t, ino_t>, std::size_t> identity;
  for (std::size_t k = 0; k < files.size(); ++k) {
    struct stat st {};
    if (::stat(files[k].c_str(), &st) != 0) continue;  // a missing file is its reader's error
    if (auto [it, fresh] = identity.emplace(std::make_pair(st.st_dev, st.st_ino), index[k]);
        !fresh) {
      throw InputError(
          fmt::format("inputs {} and {} are the same file (a link?); give each "
                      "table once",
                      inputs[it->second], inputs[index[k]]));
    }
  }
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (auto [it, fresh] = seen.emplace(keys[i], i); !fresh) {
      throw InputError(
          fmt::format("inputs {} and {} are the same material '{}' (a table given "
                      "twice?); give each table once",
                      inputs[it->second], inputs[i], keys[i]));
    }
  }
  return keys;
}

}  // namespace brdfit::pipeline
