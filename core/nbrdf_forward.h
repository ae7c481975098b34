// The NBRDF network's forward pass after its first layer's matrix product, sixteen cells at a
// time with AVX2 and FMA (core/nbrdf_network.cc's TabulateNbrdf uses it where the CPU has
// both; Eigen's GEMM elsewhere). Per cell: h1 = ReLU(p + hpart), h2 = ReLU(h1 K2 + b2), y = h2 K3 +
// b3 (Sztrajman et al. 2021, "Neural BRDF Representation and Importance Sampling", Sec. 3: two
// hidden ReLU layers, log-space output). The sums run in input order with fused multiply-adds: the
// values agree with Eigen's to ~1e-15 relative (tested), not bit for bit.
#pragma once

#include <cstddef>

namespace brdfit {

struct NbrdfForwardArgs {
  const double* p = nullptr;  // first-layer pre-activations, column-major: p[j * p_rows + r]
  std::size_t p_rows = 0;
  const long* rows = nullptr;  // the n rows of p to evaluate
  std::size_t n = 0;
  const double* hpart = nullptr;  // h1 values added to every row
  const double* k2 = nullptr;     // h1 x h2, column-major
  const double* b2 = nullptr;     // h2
  const double* k3 = nullptr;     // h2 x 3, column-major
  const double* b3 = nullptr;     // 3
  int h1 = 0, h2 = 0;
};

// True when this machine has AVX2 and FMA (NbrdfForwardAvx2 may be called).
bool NbrdfForwardVectorized();

// y[3 * i + c] for i < args.n. Only where NbrdfForwardVectorized().
void NbrdfForwardAvx2(const NbrdfForwardArgs& args, double* y);

}  // namespace brdfit
