#include "io/table_io.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/error.h"
#include "io/hdf5_table.h"
#include "io/input_file.h"
#include "io/merl.h"
#include "io/rgl_bsdf_file.h"
#include "io/tensor_file.h"

namespace brdfit {

namespace fs = std::filesystem;

TableFormat DetectTableFormat(const fs::path& path) {
  CheckInputFile(path);
  // HDF5 format specification, "Format Signature": \211HDF\r\n\032\n at offset 0 (brdfit never
  // writes a user block, so the signature is always at 0 in its files).
  static constexpr char kSignature[8] = {'\211', 'H', 'D', 'F', '\r', '\n', '\032', '\n'};
  const std::vector<char> head = ReadFilePrefix(path, sizeof(kTensorFileMagic));
  if (head.size() >= sizeof(kSignature) &&
      std::equal(std::begin(kSignature), std::end(kSignature), head.begin())) {
    return TableFormat::kHdf5;
  }
  if (head.size() == sizeof(kTensorFileMagic) &&
      std::equal(head.begin(), head.end(), std::begin(kTensorFileMagic))) {
    return TableFormat::kRglBsdf;
  }
  return TableFormat::kMerl;
}

std::optional<TableFormat> TableFormatFromExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".binary" || ext == ".merl") return TableFormat::kMerl;
  if (ext == ".h5" || ext == ".hdf5") return TableFormat::kHdf5;
  return std::nullopt;
}

Table LoadTable(const fs::path& path, LoadReport* report) {
  const TableFormat format = DetectTableFormat(path);
  LoadReport r;
  r.format = format;
  Table t;
  if (format == TableFormat::kHdf5) {
    t = ReadHdf5Table(path);
  } else if (format == TableFormat::kRglBsdf) {
    RglTabulation n;
    t = ReadRglBsdfTable(path, Grid::Merl(), &n);
    r.uncovered_cells = n.uncovered;
    r.not_finite_cells = n.not_finite;
    r.clamped_cells = n.clamped;
    r.notes = n.notes;
  } else {
    MerlReadReport mr;
    t = ReadMerl(path, &mr);
    r.negative_cells = mr.negative_cells;
  }
  if (report) *report = r;
  return t;
}

TableFormat OutputTableFormat(const fs::path& out, const std::string& format_option) {
  const std::optional<TableFormat> format = format_option.empty()
                                                ? TableFormatFromExtension(out)
                                                : FromString<TableFormat>(format_option);
  if (!format) {
    throw InputError(out,
                     "cannot tell the format from the extension: use .binary or .h5, or "
                     "--format merl|h5");
  }
  return *format;
}

void CheckFormatHoldsGrid(TableFormat format, const Grid& g, const fs::path& out) {
  if (format == TableFormat::kMerl && !(g == Grid::Merl())) {
    throw InputError(out, "MERL files hold only the 90,90,180 grid with sqrt mapping (this is " +
                              std::to_string(g.n_theta_h) + "," + std::to_string(g.n_theta_d) +
                              "," + std::to_string(g.n_phi_d) + " " +
                              std::string(ToString(g.theta_h_mapping)) + "); write .h5 instead");
  }
}

void SaveTable(const Table& table, const fs::path& path, std::optional<TableFormat> format) {
  if (path.native().find('\0') != std::string::npos) {
    throw InputError("output path contains a NUL byte: " + PrintableExcerpt(path.native()));
  }
  if (!format) format = TableFormatFromExtension(path);
  if (!format) {
    throw InputError(path,
                     "cannot tell the output format from the extension (use .binary or "
                     ".h5, or give the format)");
  }
  if (*format == TableFormat::kRglBsdf) {
    throw InputError(path,
                     "a table is not written as an RGL .bsdf here (write .binary or .h5; "
                     "brdfit export TABLE --format bsdf writes one)");
  }
  if (*format == TableFormat::kMerl) {
    WriteMerl(table, path);
  } else {
    WriteHdf5Table(table, path);
  }
}

}  // namespace brdfit
