// User strings (material and file names, read from fit reports, JSON or HDF5 attributes) in a
// one-line comment of another language's file: every byte outside printable ASCII becomes '?'.
// That removes each language's line terminators (\n, \r; JavaScript's U+2028 and U+2029, UTF-8
// E2 80 A8/A9; Python's \f and \v), NUL and invalid UTF-8, so the comment cannot end early and
// nothing after it runs. What a comment cannot hold besides (XML's "--") is the caller's.
#pragma once

#include <string>

namespace brdfit::exports {

inline std::string CommentText(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    out += c >= 0x20 && c < 0x7f ? ch : '?';
  }
  return out;
}

}  // namespace brdfit::exports
