// Tabulated isotropic BRDF on a (theta_h, theta_d, phi_d) grid.
//
// Cell convention (one for the whole project: reader, synthesizer, fitter, preview):
//  * Index layout as MERL: idx = i_phi_d + n_phi_d * (i_theta_d + n_theta_d * i_theta_h).
//  * Bin i of an axis covers the continuous index coordinate u in [i, i+1); the coordinate of an
//    angle is  theta_h: u = N sqrt(theta_h / (pi/2)) (kSqrt, MERL) or N theta_h / (pi/2)
//    (kLinear);  theta_d: u = N theta_d / (pi/2);  phi_d: u = N phi_d / pi.
//  * A cell's representative angle is its CENTRE in index coordinates (u = i + 0.5). The
//    synthesizer evaluates models there and the fitter places its samples there; nearest lookup
//    maps any angle inside the bin back to the same cell.
//  * Values: f_r in 1/sr per linear-RGB channel, without the cosine; channel scales already
//    applied. Invalid cells (below the horizon, unmeasured, NaN in the source) are MASKED:
//    valid[idx] == 0, and their value is meaningless. They are never silently zero.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/enum_names.h"
#include "models/geometry.h"

namespace brdfit {

enum class ThetaHMapping { kSqrt, kLinear };

// The cells and weights of a trilinear lookup (Table::LookupTrilinear) at one angle triple, in
// the lookup's order, those of zero weight left out: they depend on the grid only, so a lookup
// repeated on many tables of one grid (the rendered metric's pixels) computes them once.
struct TrilinearTaps {
  std::array<std::uint32_t, 8> cell{};
  std::array<double, 8> weight{};
  int count = 0;
};

// "merl" is accepted for "sqrt".
inline constexpr auto kThetaHMappingNames =
    MakeEnumNames<ThetaHMapping>("theta_h mapping", {{ThetaHMapping::kSqrt, "sqrt"},
                                                     {ThetaHMapping::kLinear, "linear"},
                                                     {ThetaHMapping::kSqrt, "merl", true}});
constexpr const auto& EnumNamesOf(ThetaHMapping) {
  return kThetaHMappingNames;
}

struct Grid {
  int n_theta_h = 90;
  int n_theta_d = 90;
  int n_phi_d = 180;
  ThetaHMapping theta_h_mapping = ThetaHMapping::kSqrt;

  static Grid Merl() { return Grid{}; }

  std::size_t NumCells() const {
    return static_cast<std::size_t>(n_theta_h) * n_theta_d * n_phi_d;
  }
  std::size_t Index(int ih, int id, int ip) const {
    return static_cast<std::size_t>(ip) +
           static_cast<std::size_t>(n_phi_d) *
               (static_cast<std::size_t>(id) + static_cast<std::size_t>(n_theta_d) * ih);
  }
  void Unindex(std::size_t idx, int* ih, int* id, int* ip) const;

  // Continuous index coordinates of an angle (bin i covers [i, i+1)).
  double ThetaHCoord(double theta_h) const;
  double ThetaDCoord(double theta_d) const;
  double PhiDCoord(double phi_d) const;
  // Angle at a continuous index coordinate (inverse of the above).
  double ThetaHAt(double u) const;
  double ThetaDAt(double u) const;
  double PhiDAt(double u) const;

  // Representative angles of a cell: its centre in index coordinates.
  HalfDiffAngles CellCentre(int ih, int id, int ip) const;
  HalfDiffAngles CellCentre(std::size_t idx) const;

  // Cell containing an angle triple (nearest-lower bin, clamped to the grid).
  std::size_t CellOf(const HalfDiffAngles& a) const;

  // True if both directions at the cell centre are strictly above the horizon.
  bool CellAboveHorizon(std::size_t idx) const;
  // CellAboveHorizon of every cell (1 above, 0 below), indexed as Index: the same arithmetic on
  // the axes' sines and cosines computed once per bin instead of once per cell.
  std::vector<std::uint8_t> AboveHorizonMask() const;

  // The taps of Table::LookupTrilinear at a (its interpolation weights, before the table's mask
  // drops invalid cells).
  TrilinearTaps TrilinearTapsAt(const HalfDiffAngles& a) const;

  bool operator==(const Grid&) const = default;
};

// Where a table came from. Free-form strings so that any generator can describe itself.
struct Provenance {
  std::string source;          // input file, or "synthetic"
  std::string generator;       // e.g. "brdfit synth", "merl", "nbrdf"
  std::string model;           // generator model name ("lambert+ggx"), empty if measured
  std::string parameters_json; // generator parameters as JSON, empty if none
  std::uint64_t seed = 0;      // RNG seed for noise / holes
  double noise = 0;            // multiplicative noise standard deviation
  double missing_fraction = 0; // fraction of valid cells removed on purpose
  bool operator==(const Provenance&) const = default;
};

// std::allocator, but a new element made without a value is default-initialised (left
// uninitialised for double) instead of value-initialised (zeroed): resize() on a table's values
// costs no pass over them (35 MB for MERL) when a reader writes every one (Table::ForOverwrite).
// assign(n, 0.0) and every other constructor with a value behave as std::allocator's.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) {
      ::new (static_cast<void*>(p)) U;
    } else {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  }
};
using TableValues = std::vector<double, DefaultInitAllocator<double>>;

struct Table {
  Grid grid;
  TableValues rgb;                   // 3 * NumCells, interleaved RGB, 1/sr
  std::vector<std::uint8_t> valid;   // NumCells, 1 = valid sample
  Provenance provenance;

  // Allocates an all-invalid table on a grid.
  static Table Empty(const Grid& grid);
  // A table on a grid whose values and mask are left uninitialised, for a reader that writes
  // every cell's values and mask before anything reads them (io/merl.cc).
  static Table ForOverwrite(const Grid& grid);

  std::size_t CountValid() const;
  const double* Value(std::size_t idx) const { return &rgb[3 * idx]; }
  double* Value(std::size_t idx) { return &rgb[3 * idx]; }

  // Nearest-cell lookup (nearest-lower bin, as MERL's reader). nullopt if that cell is invalid.
  std::optional<std::array<double, 3>> LookupNearest(const HalfDiffAngles& a) const;
  // Trilinear interpolation between cell centres in index coordinates; invalid neighbours are
  // dropped and the weights of the valid ones renormalized. nullopt if all eight are invalid.
  // phi_d wraps periodically (period pi), theta axes clamp at the grid edges.
  std::optional<std::array<double, 3>> LookupTrilinear(const HalfDiffAngles& a) const;
  // The same lookup from its taps (Grid::TrilinearTapsAt of this table's grid), bit for bit.
  std::optional<std::array<double, 3>> LookupTaps(const TrilinearTaps& taps) const;
  // Lookup by directions (local frame, pointing away from the surface).
  std::optional<std::array<double, 3>> LookupTrilinear(const Vec3& wi, const Vec3& wo) const;

  bool operator==(const Table&) const = default;
};

}  // namespace brdfit
