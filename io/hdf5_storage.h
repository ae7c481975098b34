// A check before reading an HDF5 dataset of a file we did not write.
#pragma once

#include <H5Cpp.h>

#include <string>

namespace brdfit {

// Empty when the dataset's compact or contiguous storage holds every element; otherwise what
// is wrong ("0 bytes stored for 36 elements of 8 bytes"). libhdf5 1.10.8 reads a damaged
// compact dataset by copying from a null buffer and crashes (fuzz_hdf5_table: fuzz/regressions/
// hdf5_table/damaged-*); checking first turns such a file into a clear error. Chunked (possibly
// compressed) storage has no fixed size and is left to libhdf5.
std::string DamagedStorage(const H5::DataSet& ds);

}  // namespace brdfit
