#include "io/hdf5_storage.h"

#include <fmt/format.h>

namespace brdfit {

std::string DamagedStorage(const H5::DataSet& ds) {
  const H5D_layout_t layout = ds.getCreatePlist().getLayout();
  if (layout != H5D_COMPACT && layout != H5D_CONTIGUOUS) return "";
  const hssize_t elements = ds.getSpace().getSimpleExtentNpoints();
  const std::size_t element_bytes = ds.getDataType().getSize();
  const hsize_t stored = ds.getStorageSize();
  if (elements <= 0 || stored >= static_cast<hsize_t>(elements) * element_bytes) return "";
  return fmt::format("{} bytes stored for {} elements of {} bytes", stored, elements,
                     element_bytes);
}

}  // namespace brdfit
