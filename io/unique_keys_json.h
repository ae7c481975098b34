// JSON parsing that refuses an object holding a key twice. RFC 8259 leaves the meaning open and
// nlohmann keeps the last one, so {"model": "lambert", "model": "ggx"} read as ggx without a
// word: a hand-edited file with a key twice is refused instead.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace brdfit {

// Parses text as nlohmann::json does (its exceptions propagate for malformed text); throws
// InputError(file, "duplicate key 'K' in PATH") for a repeated key, PATH being the enclosing
// members ("materials.gold", "objects[2]"; "the top-level object").
nlohmann::json ParseJsonUniqueKeys(const std::string& text, const std::filesystem::path& file);

}  // namespace brdfit
