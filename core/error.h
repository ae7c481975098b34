// Error tiers (docs/conventions.md, "Errors"): bad input -> brdfit::InputError (message names
// the file and the problem; the CLI prints it on one line and exits 2); broken invariants ->
// assertions; numerical trouble inside a residual -> the residual returns false.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace brdfit {

// Bad input: a file that is missing, malformed or inconsistent; a bad option value.
class InputError : public std::runtime_error {
 public:
  InputError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem), path_(path) {}
  explicit InputError(const std::string& problem) : std::runtime_error(problem) {}
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Failure to write an output (disk full, permission, ...). The destination is untouched.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem) {}
};

}  // namespace brdfit
