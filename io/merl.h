// MERL BRDF database binary format (Matusik, Pfister, Brand, McMillan 2003, "A Data-Driven
// Reflectance Model", SIGGRAPH; reference reader BRDFRead.cpp; docs/formats.md):
//  * header: 3 x int32 little-endian {90, 90, 180} = (theta_h, theta_d, phi_d) bins;
//  * body: 3 x 1,458,000 float64, channel-planar (all R, then G, then B), MERL index layout;
//    file size exactly 34,992,012 bytes;
//  * values are f_r in 1/sr divided by the channel scales (1/1500, 1.15/1500, 1.66/1500);
//    negative values mark invalid (unmeasured / below-horizon) cells.
//
// Reading multiplies each raw double by its channel scale once (one correctly rounded product)
// and MASKS every cell with a negative channel; it never clamps. Writing stores, per value v,
// the raw double r nearest to v / scale with r * scale == v (MerlRawFromValue), so that
//  * Table -> file -> Table is exact for every table whose values came from a MERL file;
//  * file -> Table -> file is byte-identical for every file brdfit wrote (and any file whose
//    raws are canonical in that sense). Scaling by a non-power-of-two maps some pairs of
//    adjacent raw doubles to the same product, so no double-valued table can restore those
//    raws; such a raw comes back one ulp away (relative change ~1e-16). docs/formats.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "core/table.h"

namespace brdfit {

// Per-channel factor from the stored raw value to f_r in 1/sr (BRDFRead.cpp).
inline constexpr std::array<double, 3> kMerlChannelScale = {1.0 / 1500.0, 1.15 / 1500.0,
                                                            1.66 / 1500.0};
inline constexpr std::uintmax_t kMerlHeaderBytes = 12;
inline constexpr std::uintmax_t kMerlFileBytes = kMerlHeaderBytes + 3ull * 90 * 90 * 180 * 8;

struct MerlReadReport {
  std::size_t negative_cells = 0;  // cells with at least one negative channel: masked
};

// Reads a MERL .binary file. Throws InputError naming the file and the problem: "no such
// file", "is a directory", "header dimension 1 (theta_h bins) is 91, expected 90",
// "truncated: ...", "file is N bytes, expected 34992012", "NaN at cell ...".
Table ReadMerl(const std::filesystem::path& path, MerlReadReport* report = nullptr);

// Writes a table on the MERL grid (90 x 90 x 180, sqrt theta_h mapping) atomically. Invalid
// cells are written as -1 in every channel, unless the cell already holds finite values with
// a negative channel (as read from a MERL file), which are kept. Throws InputError if the grid
// is not MERL's or a valid cell is negative or not finite (MERL cannot store it).
void WriteMerl(const Table& table, const std::filesystem::path& path);

// The raw double stored for value v of channel c: the double r nearest to v / scale with
// r * scale == v when one exists, else the correctly rounded v / scale.
double MerlRawFromValue(double v, int channel);

}  // namespace brdfit
