// Refinement of a factorization under the relative or the log-ratio loss, with an optional
// diffuse value and a sum of K products (docs/factorization.md §13).
//
// Form, per RGB channel (channels are independent problems):
//   f_r = d + sum_k exp(a_r^T x_k)
// a_r: the log-linear row of cell r in the cached system (factor_system.h), the same for every
// term; x_k: log-texel unknowns of term k (positivity is free: the unknowns are logs); d >= 0
// the diffuse value kd / pi (1/sr).
// Objective: a loss of the analytic fits (fit/loss.h), relative (after Sun et al. 2018) or
// log-ratio, rho = (f - m) / (|m| + eps) or ln((f + eps) / (m + eps)),
//   E = sum_r w_r rho(f_r, m_r)^2 + sum_k |S x_k|^2
// w_r: the system's cell weights (solid angle), S: its smoothness rows and gauge row (one gauge
// per term: each product is invariant under the same rescaling of its factors). Minimized by
// Levenberg-Marquardt (Marquardt 1963, diagonal scaling) with d projected onto d >= 0; the
// normal equations are solved densely when the unknowns are few (mccool: radial profiles) and
// by a sparse LDL^T in the pattern of the system's rows otherwise (halfdiff: a 2-D q texture).
// Start: the log-linear solution (rank 1, no diffuse); with a diffuse term, d starts at half a
// low quantile of m and the term is re-solved log-linearly on max(m - d, m / 4); each further
// term starts from the log-linear solve of what the previous terms leave,
// max(m - f, m / 50) (greedy deflation, as a truncated SVD adds singular pairs), then every
// term and d are refined together.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/enum_names.h"
#include "core/table.h"
#include "factor/factor_system.h"

namespace brdfit {

// The data term of the refinement: the relative loss or the log-ratio loss of the analytic
// fits (fit/loss.h; the log-linear solve minimizes the log-ratio with eps = 0).
enum class RefineLoss { kRel, kLogRatio };

inline constexpr auto kRefineLossNames = MakeEnumNames<RefineLoss>(
    "refinement loss", {{RefineLoss::kRel, "rel"}, {RefineLoss::kLogRatio, "logratio"}});
constexpr const auto& EnumNamesOf(RefineLoss) {
  return kRefineLossNames;
}

struct RefineOptions {
  RefineLoss loss = RefineLoss::kRel;
  bool diffuse = false;
  int rank = 1;
  int max_iterations = 30;         // LM iterations per channel and stage
  std::size_t max_rows = 1 << 13;  // rows used at most (every s-th row, weights times s)
  std::size_t dense_limit = 1024;  // unknowns per channel up to which H is solved densely
  double tolerance = 1e-6;         // stop when a step lowers the objective by less (relative)
};

struct RefineResult {
  std::array<double, 3> diffuse{0, 0, 0};
  std::vector<Eigen::MatrixX3d> terms;  // log-texel unknowns per term (system layout)
  // The refined solution of every lower rank on the way (ranks 1 .. K-1, in order): what each
  // further product bought (docs/factorization.md §13).
  struct Stage {
    std::array<double, 3> diffuse{0, 0, 0};
    std::vector<Eigen::MatrixX3d> terms;
  };
  std::vector<Stage> lower_ranks;
  std::size_t rows = 0;
  int iterations = 0;
  double rel_rms_start = 0;    // sqrt(sum res^2 / (3 sum w)) over the rows used, at the start
  double rel_rms = 0;          // ... at the end
  double objective_start = 0;  // E (data + smoothness), channels summed, at the start
  double objective = 0;        // ... at the end (never above objective_start at rank 1)
};

// `x0`: the log-linear solution of `sys` for this table (rank 1); `removed`: the rows Solve
// dropped (a channel <= 0). Rows with a non-finite value are skipped. Throws
// std::runtime_error if the result is not finite.
RefineResult RefineFactorization(const FactorSystem& sys, const Table& table,
                                 const Eigen::MatrixX3d& x0,
                                 const std::vector<std::uint32_t>& removed,
                                 const RefineOptions& options);

}  // namespace brdfit
