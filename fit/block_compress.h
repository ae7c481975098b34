// Helpers of the compressed residual blocks (fit/block_cost.h, fit/pixel_cost.h): the Gram
// accumulation and compression (non-template, kept out of the per-model autodiff
// instantiations to keep compile times down) and the two small templates both blocks share.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <mutex>

#include "fit/param_layout.h"

namespace brdfit::internal {

// The rows of a Gram chunk: GramRows (below) keeps kGramChunk of them column by column.
inline constexpr int kGramChunk = 64;

// gram ((cols x cols), column-major, lower triangle) += C^T C, where C is kGramChunk x cols and
// column-major (column c at columns + c * kGramChunk; unused rows zero). Each entry is a dot
// product of two columns summed in four interleaved partial sums (rows r = l mod 4 into lane l,
// then (l0 + l1) + (l2 + l3)), without fused multiply-adds: the same bits whether the AVX or
// the portable loop runs.
void AccumulateGramColumns(const double* columns, int cols, double* gram);
// The portable loop alone (what AccumulateGramColumns runs without AVX): for tests.
void AccumulateGramColumnsPortable(const double* columns, int cols, double* gram);

// From the Gram matrix [J r]^T [J r] ((P+1) x (P+1), lower triangle) and the directly summed
// cost, writes residuals (P + 1) and the row-major (P + 1) x P Jacobian of the compressed block:
// R^T R = J^T J, R^T z = J^T r, |z|^2 + rho^2 = cost (fit/block_cost.h). False if non-finite.
bool CompressGram(const double* gram, int P, double cost, double* residuals, double* jacobian);

// The cost-only evaluation of a compressed block: P zeros and sqrt(cost), so that the residuals'
// squares sum to the directly summed cost. False if the cost is not finite.
inline bool CostOnlyResiduals(int P, double cost, double* residuals) {
  if (!std::isfinite(cost)) return false;
  for (int i = 0; i < P; ++i) residuals[i] = 0.0;
  residuals[P] = std::sqrt(cost);
  return true;
}

// Rows [grad r, r] (kCols = P + 1 wide) gathered in chunks and added to the Gram matrix. A row
// is written into a scratch row and stored column by column, so that each Gram entry is one
// contiguous dot product (AccumulateGramColumns; ~1.5x faster per row than Eigen's rank update
// of the row-major chunk at 9 and at 19 columns, transposition included: bench/bench_gram.cc).
template <int kCols>
class GramRows {
 public:
  double* Next() { return row_.data(); }  // fill it, then Commit()
  void Commit() {
    for (int c = 0; c < kCols; ++c) columns_[c * kGramChunk + filled_] = row_[c];
    if (++filled_ == kGramChunk) Flush();
  }
  const double* Finish() {
    Flush();
    return gram_.data();
  }

 private:
  void Flush() {
    if (filled_ == 0) return;
    for (int c = 0; c < kCols; ++c) {
      std::fill(&columns_[c * kGramChunk + filled_], &columns_[(c + 1) * kGramChunk], 0.0);
    }
    AccumulateGramColumns(columns_.data(), kCols, gram_.data());
    filled_ = 0;
  }
  std::array<double, kCols> row_;
  alignas(32) std::array<double, kGramChunk * kCols> columns_;
  std::array<double, kCols * kCols> gram_{};
  int filled_ = 0;
};

// A block's last Jacobian evaluation, given again for the same x bit for bit. Ceres 2.1's
// projected line search (bounded problems) evaluates the gradient, so every block's Jacobian, at
// x + delta; when the step is taken the minimizer evaluates the cost and then the Jacobian at that
// same point again. A block whose Jacobian evaluation sums its cost as the cost-only evaluation
// does (same terms, same order) answers both repeats from here: one Jacobian per LM iteration
// instead of two, the same iterates. Thread-safe (Ceres may evaluate blocks on several threads).
template <int P>
class JacobianCache {
 public:
  // True when x is the cached point: residuals (and the Jacobian, when asked for) written.
  bool Answer(const double* x, double* residuals, double* jacobian) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!valid_ || std::memcmp(x_.data(), x, sizeof x_) != 0) return false;
    if (jacobian == nullptr) return CostOnlyResiduals(P, cost_, residuals);
    std::memcpy(residuals, residuals_.data(), sizeof residuals_);
    std::memcpy(jacobian, jacobian_.data(), sizeof jacobian_);
    return true;
  }
  void Store(const double* x, const double* residuals, const double* jacobian, double cost) {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::memcpy(x_.data(), x, sizeof x_);
    std::memcpy(residuals_.data(), residuals, sizeof residuals_);
    std::memcpy(jacobian_.data(), jacobian, sizeof jacobian_);
    cost_ = cost;
    valid_ = true;
  }

 private:
  mutable std::mutex mutex_;
  bool valid_ = false;
  std::array<double, P> x_{};
  std::array<double, P + 1> residuals_{};
  std::array<double, (P + 1) * P> jacobian_{};
  double cost_ = 0;
};

// The parameters as Jets seeded in optimization space: p_i = exp(x_i) for log_scale ones.
template <class Jet, int P>
void SeedParams(const ParamLayout& layout, const double* x, Jet* p) {
  for (int i = 0; i < P; ++i) {
    const Jet xi(x[i], i);
    p[i] = layout.specs[i].log_scale ? exp(xi) : xi;
  }
}

}  // namespace brdfit::internal
