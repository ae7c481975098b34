// Rank-1 homomorphic factorization of a tabulated isotropic BRDF into two textures
// (McCool, Ang, Ahmad 2001; Kautz & McCool 1999). Derivation: docs/factorization.md.
//
//   FactorSystemCache cache;                       // share across materials on one grid
//   Factorization r = Factor(table, options, &cache);
//   r.brdf.Eval(wi, wo);                           // f_r in 1/sr, from the float32 textures
//
// Cells are used if valid, strictly above the horizon at their centre and within
// options.max_theta; of those, cells with a channel <= 0 (or not finite) cannot enter log space
// and are masked for this material (counted in stats.nonpositive_cells), never clamped.
#pragma once

#include <cstddef>
#include <string>

#include "factor/factor_eval.h"
#include "factor/factor_param.h"
#include "factor/factor_system.h"
#include "core/table.h"

namespace brdfit {

using FactorOptions = FactorSystemOptions;

struct FactorStats {
  std::size_t grid_cells = 0;
  std::size_t valid_cells = 0;        // table.valid
  std::size_t usable_cells = 0;       // valid, above the horizon, within max_theta
  std::size_t nonpositive_cells = 0;  // usable cells masked because a channel is <= 0
  std::size_t used_cells = 0;         // usable - nonpositive: rows in the data term
  bool system_reused = false;         // the factored system came from the cache
  bool system_rebuilt = false;        // too many nonpositive cells: built a system without them
  int pcg_iterations = 0;             // low-rank correction for the nonpositive cells
  std::size_t clamped_texels = 0;     // texel values clamped into the float32 range
  double system_seconds = 0;          // building + factoring M in this call (0 if reused)
  double seconds = 0;                 // the whole Factor() call
  double solve_log_rms = 0;           // weighted RMS log residual of the solution, pre-bake
};

struct Factorization {
  FactorOptions options;
  FactoredBrdf brdf;
  FactorStats stats;
};

// Throws InputError (bad options, no usable cell). Throws std::runtime_error if the solve
// produced non-finite values. `cache` may be null (a private cache is used).
Factorization Factor(const Table& table, const FactorOptions& options,
                     FactorSystemCache* cache = nullptr);

}  // namespace brdfit
