// Format-independent table loading and saving. Loading detects the format by content (the
// HDF5 signature at offset 0, else MERL binary), never by the file name; saving picks the
// format explicitly or from the extension.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/enum_names.h"
#include "core/table.h"

namespace brdfit {

enum class TableFormat { kMerl, kHdf5 };

// "binary" is accepted for "merl", "hdf5" for "h5".
inline constexpr auto kTableFormatNames =
    MakeEnumNames<TableFormat>("table format", {{TableFormat::kMerl, "merl"},
                                                {TableFormat::kHdf5, "h5"},
                                                {TableFormat::kMerl, "binary", true},
                                                {TableFormat::kHdf5, "hdf5", true}});
constexpr const auto& EnumNamesOf(TableFormat) {
  return kTableFormatNames;
}

// Format of an existing file by its first bytes. Throws InputError for a missing path or a
// directory.
TableFormat DetectTableFormat(const std::filesystem::path& path);

// Format implied by an output name: .binary/.merl -> MERL, .h5/.hdf5 -> HDF5; nullopt else.
std::optional<TableFormat> TableFormatFromExtension(const std::filesystem::path& path);

struct LoadReport {
  TableFormat format = TableFormat::kMerl;
  std::size_t negative_cells = 0;  // MERL: cells masked because a channel was negative
};

Table LoadTable(const std::filesystem::path& path, LoadReport* report = nullptr);

// format = nullopt: from the extension; InputError if the extension says nothing.
void SaveTable(const Table& table, const std::filesystem::path& path,
               std::optional<TableFormat> format = std::nullopt);

}  // namespace brdfit
