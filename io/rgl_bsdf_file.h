// RGL `.bsdf` files (Dupuy & Jakob 2018; the RGL material database, pbrt-v4's and Mitsuba's
// `measured` material): a tensor file (io/tensor_file.h) with the fields
//
//   description u8[n]          free text
//   jacobian    u8[1]          the file's flag
//   theta_i     f32[nt]        incident elevations (rad), strictly increasing in [0, pi/2]
//   phi_i       f32[np]        incident azimuths (rad); np <= 2 is isotropic
//   ndf         f32[a, b]      the NDF on (phi_m, theta_m)
//   sigma       f32[c, d]      the projected area on (phi_i, theta_i)
//   vndf        f32[np, nt, H, W]         the VNDF per incident direction
//   luminance   f32[np, nt, H, W]         the luminance warp (sampling only; checked, unused)
//   rgb         f32[np, nt, 3, H, W]      the values (RGB files), or
//   spectra     f32[np, nt, nw, H, W] and wavelengths f32[nw] (nm)   (spectral files)
//   valid       u8[np, nt, H, W]          optional: 0 where a sample was not measured (another
//                                         layout is left out with a note, RglBsdf::notes)
//
// Read strictly: a missing or malformed field, a non-finite or negative density, a zero
// projected area, an anisotropic file (np > 2: not supported) is an InputError naming the file
// and the field. The evaluation and the tabulation onto brdfit's grid: core/rgl_bsdf.h.
#pragma once

#include <filesystem>

#include "core/rgl_bsdf.h"
#include "core/table.h"
#include "io/tensor_file.h"

namespace brdfit {

RglBsdf ReadRglBsdf(const std::filesystem::path& path);
// The same from a parsed tensor file (`path` names it in messages).
RglBsdf RglBsdfFromTensors(const TensorFile& file, const std::filesystem::path& path);

// Writes the fields above (float32; `valid` only when the BRDF has one; `luminance` the vndf
// when empty) atomically. The authors' loader wants a square warped grid (rows == cols).
void WriteRglBsdf(const RglBsdf& bsdf, const std::filesystem::path& path);

// Reads and tabulates onto `grid` (core/rgl_bsdf.h TabulateRglBsdf). Provenance: the file as
// source, generator "rgl-bsdf", its description in parameters_json as {"description": ...}.
Table ReadRglBsdfTable(const std::filesystem::path& path, const Grid& grid = Grid::Merl(),
                       RglTabulation* counts = nullptr);

}  // namespace brdfit
