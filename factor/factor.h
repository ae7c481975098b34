// Homomorphic factorization of a tabulated isotropic BRDF into textures (McCool, Ang, Ahmad
// 2001; Kautz & McCool 1999): rank 1 by the log-linear solve, optionally refined, with a
// diffuse value and a sum of K products (factor/factor_refine.h). Derivation:
// docs/factorization.md.
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
#include <vector>

#include "core/table.h"
#include "factor/factor_eval.h"
#include "factor/factor_param.h"
#include "factor/factor_refine.h"
#include "factor/factor_system.h"

namespace brdfit {

// The factored form and how it is solved, beyond what the cached system depends on.
//   diffuse: f = kd/pi + products (RGB kd >= 0 solved jointly with the textures);
//   rank:    number of products K in [1, kMaxFactorRank] (greedy: each new term starts from
//            what the previous ones leave, then all are refined together);
//   refine:  after the log-linear solve, Levenberg-Marquardt on the log-texel values (and kd)
//            under refine_loss, the relative or the log-ratio loss of the analytic fits
//            (fit/loss.h) with the solid-angle cell weights. diffuse or rank > 1 imply it:
//            they have no log-linear solve.
inline constexpr int kMaxFactorRank = 4;
struct FactorOptions : FactorSystemOptions {
  RefineLoss refine_loss = RefineLoss::kRel;
  bool diffuse = false;
  int rank = 1;
  bool refine = false;
  int refine_iterations = 30;         // LM iterations per channel, at most
  std::size_t refine_rows = 1 << 13;  // rows the refinement uses at most (deterministic stride)
  bool NeedsRefinement() const { return refine || diffuse || rank > 1; }
};

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
  // Refinement (FactorOptions::NeedsRefinement), channels pooled, over the rows it used:
  std::size_t refine_rows = 0;      // rows used (a deterministic subset of the used cells)
  int refine_iterations = 0;        // LM iterations, summed over channels and terms
  double refine_rel_rms_start = 0;  // sqrt(weighted mean rel^2) of the log-linear start
  double refine_rel_rms = 0;        // ... and of the refined solution
  double refine_seconds = 0;
};

struct Factorization {
  FactorOptions options;
  FactoredBrdf brdf;
  FactorStats stats;
  // With rank K > 1: the refined solutions of ranks 1 .. K-1 met on the way (same d option),
  // so that what each further product buys can be shown.
  std::vector<FactoredBrdf> lower_ranks;
};

// Throws InputError (bad options, no usable cell). Throws std::runtime_error if the solve
// produced non-finite values. `cache` may be null (a private cache is used).
Factorization Factor(const Table& table, const FactorOptions& options,
                     FactorSystemCache* cache = nullptr);

}  // namespace brdfit
