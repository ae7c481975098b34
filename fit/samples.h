// Fit samples: the valid cells of a table that a fit (or a metric) looks at, with their
// geometry computed once, their values, and their bin-measure weights.
//
// What is skipped because it cannot change the fit:
//  * invalid cells (masked in the table; never read as zero) and non-finite values;
//  * cells beyond the angle cut-off (theta_i or theta_o > cutoff, default 80 deg) or with
//    cos theta_i or cos theta_o <= 1e-3 (the masking terms divide by ~0 at grazing angles);
//  * half of the model evaluations: for an isotropic, reciprocal BRDF the cell at phi_d and
//    its mirror at pi - phi_d hold the same value. (Mirroring phi_d is a reflection of the
//    configuration plus the swap wi <-> wo: theta_i and theta_o trade places.) On a uniform
//    phi_d grid bin ip and bin n-1-ip are exact mirrors, so both cells become observations
//    of ONE sample: the model is evaluated once, and each cell keeps its own value, weight
//    and cos theta_i. Losses and metrics are unchanged; only the model cost halves.
//  * for sub-sampled budgets, geometry is computed only for the selected samples.
// What depends only on the grid and the options (the cells inside the cut-off, their cosines
// and bin measures) is the grid's SamplePlan (fit/sample_plan.h), made once per batch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/sample_counts.h"
#include "core/table.h"
#include "models/geometry.h"

namespace brdfit {

// How many samples a fit uses. A "sample" is one model evaluation point: a cell and, when
// present, its phi_d mirror.
struct Budget {
  enum class Kind { kFull, kStride, kRandom };
  Kind kind = Kind::kFull;
  int stride = 1;         // kStride: every stride-th phi_d bin of [0, pi/2) and its mirror
  std::size_t count = 0;  // kRandom: number of samples, stratified over theta_h bins

  // "full", "stride:K" (K >= 1), "random:N" (N >= 1). Throws InputError on anything else.
  static Budget Parse(const std::string& text);
  std::string ToString() const;
  bool operator==(const Budget&) const = default;
};

// The budget `brdfit fit` (and the preview's fits) use unless told otherwise: stride:32.
// Over the 100 MERL proxies (lambert+ggx, rel loss) it renders as well as the full set
// (rendered score mean +0.21 dB, worst -0.37 dB) in a quarter of the time; docs/fitting.md,
// "Budget". Budget{} (full) stays the library's default.
inline Budget DefaultFitBudget() {
  Budget b;
  b.kind = Budget::Kind::kStride;
  b.stride = 32;
  return b;
}

enum class Weighting {
  kBinMeasure,  // each cell weighted by its measure in (wi, wo) space (fit/bin_measure.h)
  kUniform,     // every cell weighs 1 (as tools that ignore the non-uniform MERL bins)
};
// "measure" is accepted for "bin-measure".
inline constexpr auto kWeightingNames =
    MakeEnumNames<Weighting>("weighting", {{Weighting::kBinMeasure, "bin-measure"},
                                           {Weighting::kUniform, "uniform"},
                                           {Weighting::kBinMeasure, "measure", true}});
constexpr const auto& EnumNamesOf(Weighting) {
  return kWeightingNames;
}
// FromString<Weighting> under the name its callers use.
inline Weighting WeightingFromString(const std::string& s) {
  return FromString<Weighting>(s);
}

struct SampleOptions {
  double cutoff_deg = 80.0;  // cells with theta_i or theta_o above it are skipped
  Weighting weighting = Weighting::kBinMeasure;
  Budget budget;
  std::uint64_t seed = 1;    // for kRandom budgets; fixed so that fits are reproducible
  bool pair_mirrors = true;  // one model evaluation for a cell and its phi_d mirror
  bool operator==(const SampleOptions&) const = default;
};

// Sines and cosines of the grid's bin centres, per axis (docs/conventions.md: centre =
// index + 0.5): what every sample's geometry is computed from.
struct AxisTrig {
  std::vector<double> sin_h, cos_h, sin_d, cos_d, sin_p, cos_p;
};

struct Samples {
  Grid grid;
  SampleOptions options;
  SampleCounts counts;
  AxisTrig trig;

