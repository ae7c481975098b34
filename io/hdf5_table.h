// brdfit's own table format: one HDF5 file per table (docs/formats.md, "brdfit-table" v1).
//
//   /                 attrs format = "brdfit-table", format_version = 1
//   /values           float64 [n_theta_h][n_theta_d][n_phi_d][3]  f_r in 1/sr, linear RGB
//   /valid            uint8   [n_theta_h][n_theta_d][n_phi_d]     1 = valid, 0 = masked
//   /axes/theta_h     float64 [n_theta_h]  cell-centre angles (rad), attr mapping sqrt|linear
//   /axes/theta_d     float64 [n_theta_d]  cell-centre angles (rad), attr mapping linear
//   /axes/phi_d       float64 [n_phi_d]    cell-centre angles (rad), attr mapping linear
//   /provenance       attrs source, generator, model, parameters (JSON), seed, noise,
//                     missing_fraction
//
// The layout of /values is the Table's own (MERL index order, interleaved RGB), so write -> read
// is exact: every double, the mask and the provenance come back bit for bit. Files carry no
// timestamps, so the same table always gives the same bytes.
#pragma once

#include <filesystem>

#include "core/table.h"

namespace brdfit {

inline constexpr const char* kHdf5TableFormat = "brdfit-table";
inline constexpr int kHdf5TableVersion = 1;

// Throws InputError naming the file and the problem (missing dataset, inconsistent shapes or
// axes, NaN/Inf in a valid cell, mask values other than 0/1, unsupported version).
Table ReadHdf5Table(const std::filesystem::path& path);

// Writes atomically (temporary file + rename).
void WriteHdf5Table(const Table& table, const std::filesystem::path& path);

}  // namespace brdfit
