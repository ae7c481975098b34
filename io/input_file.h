// Checks every reader does before parsing: the path exists, is a regular file, and can be read.
// Problems are InputErrors naming the file ("no such file", "is a directory", ...).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace brdfit {

// Throws InputError(path, "no such file" | "is a directory" | "is not a regular file").
// Returns the file size in bytes.
std::uintmax_t CheckInputFile(const std::filesystem::path& path);

// Reads at most max_bytes from the start of a file (after CheckInputFile).
std::vector<char> ReadFilePrefix(const std::filesystem::path& path, std::size_t max_bytes);

// Text taken from inside a file (a library's message quoting a damaged header, a name) made
// safe for a one-line message: bytes outside printable ASCII as \xNN, at most max_bytes of it
// (then "..."). A garbage EXR printed its raw bytes to the terminal.
std::string PrintableExcerpt(std::string_view text, std::size_t max_bytes = 160);

// Reads a whole file into memory (after CheckInputFile).
std::vector<char> ReadWholeFile(const std::filesystem::path& path);

}  // namespace brdfit
