// Synthetic tables: any BRDF (a registered model, a network, a lambda) evaluated at the cell
// centres of a grid, with optional multiplicative noise and holes. Deterministic: the same
// inputs and seed give the same table, whatever the evaluation order or thread count, and the
// random numbers do not depend on any standard-library distribution.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "core/table.h"
#include "models/geometry.h"

namespace brdfit {

// f_r (1/sr, no cosine) at a geometry; cos_i > 0 and cos_o > 0 are guaranteed.
using BrdfEvalFn = std::function<void(const Geometry& g, double rgb[3])>;

struct SynthOptions {
  double noise = 0;             // sigma of log-normal multiplicative noise (0: none)
  double missing_fraction = 0;  // fraction of the valid cells removed, in [0, 1]
  std::uint64_t seed = 0;
};

struct SynthReport {
  std::size_t below_horizon = 0;  // masked: a direction at the cell centre is below
  std::size_t removed = 0;        // masked on purpose (missing_fraction)
  std::size_t non_finite = 0;     // masked: the model returned NaN or Inf
  std::size_t negative = 0;       // masked: the model returned a negative value
};

// Evaluates `eval` at every cell centre above the horizon (Geometry from Grid::CellCentre with
// phi_h = 0; core/table.h). Then, with the seed:
//  * noise: each valid value v becomes v * exp(noise * z), z ~ N(0, 1) independent per cell and
//    channel (log-normal, median-preserving, never changes the sign);
//  * holes: exactly round(missing_fraction * N) of the N valid cells are masked, chosen
//    uniformly at random (N = the above-horizon cells unless the model returned bad values).
// Values the model returns negative or non-finite are masked and counted, never clamped.
// Provenance: source "synthetic", generator "brdfit synth", noise, missing_fraction and seed;
// the caller fills model and parameters. Throws std::invalid_argument on bad options.
Table SynthesizeTable(const Grid& grid, const BrdfEvalFn& eval, const SynthOptions& options,
                      SynthReport* report = nullptr);

// The noise and holes step alone, on any table (e.g. a tabulated network): noise on every valid
// value, then holes among the valid cells; sets the provenance's noise, missing_fraction and
// seed, and report->removed.
void ApplyNoiseAndHoles(Table& table, const SynthOptions& options, SynthReport* report = nullptr);

// The counter-based generator behind the noise and holes, exposed for tests: a uniform double
// in (0, 1) from (seed, stream, index) via SplitMix64 finalizers (Steele, Lea, Flood 2014,
// "Fast Splittable Pseudorandom Number Generators", OOPSLA; constants of Vigna's splitmix64.c).
double SynthUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);
// A standard normal from two such uniforms (Box and Muller 1958).
double SynthNormal(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

}  // namespace brdfit
