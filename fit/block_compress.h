// Non-template helpers of the compressed residual block (fit/block_cost.h), kept out of the
// per-model autodiff instantiations to keep compile times down.
#pragma once

namespace brdfit::internal {

// gram ((cols x cols), column-major, lower triangle used) += rows^T rows, rows row-major n x cols.
void AccumulateGram(const double* rows, int n, int cols, double* gram);

// From the Gram matrix [J r]^T [J r] ((P+1) x (P+1), lower triangle) and the directly summed
// cost, writes residuals (P + 1) and the row-major (P + 1) x P Jacobian of the compressed block:
// R^T R = J^T J, R^T z = J^T r, |z|^2 + rho^2 = cost (fit/block_cost.h). False if non-finite.
bool CompressGram(const double* gram, int P, double cost, double* residuals, double* jacobian);

}  // namespace brdfit::internal
