// What `brdfit info` reports about a table: cell counts (valid, masked, below the horizon,
// holes), per-channel value ranges, and the directional albedo at a few incidence angles.
#pragma once

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/table.h"

namespace brdfit {

struct ChannelSummary {
  double min = 0, median = 0, max = 0;  // over valid cells; NaN if there are none
};

struct AlbedoEstimate {
  double theta_i = 0;              // incidence angle (rad)
  std::array<double, 3> albedo{};  // integral over the covered part of the hemisphere
  double coverage = 0;             // covered fraction of the projected hemisphere, [0, 1]
};

struct TableStats {
  std::size_t cells = 0;
  std::size_t valid = 0;
  std::size_t below_horizon = 0;         // geometrically invalid cells (Grid::CellAboveHorizon)
  std::size_t masked_above_horizon = 0;  // holes: invalid cells whose directions are above
  std::size_t valid_below_horizon = 0;   // valid cells the geometry says cannot be measured
  std::array<ChannelSummary, 3> channels;
  std::vector<AlbedoEstimate> albedo;
};

inline constexpr std::array<double, 4> kInfoIncidenceDeg = {0, 30, 60, 75};

// Directional albedo a(wi) = int_{H+} f_r(wi, wo) cos(theta_o) dwo, estimated from the table
// with trilinear lookups (Table::LookupTrilinear). Quadrature over the half vector h, where
// the specular peak of every isotropic table sits (theta_h = 0): wo = 2 (wi.h) h - wi,
// dwo = 4 (wi.h) dwh (Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces", eq. 14). theta_h = (pi/2) t^2 (MERL's sqrt spacing) with a midpoint rule in t
// (n_t nodes) and in phi_h (n_phi nodes over [0, pi], doubled by the mirror symmetry of an
// isotropic BRDF about the plane of incidence). Directions whose lookup finds no valid cell
// are skipped; `coverage` is the cos-weighted measure of the rest over that of the hemisphere.
AlbedoEstimate EstimateAlbedo(const Table& table, double theta_i, int n_t = 256, int n_phi = 256);

TableStats ComputeTableStats(const Table& table,
                             const std::vector<double>& incidence_deg = {kInfoIncidenceDeg.begin(),
                                                                         kInfoIncidenceDeg.end()});

// JSON form used by `brdfit info --json` (keys documented in docs/formats.md).
nlohmann::ordered_json TableStatsToJson(const TableStats& stats);

}  // namespace brdfit
