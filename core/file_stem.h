// Names that come from inside files (NBRDF archive members, material names, HDF5 attributes)
// become file names only through SafeFileStem: one path component that cannot climb out of,
// or point beside, the output folder.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace brdfit {

inline constexpr std::size_t kMaxFileStem = 128;  // bytes; the suffixes still fit NAME_MAX
inline constexpr std::string_view kEmptyFileStem = "unnamed";

// `name` as a safe file stem: '/', '\\', NUL and control characters become '_'; leading dots
// are dropped (no hidden files, no "." or ".."); ".." inside becomes "__"; at most
// kMaxFileStem bytes (cut on a UTF-8 character boundary); empty → kEmptyFileStem. A name that
// is already safe is returned unchanged.
std::string SafeFileStem(std::string_view name);

}  // namespace brdfit
