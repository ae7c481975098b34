// The sparse log-linear least-squares system of the homomorphic factorization and its cached
// factorization (docs/factorization.md §2-§5).
//
// Unknowns x = [log p (n_p), log q (n_q)] per RGB channel. Each usable table cell c gives one
// row a_c: the interpolation weights of the unknowns its log-product touches
// (McCool et al. 2001: log f = log p(wi) + log q(wh) + log p(wo) is linear in the texels).
// The normal matrix
//     M = sum_c w_c a_c a_c^T  +  lambda L^T L  +  g g^T
// (w_c: cell weights, FactorWeighting; L: second differences; g: gauge row) depends only on
// the grid, the cell mask, the parameterization, the resolution, lambda, the weighting and the
// angle cut-off, never on the BRDF values. It is assembled and factored (sparse LDL^T) once per
// key and reused: a material then costs one log per value, A^T W y and two triangular solves
// (Jaroszkiewicz & McCool 2003, "Fast Extraction of BRDFs and Material Maps from Images", GI:
// a fixed sampling pattern and layout allow the constraint matrix to be pre-inverted).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/factor_form.h"
#include "core/table.h"
#include "factor/factor_param.h"

namespace brdfit {

// How table cells are weighted in the least-squares data term.
//  kSolidAngle: by the measure of the cell in (wi, wo) space (fit/bin_measure.h, the weight
//    the analytic fits use: dwi dwo = 4 cos(theta_d) dwh dwd, derived there), divided by the
//    measure of the whole (theta_h, theta_d, phi_d) box, 4 pi^2: the weights of all cells of
//    any grid sum to 1, the data term is a mean squared log error over (wi, wo) and does not
//    depend on how the table is binned.
//  kCell: w = 1 / (number of grid cells): every cell counts the same (MERL's sqrt theta_h
//    bins then emphasise the highlight).
// Weights do not depend on the mask, so dropping rows from a system and building a system
// without them give the same matrix.
enum class FactorWeighting { kSolidAngle, kCell };

inline constexpr auto kFactorWeightingNames = MakeEnumNames<FactorWeighting>(
    "weighting", {{FactorWeighting::kSolidAngle, "solid-angle"}, {FactorWeighting::kCell, "cell"}});
constexpr const auto& EnumNamesOf(FactorWeighting) {
  return kFactorWeightingNames;
}

// Everything the system matrix depends on besides the cell mask.
struct FactorSystemOptions {
  FactorParam param = FactorParam::kMcCool;
  int resolution = 64;  // texture side N in [4, 1024] (halfdiff: [4, 256]); profiles: N knots
  double lambda = 1e-8;
  FactorWeighting weighting = FactorWeighting::kSolidAngle;
  double max_theta = kPi / 2;  // cells with theta_i or theta_o above this are not used (rad)
  bool operator==(const FactorSystemOptions&) const = default;
};

// How one material was solved with a cached system.
struct FactorSolveInfo {
  std::size_t removed_rows = 0;  // rows of cells with a channel <= 0 or not finite
  int pcg_iterations = 0;        // low-rank correction iterations (0 if none was needed)
  // Data-term residual of the solution, sqrt(sum_c w_c |y_c - a_c^T x|^2 / (3 sum_c w_c)) over
  // the kept rows, channels pooled (before the textures are baked). From the normal equations
  // (M' x = b): |y - A x|_W^2 = y^T W y - x^T b - |L x|^2, no second pass over the rows.
  double weighted_rms = 0;
};

// Per-row data, one RGB triple per row (row-major: a row's channels are adjacent).
using RowValues = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

class FactorSystem {
 public:
  // Builds the rows of every cell with mask[cell] != 0 whose directions at the cell centre are
  // strictly above the horizon and within options.max_theta, then assembles and factors M.
  // Throws InputError if no cell is usable or the system is singular.
  static std::shared_ptr<const FactorSystem> Build(const Grid& grid,
                                                   const std::vector<std::uint8_t>& mask,
                                                   const FactorSystemOptions& options);

