#include "core/file_stem.h"

namespace brdfit {

std::string SafeFileStem(std::string_view name) {
  std::string s;
  s.reserve(name.size());
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    s += (c == '/' || c == '\\' || u < 0x20 || u == 0x7f) ? '_' : c;
  }
  for (std::size_t at; (at = s.find("..")) != std::string::npos;) s.replace(at, 2, "__");
  s.erase(0, s.find_first_not_of('.') == std::string::npos ? s.size() : s.find_first_not_of('.'));
  if (s.size() > kMaxFileStem) {
    std::size_t cut = kMaxFileStem;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // UTF-8 tail
    s.resize(cut);
  }
  if (s.empty()) s = kEmptyFileStem;
  return s;
}

}  // namespace brdfit
