// brdfit's version, for `brdfit --version` and for the files that state which brdfit wrote them
// (export/, docs/exports.md).
#pragma once

namespace brdfit {

inline constexpr const char* kBrdfitVersion = "0.1.0";

}  // namespace brdfit
