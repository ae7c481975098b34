// Neural BRDFs of the 100 MERL materials (Sztrajman, Rainer, Ritschel, Weyrich 2021, "Neural
// BRDF Representation and Importance Sampling", Computer Graphics Forum), as distributed in
// ../shared/data/merl_nbrdf.zip: merl_nbrdf/<material>.h5 holds three dense layers
//   dense_k/dense_k/kernel:0  float32 [in][out],  dense_k/dense_k/bias:0  float32 [out].
// Evaluation (shared/data/README.md), row vector x, in double:
//   x  = (sin th, 0, cos th, sin td cos pd, sin td sin pd, cos td)   (half and difference vectors)
//   h1 = relu(x K1 + b1),  h2 = relu(h1 K2 + b2),  y = h2 K3 + b3,   f_r = exp(y) - 1  [1/sr]
// The output is f_r in 1/sr with MERL's channel scales already applied.
// This file reads the archive; the network and its evaluation are core/nbrdf_network.h.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_name.h"
#include "core/nbrdf_network.h"

namespace brdfit {

// Inputs that name a network of the archive, "nbrdf:NAME": core/input_name.h.

// The materials in the archive (names of merl_nbrdf/*.h5 without extension), sorted; empty for
// an archive without such members (callers that need one say kNoNbrdfMaterials).
// Throws InputError if the archive is missing or unreadable.
inline constexpr const char* kNoNbrdfMaterials =
    "holds no NBRDF materials (no member merl_nbrdf/<name>.h5)";
std::vector<std::string> ListNbrdfMaterials(const std::filesystem::path& zip);

// Reads one network: the member is decompressed into memory and opened by HDF5 from there (no
// temporary file). Throws InputError naming the archive and the problem (unknown material,
// missing dataset, wrong shape, non-finite weight).
NbrdfNetwork ReadNbrdf(const std::filesystem::path& zip, const std::string& material);

}  // namespace brdfit
