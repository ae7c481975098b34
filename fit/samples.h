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

struct Samples {
  Grid grid;
  SampleOptions options;
  SampleCounts counts;

  // Evaluation points. Observations of sample s are [obs_begin[s], obs_begin[s + 1]).
  std::vector<Geometry> geometry;
  std::vector<std::uint32_t> obs_begin;

  // Observations: one per selected cell.
  std::vector<std::uint32_t> cell;  // table index
  std::vector<double> value;        // 3 per observation: f_r in 1/sr, linear RGB
  std::vector<double> weight;       // cell weight; sub-sampled budgets scale it so that each
                                    // stratum keeps its total (ratio estimator)
  std::vector<double> cos_i;        // cos theta_i of this cell (mirrors swap theta_i, theta_o)
  std::vector<double> cos_o;
  double total_weight = 0;  // sum of weight

  std::size_t NumSamples() const { return geometry.size(); }
  std::size_t NumObservations() const { return cell.size(); }
};

// Builds the samples of a table. Throws InputError if the options are invalid
// (cut-off outside (0, 90], zero budget). A table with no usable cell gives empty samples
// (the fitter reports that as a failed fit, not an exception).
Samples PrepareSamples(const Table& table, const SampleOptions& options);

// A stratified subset (over theta_h bins, proportional to weight, at least a few per bin) of
// about n samples, weights rescaled per stratum; the whole set if it is not larger than n.
// Deterministic for a given seed. Used for the initializer and the coarse solve.
Samples Subsample(const Samples& samples, std::size_t n, std::uint64_t seed);

// Expands per-sample predictions (3 per sample) to per-observation (3 per observation).
std::vector<double> ExpandToObservations(const Samples& samples,
                                         const std::vector<double>& per_sample_rgb);

}  // namespace brdfit
