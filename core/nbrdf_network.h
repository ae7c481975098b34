// Neural BRDFs of the 100 MERL materials (Sztrajman, Rainer, Ritschel, Weyrich 2021, "Neural
// BRDF Representation and Importance Sampling", Computer Graphics Forum), as distributed in
// ../shared/data/merl_nbrdf.zip: merl_nbrdf/<material>.h5 holds three dense layers
//   dense_k/dense_k/kernel:0  float32 [in][out],  dense_k/dense_k/bias:0  float32 [out].
// Evaluation (shared/data/README.md), row vector x, in double:
//   x  = (sin th, 0, cos th, sin td cos pd, sin td sin pd, cos td)   (half and difference vectors)
//   h1 = relu(x K1 + b1),  h2 = relu(h1 K2 + b2),  y = h2 K3 + b3,   f_r = exp(y) - 1  [1/sr]
// The output is f_r in 1/sr with MERL's channel scales already applied.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>

#include "core/table.h"
#include "models/geometry.h"

namespace brdfit {

struct NbrdfNetwork {
  std::string material;
  std::string source;  // "<zip>:merl_nbrdf/<material>.h5"
  // Kernels input-major as stored (x K + b with row vectors x).
  Eigen::MatrixXd k1, k2, k3;
  Eigen::RowVectorXd b1, b2, b3;
};

// Network output exp(y) - 1 at one angle triple, unclamped (can be slightly negative).
std::array<double, 3> EvalNbrdf(const NbrdfNetwork& net, const HalfDiffAngles& a);

struct NbrdfTabulation {
  Table table;
  std::size_t below_horizon = 0;   // cells masked: a direction at the cell centre is below
  std::size_t clamped_values = 0;  // valid (cell, channel) outputs < 0 set to 0
  std::size_t clamped_cells = 0;   // valid cells with at least one clamped channel
};

// Tabulates a network at the cell centres of a grid (core/table.h) following the README: cells
// whose incident or outgoing direction is below the horizon are invalid, negative outputs are
// clamped to 0 and counted. Batched with Eigen, one theta_h slice at a time, on `threads`
// threads (results do not depend on the thread count). Throws InputError if an output is not
// finite.
NbrdfTabulation TabulateNbrdf(const NbrdfNetwork& net, const Grid& grid, int threads = 1);

}  // namespace brdfit