  const Grid& grid() const { return grid_; }
  const std::vector<std::uint8_t>& mask() const { return mask_; }
  const FactorSystemOptions& options() const { return options_; }
  int num_p() const { return n_p_; }  // p unknowns come first
  int num_q() const { return n_q_; }
  // num_p() + num_q() of a system built at `resolution`, before building it: radial profiles of
  // `resolution` knots for p (and mccool's q), a resolution^2 texture for halfdiff's q.
  static int NumP(int resolution) { return resolution; }
  static int NumQ(FactorParam param, int resolution) {
    return param == FactorParam::kMcCool ? resolution : resolution * resolution;
  }
  std::size_t num_rows() const { return row_cells_.size(); }
  // Table cell index of each row.
  const std::vector<std::uint32_t>& row_cells() const { return row_cells_; }
  const std::vector<double>& row_weights() const { return row_weight_; }
  double build_seconds() const { return build_seconds_; }
  // A in compressed row storage: row r's unknowns cols()[row_start()[r] .. row_start()[r+1]),
  // weights vals() (log f_r = sum vals * x[cols]); one block of num_p() + num_q() unknowns.
  const std::vector<int>& row_start() const { return row_start_; }
  const std::vector<int>& cols() const { return col_; }
  const std::vector<float>& vals() const { return val_; }
  // L (smoothness, sqrt(lambda)-scaled) with the gauge row g below it: M = A^T W A + S^T S.
  const Eigen::SparseMatrix<double>& smoothing() const { return smooth_; }

  // Solves for x (n x 3) given y = log f per row (rows x 3). Rows listed in `removed` (sorted,
  // no duplicates) are dropped for this material: their y is ignored and their contribution is
  // subtracted from M by a preconditioned conjugate-gradient correction that uses the cached
  // factorization as preconditioner (exact in at most |removed| + 1 steps). Returns false,
  // leaving x untouched, if too many rows are removed or the correction does not converge:
  // the caller then builds a system for the reduced mask.
  bool Solve(const RowValues& y, const std::vector<std::uint32_t>& removed, Eigen::MatrixX3d* x,
             FactorSolveInfo* info) const;

  // The same residual as FactorSolveInfo::weighted_rms by an explicit pass over the rows.
  double WeightedRms(const RowValues& y, const std::vector<std::uint32_t>& removed,
                     const Eigen::MatrixX3d& x) const;

  static constexpr std::size_t kMaxRemovedRows = 4096;
  static constexpr int kMaxHalfDiffResolution = brdfit::kMaxHalfDiffResolution;
  static constexpr int kMaxPcgIterations = 60;

 private:
  FactorSystem() = default;
  // (M - sum_{r in removed} w_r a_r a_r^T) v, for the three channels at once.
  void ApplyReduced(const Eigen::MatrixX3d& v, const std::vector<std::uint32_t>& removed,
                    Eigen::MatrixX3d* out) const;

  Grid grid_;
  std::vector<std::uint8_t> mask_;
  FactorSystemOptions options_;
  int n_p_ = 0, n_q_ = 0;
  std::vector<std::uint32_t> row_cells_;
  std::vector<double> row_weight_;  // cell weights w_c
  // A in compressed row storage (duplicates merged): row r spans [row_start_[r], row_start_[r+1]).
  std::vector<int> row_start_;
  std::vector<int> col_;
  // Interpolation weights in [0, 2] (2: a knot shared by p(wi) and p(wo)), stored in float32:
  // half the memory of the largest array (~26 MB on the MERL grid); 2^-24 relative rounding
  // moves log f by < 1e-6 for log-texel values below ~10; M is assembled from these rounded
  // weights, so the system is exact for the A it stores.
  std::vector<float> val_;
  Eigen::SparseMatrix<double> smooth_;  // L (sqrt(lambda) scaled) and the gauge row g
  Eigen::SparseMatrix<double> normal_;  // M, full symmetric storage
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  double build_seconds_ = 0;
};

// Cache of factored systems, keyed by (grid, mask, options); the mask is compared exactly
// (after a hash check). Least-recently-used entries beyond `capacity` are dropped. Thread-safe.
class FactorSystemCache {
 public:
  explicit FactorSystemCache(std::size_t capacity = 4) : capacity_(capacity) {}
  // Returns the cached system or builds (and caches) one. *hit tells which.
  std::shared_ptr<const FactorSystem> GetOrBuild(const Grid& grid,
                                                 const std::vector<std::uint8_t>& mask,
                                                 const FactorSystemOptions& options,
                                                 bool* hit = nullptr);
  std::size_t size() const;
  void Clear();

 private:
  struct Entry {
    std::uint64_t mask_hash;
    std::shared_ptr<const FactorSystem> system;
  };
  mutable std::mutex mu_;
  std::size_t capacity_;
  std::list<Entry> entries_;  // most recently used first
};

std::uint64_t HashMask(const std::vector<std::uint8_t>& mask);

}  // namespace brdfit