  // Evaluation points. Observations of sample s are [obs_begin[s], obs_begin[s + 1]).
  // `geometry` is empty when the samples were prepared without it (GeometryStorage::kOnDemand):
  // SampleGeometry computes it then.
  std::vector<Geometry> geometry;
  std::vector<std::uint32_t> obs_begin;

  // Observations: one per selected cell.
  std::vector<std::uint32_t> cell;  // table index
  std::vector<double> value;        // 3 per observation: f_r in 1/sr, linear RGB (empty when
                                    // the values are the table's own, table_rgb)
  std::vector<double> weight;       // cell weight; sub-sampled budgets scale it so that each
                                    // stratum keeps its total (ratio estimator)
  std::vector<double> cos_i;        // cos theta_i of this cell (mirrors swap theta_i, theta_o)
  double total_weight = 0;          // sum of weight
  // The whole table's values (3 per cell), moved from the table by PrepareMetricSamples so that
  // a metric set holds no copy of them (22 MB for a MERL table); empty otherwise.
  TableValues table_rgb;

  std::size_t NumSamples() const { return obs_begin.empty() ? 0 : obs_begin.size() - 1; }
  std::size_t NumObservations() const { return cell.size(); }
  // The 3 measured values of observation o.
  const double* Value(std::size_t o) const {
    return value.empty() ? &table_rgb[3 * static_cast<std::size_t>(cell[o])] : &value[3 * o];
  }
};

// Builds the samples of a table (a sub-sampled budget: SelectBudget of the full set, below).
// Throws InputError if the options are invalid
// (cut-off outside (0, 90], zero budget). A table with no usable cell gives empty samples
// (the fitter reports that as a failed fit, not an exception).
// kOnDemand leaves Samples::geometry empty (120 bytes per sample, 55 MB for a full MERL table):
// for sets that are only scored (the metric set of a sub-sampled fit), not solved on.
enum class GeometryStorage { kStored, kOnDemand };
Samples PrepareSamples(const Table& table, const SampleOptions& options,
                       GeometryStorage storage = GeometryStorage::kStored);
// The same from the table's grid's plan (fit/sample_plan.h), made once for many tables (a
// batch: fit/prepare_cache.h). Throws std::invalid_argument if the plan is of another grid, cut-off,
// weighting or pairing.
struct SamplePlan;
Samples PrepareSamples(const Table& table, const SamplePlan& plan, const SampleOptions& options,
                       GeometryStorage storage = GeometryStorage::kStored);

// The metric set of a fit (every usable cell, full budget; options.budget is ignored), built
// consuming the table: geometry on demand, and the table's value array moved into
// Samples::table_rgb instead of copied per observation. The table is left empty. Equal in every
// observation to PrepareSamples(table, full budget) (tested).
Samples PrepareMetricSamples(Table&& table, const SampleOptions& options);
Samples PrepareMetricSamples(Table&& table, const SamplePlan& plan, const SampleOptions& options);

// The geometry of sample s: the stored one, or (kOnDemand) the same value computed from its cell
// with the same operations, bit for bit.
Geometry SampleGeometry(const Samples& samples, std::size_t s);

// The samples a budget keeps of the full samples of a table (options.budget full), with their
// geometry stored and their weights rescaled (stride: per (theta_h, theta_d) row; random: per
// theta_h stratum). The one selection rule: PrepareSamples of a sub-sampled budget is this
// applied to its full set, and the fitter applies it to its metric set (no geometry computed
// twice). Throws InputError on a bad budget.
Samples SelectBudget(const Samples& full, const Budget& budget, std::uint64_t seed);

// A stratified subset (over theta_h bins, proportional to weight, at least a few per bin) of
// about n samples, weights rescaled per stratum; the whole set if it is not larger than n.
// Deterministic for a given seed. Used for the initializer and the coarse solve.
Samples Subsample(const Samples& samples, std::size_t n, std::uint64_t seed);

// Expands per-sample predictions (3 per sample) to per-observation (3 per observation).
std::vector<double> ExpandToObservations(const Samples& samples,
                                         const std::vector<double>& per_sample_rgb);

}  // namespace brdfit
