// How users name inputs, and the material an input stands for: a table file, or "nbrdf:NAME",
// the MERL material NAME of the NBRDF archive (Sztrajman et al. 2021; io/nbrdf.h reads the
// network, pipeline/inputs.h tabulates it on the MERL grid). Every command, the report and
// Python name materials by MaterialName.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace brdfit {

inline constexpr std::string_view kNbrdfInputPrefix = "nbrdf:";
inline bool IsNbrdfInput(std::string_view input) {
  return input.starts_with(kNbrdfInputPrefix);
}

// The material an input stands for: its file name without the extension ("red-plastic" for
// dir/red-plastic.binary), or NAME for "nbrdf:NAME".
inline std::string MaterialName(const std::filesystem::path& input) {
  const std::string text = input.string();
  if (IsNbrdfInput(text)) return text.substr(kNbrdfInputPrefix.size());
  return input.stem().string();
}

}  // namespace brdfit
