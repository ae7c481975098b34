// The per-grid part of sample preparation (fit/samples.h), done once per grid:
// everything a table's samples need that depends only on its grid and on the sample options'
// cut-off, weighting and mirror pairing, not on the table's mask or values. Every MERL table
// shares one grid, so a batch computes this once (fit/prepare_cache.h) and PrepareSamples
// applies it to each table: the table's mask and values decide which members are kept, masked
// cells are skipped (never zeroed), and the budget is selected per table (its per-row weight
// factors depend on the mask).
//
// What it holds, in the order fit/samples.h visits cells ((theta_h, theta_d, phi_d), a cell and
// its phi_d mirror as one unit): the bin centres' sines and cosines, every unit inside the
// cut-off with its member cells (the first-half cell first) and each member's cos theta_i at
// its centre, and each (theta_h, theta_d) row's bin measure. About 15 MB for the MERL grid.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/table.h"
#include "fit/samples.h"
#include "models/geometry.h"

namespace brdfit {

// What a plan depends on: its grid and three of the sample options (budget and seed play no
// part). The plan's identity, and the key of the batch's cache (fit/prepare_cache.h).
struct SamplePlanKey {
  Grid grid;
  double cutoff_deg = 0;
  Weighting weighting = Weighting::kBinMeasure;
  bool pair_mirrors = true;
  static SamplePlanKey Of(const Grid& g, const SampleOptions& o) {
    return {g, o.cutoff_deg, o.weighting, o.pair_mirrors};
  }
  bool operator==(const SamplePlanKey&) const = default;
};

struct SamplePlan {
  SamplePlanKey key;
  AxisTrig trig;
  // Row r = ih * n_theta_d + id holds units [row_begin[r], row_begin[r + 1]); its cells weigh
  // row_weight[r] (fit/bin_measure.h, or 1 for uniform weighting).
  std::vector<std::uint32_t> row_begin;
  std::vector<double> row_weight;
  // Unit u (inside the cut-off) has members [unit_begin[u], unit_begin[u + 1]): the cell of
  // phi_d bin ip < n_phi_d / 2 first, then its mirror n_phi_d - 1 - ip (when paired and
  // distinct). cos_i: the member's own cos theta_i (a mirror swaps theta_i and theta_o).
  std::vector<std::uint32_t> unit_begin;
  std::vector<std::uint32_t> cell;
  std::vector<double> cos_i;

  std::size_t NumUnits() const { return unit_begin.empty() ? 0 : unit_begin.size() - 1; }
  std::size_t Bytes() const;
  // True if the plan was made for this grid and these options (budget and seed play no part).
  bool Matches(const Grid& g, const SampleOptions& o) const {
    return key == SamplePlanKey::Of(g, o);
  }
};

// Throws InputError for a cut-off outside (0, 90] degrees.
SamplePlan MakeSamplePlan(const Grid& grid, const SampleOptions& options);

// One (theta_h, theta_d) row of a plan: its cells' weight and its units; unit k of the row has
// members [unit_begin[k], unit_begin[k + 1]) of `cell` and `cos_i`.
struct PlanRow {
  int ih = 0, id = 0;
  double weight = 0;
  std::size_t units = 0;
  const std::uint32_t* unit_begin = nullptr;  // units + 1 offsets
  const std::uint32_t* cell = nullptr;
  const double* cos_i = nullptr;
};
using PlanRowFn = std::function<void(const PlanRow&)>;
// fn(row) for every row of a stored plan, in order.
void ForEachPlanRow(const SamplePlan& plan, const PlanRowFn& fn);
// The same rows computed on the fly, nothing stored (a table prepared alone: 15 MB less at
// the peak for MERL); MakeSamplePlan stores these. Throws InputError for a bad cut-off.
void ForEachPlanRow(const Grid& grid, const SampleOptions& options, const AxisTrig& trig,
                    const PlanRowFn& fn);

// The sines and cosines of a grid's bin centres (docs/conventions.md: centre = index + 0.5).
AxisTrig MakeAxisTrig(const Grid& grid);

// wi and wo at the centre of cell (ih, id, ip) with phi_h = 0: FromHalfDiff's operations
// (models/geometry.h) on the axis tables. wi = R_y(theta_h) d with d = (sd cp, sd sp, cd); wo
// mirrors wi about h.
inline void CentreDirections(const AxisTrig& t, int ih, int id, int ip, Vec3* wi, Vec3* wo) {
  const Vec3 d{t.sin_d[id] * t.cos_p[ip], t.sin_d[id] * t.sin_p[ip], t.cos_d[id]};
  *wi = {t.cos_h[ih] * d.x + t.sin_h[ih] * d.z, d.y, -t.sin_h[ih] * d.x + t.cos_h[ih] * d.z};
  const Vec3 h{t.sin_h[ih], 0.0, t.cos_h[ih]};
  *wo = 2.0 * Dot(*wi, h) * h - *wi;
}

// The geometry at the centre of cell (ih, id, ip) from the axis tables: the same operations as
// MakeGeometry(grid.CellCentre(ih, id, ip)) with phi_h = 0, bit for bit (tested).
inline Geometry CentreGeometry(const AxisTrig& t, int ih, int id, int ip) {
  Vec3 wi, wo;
  CentreDirections(t, ih, id, ip, &wi, &wo);
  return MakeGeometry(wi, wo);
}

}  // namespace brdfit
