// Helpers of the compressed residual blocks (fit/block_cost.h, fit/pixel_cost.h): the Gram
// accumulation and compression (non-template, kept out of the per-model autodiff
// instantiations to keep compile times down) and the two small templates both blocks share.
#pragma once

#include <array>
#include <cmath>

#include "fit/param_layout.h"

namespace brdfit::internal {

// gram ((cols x cols), column-major, lower triangle used) += rows^T rows, rows row-major n x cols.
void AccumulateGram(const double* rows, int n, int cols, double* gram);

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

// Rows [grad r, r] (kCols = P + 1 wide) gathered in chunks and added to the Gram matrix.
template <int kCols>
class GramRows {
 public:
  double* Next() { return &rows_[filled_ * kCols]; }  // fill it, then Commit()
  void Commit() {
    if (++filled_ == kChunk) Flush();
  }
  const double* Finish() {
    Flush();
    return gram_.data();
  }

 private:
  void Flush() {
    AccumulateGram(rows_.data(), filled_, kCols, gram_.data());
    filled_ = 0;
  }
  static constexpr int kChunk = 64;
  std::array<double, kChunk * kCols> rows_;
  std::array<double, kCols * kCols> gram_{};
  int filled_ = 0;
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
