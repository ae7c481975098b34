// Fuzz harness: RGL .bsdf reader (io/tensor_file.h, io/rgl_bsdf_file.h) and the evaluation of
// what it accepts (core/rgl_bsdf.h).
//
// The input is the file as is. After a successful read: the evaluator builds, a tabulation on a
// small grid accounts for every cell (valid + below the horizon + not covered + not finite),
// every valid cell is finite and non-negative, and the tensor container survives a
// serialize -> parse round trip byte for byte.
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rgl_bsdf.h"
#include "fuzz/harness_util.h"
#include "io/rgl_bsdf_file.h"
#include "io/tensor_file.h"

namespace brdfit::fuzz {

int FuzzRglBsdf(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = WriteScratch("in.bsdf", data, size);
  TensorFile tensors;
  RglBsdf b;
  try {
    tensors = ReadTensorFile(path);
    b = RglBsdfFromTensors(tensors, path);
  } catch (const InputError&) {
    return 0;  // rejected with a message: the expected outcome for bad input
  }
  const Grid grid{6, 5, 8, ThetaHMapping::kLinear};
  RglTabulation n;
  const Table t = TabulateRglBsdf(b, grid, &n);
  CheckInvariant(t.CountValid() + n.below_horizon + n.uncovered + n.not_finite == grid.NumCells(),
                 "tabulation counts do not add up to the grid");
  for (std::size_t i = 0; i < grid.NumCells(); ++i) {
    if (!t.valid[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double v = t.Value(i)[c];
      if (!(std::isfinite(v) && v >= 0))
        Violation("valid cell " + std::to_string(i) + " is " + std::to_string(v));
    }
  }
  const std::vector<char> bytes = SerializeTensorFile(tensors);
  const TensorFile back = ParseTensorFile(bytes, path);
  CheckInvariant(back.fields.size() == tensors.fields.size(), "round trip changed the fields");
  for (std::size_t k = 0; k < back.fields.size(); ++k) {
    CheckInvariant(back.fields[k].name == tensors.fields[k].name &&
                       back.fields[k].shape == tensors.fields[k].shape &&
                       back.fields[k].bytes == tensors.fields[k].bytes,
                   "round trip changed a field");
  }
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzRglBsdf)
