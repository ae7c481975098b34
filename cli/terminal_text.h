// Text from files and names (a material name, a path, a library's message quoting a file) made
// safe for one line of a terminal: control characters (below 0x20, and DEL) as \xNN, so an
// escape sequence or a newline in a name cannot repaint the terminal or forge a line. UTF-8
// passes unchanged (io/input_file.h PrintableExcerpt escapes every non-ASCII byte, for bytes
// quoted from inside damaged files).
#pragma once

#include <fmt/core.h>

#include <string>
#include <string_view>

namespace brdfit::cli {

inline std::string TerminalSafe(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace brdfit::cli
