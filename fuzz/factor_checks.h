// What the factorization harnesses (fuzz_factor_sidecar, fuzz_factor_files) share: the valid
// rank-2 factorization they put beside the fuzzed file, and the checks after a successful read.
#pragma once

#include <filesystem>

#include "io/factor_io.h"

namespace brdfit::fuzz {

// Parameterization "pq", rank 2, a diffuse value: p is 3 x 2, q is 2 x 4, p2 is 2 x 2, q2 is
// 3 x 3 (fuzz/make_seeds.cc writes the same files as seeds).
FactorFiles ValidFactorFiles();

// The sidecar agrees with the images (sizes, parameterization, factor names, rank) and the
// diffuse value is finite and >= 0.
void CheckFactorAgreement(const FactorFiles& f);

// Writing f to `dir` (stem "g") and reading it back gives the same images, diffuse value and
// parameterization.
void CheckFactorRoundTrip(const FactorFiles& f, const std::filesystem::path& dir);

}  // namespace brdfit::fuzz
