// Format-independent table loading and saving. Loading detects the format by content (the
// HDF5 signature at offset 0, the tensor-file signature of an RGL .bsdf, else MERL binary),
// never by the file name; saving picks the format explicitly or from the extension. An RGL
// .bsdf is read by tabulating it onto the MERL grid (io/rgl_bsdf_file.h); it is not written
// as a table.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "core/table.h"

namespace brdfit {

enum class TableFormat { kMerl, kHdf5, kRglBsdf };

// "binary" is accepted for "merl", "hdf5" for "h5".
inline constexpr auto kTableFormatNames =
    MakeEnumNames<TableFormat>("table format", {{TableFormat::kMerl, "merl"},
                                                {TableFormat::kHdf5, "h5"},
                                                {TableFormat::kRglBsdf, "bsdf"},
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
  // RGL .bsdf: cells masked because the file does not cover them (theta_i beyond its range,
  // unmeasured samples) or its value is not finite, and cells with a channel clamped to 0.
  std::size_t uncovered_cells = 0;
  std::size_t not_finite_cells = 0;
  std::size_t clamped_cells = 0;
  std::vector<std::string> notes;  // what the reader left out and why (RGL .bsdf)
};

Table LoadTable(const std::filesystem::path& path, LoadReport* report = nullptr);

// The format of an output table: `format_option` ("merl", "h5", ...) when not empty, else the
// extension; InputError naming `out` when neither says (or the option names no format).
TableFormat OutputTableFormat(const std::filesystem::path& out, const std::string& format_option);

// InputError naming `out` when `format` cannot hold `grid`: MERL holds only its own grid.
void CheckFormatHoldsGrid(TableFormat format, const Grid& grid, const std::filesystem::path& out);

// format = nullopt: from the extension; InputError if the extension says nothing.
void SaveTable(const Table& table, const std::filesystem::path& path,
               std::optional<TableFormat> format = std::nullopt);

}  // namespace brdfit
