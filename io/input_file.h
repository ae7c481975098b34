// Checks every reader does before parsing: the path exists, is a regular file, and can be read.
// Problems are InputErrors naming the file ("no such file", "is a directory", ...).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace brdfit {

// Throws InputError(path, "no such file" | "is a directory" | "is not a regular file").
// Returns the file size in bytes.
std::uintmax_t CheckInputFile(const std::filesystem::path& path);

// Reads at most max_bytes from the start of a file (after CheckInputFile).
std::vector<char> ReadFilePrefix(const std::filesystem::path& path, std::size_t max_bytes);

// Reads a whole file into memory (after CheckInputFile).
std::vector<char> ReadWholeFile(const std::filesystem::path& path);

}  // namespace brdfit
