// Fuzz harness: brdfit's HDF5 table reader (io/hdf5_table.h) through LoadTable (io/table_io.h),
// so format detection runs too. The input is the whole file.
//
// libhdf5 is not built with sanitizers or coverage: the fuzzer is guided by our reader's
// branches (which attribute, dataset, shape, axis or value check fails), while ASan still sees
// what libhdf5 does to memory it was handed by us (buffers we allocate from declared shapes).
// After a successful read: sizes, mask values, finiteness of valid cells, and an exact
// write -> read round trip (io/hdf5_table.h promises it bit for bit).
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/hdf5_table.h"
#include "io/table_io.h"

namespace brdfit::fuzz {

namespace {

void CheckTable(const Table& t) {
  const Grid& g = t.grid;
  CheckInvariant(g.n_theta_h > 0 && g.n_theta_d > 0 && g.n_phi_d > 0, "grid has an empty axis");
  const std::size_t n = g.NumCells();
  CheckInvariant(t.rgb.size() == 3 * n && t.valid.size() == n, "array sizes");
  for (std::size_t i = 0; i < n; ++i) {
    if (t.valid[i] > 1) Violation("mask value not 0/1 at cell " + std::to_string(i));
    if (!t.valid[i]) continue;
    const double* v = t.Value(i);
    if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
      Violation("valid cell " + std::to_string(i) + " is not finite");
    }
  }
}

bool SameBits(const Table& a, const Table& b) {
  return a.grid == b.grid && a.valid == b.valid && a.provenance == b.provenance &&
         a.rgb.size() == b.rgb.size() &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(double)) == 0;
}

// The reader must release every HDF5 object and file descriptor, also when it rejects a file
// (a long batch over bad files must not run out of either).
void CheckNothingOpen(std::size_t fds_before) {
  // Datatypes are left out: the C++ API keeps its predefined types (PredType) open for good.
  const ssize_t objects = H5Fget_obj_count(
      H5F_OBJ_ALL, H5F_OBJ_FILE | H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_ATTR);
  if (objects != 0) Violation("HDF5 objects left open: " + std::to_string(objects));
  const std::size_t fds = OpenFdCount();
  if (fds != fds_before) {
    Violation("file descriptors " + std::to_string(fds_before) + " -> " + std::to_string(fds));
  }
}

}  // namespace

int FuzzHdf5Table(const std::uint8_t* data, std::size_t size) {
  const auto path = WriteScratch("table-in.h5", data, size);
  const std::size_t fds = OpenFdCount();
  Table t;
  try {
    t = LoadTable(path);
  } catch (const InputError&) {
    CheckNothingOpen(fds);
    return 0;  // rejected with a message: the expected outcome for bad input
  }
  CheckNothingOpen(fds);
  CheckTable(t);

  const auto out = ScratchDir() / "table-out.h5";
  WriteHdf5Table(t, out);
  CheckInvariant(SameBits(ReadHdf5Table(out), t), "write -> read round trip changed the table");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzHdf5Table)
