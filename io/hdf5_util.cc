#include "io/hdf5_util.h"

#include <fmt/core.h>
#include <hdf5.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace brdfit::hdf5 {

namespace fs = std::filesystem;

namespace {

// Longest fixed-length string attribute (provenance parameters, fit options: JSON of a few
// hundred bytes).
constexpr std::size_t kMaxStringBytes = std::size_t{1} << 20;
// Largest non-string element: libhdf5 sizes its conversion buffers by the declared element size
// (fuzz_hdf5_table, fuzz_fit_report, fuzz_nbrdf: float and integer types of gigabytes per
// element made it calloc that much).
constexpr std::size_t kMaxElementBytes = 8;

template <class T>
void WriteScalarAttr(const H5::H5Object& obj, const char* name, const H5::PredType& file_type,
                     const H5::PredType& mem_type, T value) {
  obj.createAttribute(name, file_type, H5::DataSpace(H5S_SCALAR)).write(mem_type, &value);
}

}  // namespace

void Quiet() {
  thread_local const bool once = [] {
    H5::Exception::dontPrint();
    return true;
  }();
  (void)once;
}

void WriteFileImageAtomically(const fs::path& dest, const std::function<void(H5::H5File&)>& fill,
                              const H5::FileCreatPropList& fcpl) {
  Quiet();
  std::vector<char> image;
  try {
    H5::FileAccPropList fapl;
    H5Pset_fapl_core(fapl.getId(), std::size_t{1} << 20, /*backing_store=*/0);
    // A name no other open file has (libhdf5 refuses to create an open file's name twice).
    static std::atomic<unsigned> serial{0};
    const std::string name = fmt::format("{}.in-memory-{}", dest.string(), serial++);
    H5::H5File f(name, H5F_ACC_TRUNC, fcpl, fapl);
    fill(f);
    f.flush(H5F_SCOPE_LOCAL);
    const ssize_t size = H5Fget_file_image(f.getId(), nullptr, 0);
    if (size < 0) throw OutputError(dest, "HDF5: cannot take the file's image");
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(f.getId(), image.data(), image.size()) != size) {
      throw OutputError(dest, "HDF5: cannot take the file's image");
    }
    f.close();
  } catch (const H5::Exception& e) {
    throw OutputError(dest, Describe(e));
  }
  WriteBytesAtomically(dest, image.data(), image.size());
}

std::string Describe(const H5::Exception& e) {
  return "HDF5: " + e.getFuncName() + ": " + e.getDetailMsg();
}

std::string Join(const std::string& where, const std::string& name) {
  return (where == "/" ? "" : where) + "/" + name;
}

// ---- writing ------------------------------------------------------------------------------

H5::DSetCreatPropList NoTimestamps() {
  H5::DSetCreatPropList dcpl;
  H5Pset_obj_track_times(dcpl.getId(), 0);
  return dcpl;
}

void WriteStringAttr(const H5::H5Object& obj, const char* name, const std::string& value) {
  const H5::StrType type(H5::PredType::C_S1, value.size() + 1);  // NUL-terminated
  obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR)).write(type, value.c_str());
}

void WriteDoubleAttr(const H5::H5Object& obj, const char* name, double value) {
  WriteScalarAttr(obj, name, H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE, value);
}

void WriteIntAttr(const H5::H5Object& obj, const char* name, std::int64_t value) {
  WriteScalarAttr(obj, name, H5::PredType::STD_I64LE, H5::PredType::NATIVE_INT64, value);
}

void WriteInt32Attr(const H5::H5Object& obj, const char* name, std::int32_t value) {
  WriteScalarAttr(obj, name, H5::PredType::STD_I32LE, H5::PredType::NATIVE_INT32, value);
}

void WriteUint64Attr(const H5::H5Object& obj, const char* name, std::uint64_t value) {
  WriteScalarAttr(obj, name, H5::PredType::STD_U64LE, H5::PredType::NATIVE_UINT64, value);
}

H5::DataSet WriteDataset(const H5::Group& parent, const char* name, const H5::PredType& file_type,
                         const H5::PredType& mem_type, const std::vector<hsize_t>& dims,
                         const void* data) {
  const H5::DataSpace space(static_cast<int>(dims.size()), dims.data());
  H5::DataSet ds = parent.createDataSet(name, file_type, space, NoTimestamps());
  if (space.getSimpleExtentNpoints() > 0) ds.write(data, mem_type);
  return ds;
}

H5::DataSet WriteDoubles(const H5::Group& parent, const char* name, const std::vector<double>& v) {
  return WriteDataset(parent, name, H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE,
                      {v.size()}, v.data());
}

// ---- reading ------------------------------------------------------------------------------

Reader::Reader(fs::path file, std::string prefix)
    : file_(std::move(file)), prefix_(std::move(prefix)) {}

void Reader::Fail(const std::string& problem) const {
  throw InputError(file_, prefix_ + problem);
}

H5::H5File Reader::Open() const {
  Quiet();
  CheckInputFile(file_);
  if (H5Fis_hdf5(file_.c_str()) <= 0) Fail("not an HDF5 file");
  H5::H5File f;
  try {
    f.openFile(file_.string(), H5F_ACC_RDONLY);
  } catch (const H5::Exception&) {
    Fail("has the HDF5 signature but cannot be opened (truncated or corrupt)");
  }
  return f;
}

H5::Attribute Reader::Attr(const H5::H5Object& obj, const std::string& where, const char* name,
                           H5T_class_t cls, const char* class_name) const {
  if (!obj.attrExists(name)) Fail(fmt::format("missing attribute '{}' on {}", name, where));
  H5::Attribute a = obj.openAttribute(name);
  const std::string what = fmt::format("{}@{}", where, name);
  if (a.getTypeClass() != cls) Fail(fmt::format("{} is not {}", what, class_name));
  // The C++ API reads a string attribute as one element whatever its extent
  // (fuzz/regressions/hdf5_table/crafted-vlen-string-array-attr.h5: stack overflow).
  const H5::DataType type = a.getDataType();
  const std::size_t max = cls == H5T_STRING ? kMaxStringBytes : kMaxElementBytes;
  if (!(cls == H5T_STRING && type.isVariableStr()) && type.getSize() > max) {
    Fail(fmt::format("{} has {}-byte elements (at most {})", what, type.getSize(), max));
  }
  if (a.getSpace().getSimpleExtentNpoints() != 1) Fail(what + " must hold a single value");
  return a;
}

template <class T>
T Reader::Scalar(const H5::H5Object& obj, const std::string& where, const char* name,
                 const H5::PredType& mem_type) const {
  const bool is_float = std::is_floating_point_v<T>;
  H5::Attribute a = Attr(obj, where, name, is_float ? H5T_FLOAT : H5T_INTEGER,
                         is_float ? "a float" : "an integer");
  T v{};
  a.read(mem_type, &v);
  return v;
}

std::string Reader::String(const H5::H5Object& obj, const std::string& where,
                           const char* name) const {
  H5::Attribute a = Attr(obj, where, name, H5T_STRING, "a string");
  std::string s;
  a.read(a.getStrType(), s);
  return s;
}

double Reader::Double(const H5::H5Object& obj, const std::string& where, const char* name) const {
  const double v = Scalar<double>(obj, where, name, H5::PredType::NATIVE_DOUBLE);
  if (!std::isfinite(v)) Fail(fmt::format("{}@{} is not finite", where, name));
  return v;
}

std::int64_t Reader::Int(const H5::H5Object& obj, const std::string& where,
                         const char* name) const {
  return Scalar<std::int64_t>(obj, where, name, H5::PredType::NATIVE_INT64);
}

std::int32_t Reader::Int32(const H5::H5Object& obj, const std::string& where,
                           const char* name) const {
  return Scalar<std::int32_t>(obj, where, name, H5::PredType::NATIVE_INT32);
}

std::uint64_t Reader::Uint64(const H5::H5Object& obj, const std::string& where,
                             const char* name) const {
  return Scalar<std::uint64_t>(obj, where, name, H5::PredType::NATIVE_UINT64);
}

void Reader::RequireHardLink(const H5::Group& parent, const std::string& where,
                             const std::string& name) const {
  H5L_info_t info{};
  if (H5Lget_info(parent.getId(), name.c_str(), &info, H5P_DEFAULT) < 0) {
    Fail("cannot read the link " + Join(where, name));
  }
  if (info.type == H5L_TYPE_HARD) return;
  const char* kind = info.type == H5L_TYPE_SOFT       ? "a soft link"
                     : info.type == H5L_TYPE_EXTERNAL ? "an external link (into another file)"
                                                      : "a user-defined link";
  Fail(fmt::format("{} is {}; brdfit reads only objects stored in the file itself",
                   Join(where, name), kind));
}

H5::Group Reader::Group(const H5::Group& parent, const std::string& where,
                        const std::string& name) const {
  if (!parent.nameExists(name)) Fail("missing group " + Join(where, name));
  RequireHardLink(parent, where, name);
  return parent.openGroup(name);
}

H5::DataSet Reader::Dataset(const H5::Group& parent, const std::string& where,
                            const std::string& name, H5T_class_t cls,
                            std::vector<hsize_t>* dims) const {
  const std::string what = "dataset " + Join(where, name);
  if (!parent.nameExists(name)) Fail("missing " + what);
  RequireHardLink(parent, where, name);
  H5::DataSet ds = parent.openDataSet(name);
  if (ds.getTypeClass() != cls) {
    Fail(fmt::format("{} must hold {}", what, cls == H5T_FLOAT ? "floats" : "integers"));
  }
  const std::size_t size = ds.getDataType().getSize();
  if (size > kMaxElementBytes) {
    Fail(fmt::format("{} has {}-byte elements (at most {})", what, size, kMaxElementBytes));
  }
  const H5::DataSpace space = ds.getSpace();
  dims->resize(space.getSimpleExtentNdims());
  space.getSimpleExtentDims(dims->data());
  return ds;
}

void Reader::ReadChecked(const H5::DataSet& ds, const std::string& what,
                         const H5::PredType& mem_type, void* out) const {
  const H5D_layout_t layout = ds.getCreatePlist().getLayout();
  const hssize_t elements = ds.getSpace().getSimpleExtentNpoints();
  if (elements <= 0) return;
  if (layout == H5D_COMPACT || layout == H5D_CONTIGUOUS) {
    const std::size_t element_bytes = ds.getDataType().getSize();
    const hsize_t stored = ds.getStorageSize();
    if (stored < static_cast<hsize_t>(elements) * element_bytes) {
      Fail(fmt::format("{} is damaged: {} bytes stored for {} elements of {} bytes", what, stored,
                       elements, element_bytes));
    }
  }
  ds.read(out, mem_type);
}

std::vector<double> Reader::ReadFinite(const H5::DataSet& ds, const std::string& what) const {
  std::vector<double> v(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
  ReadChecked(ds, what, H5::PredType::NATIVE_DOUBLE, v.data());
  for (double x : v) {
    if (!std::isfinite(x)) Fail(what + " holds a non-finite value");
  }
  return v;
}

void Reader::RequireAllocated(const H5::DataSet& ds, const std::string& what) const {
  const H5::DSetCreatPropList plist = ds.getCreatePlist();
  if (plist.getLayout() == H5D_CHUNKED) {
    RequireAllChunks(ds, plist, what);
    return;
  }
  H5D_space_status_t status;
  if (H5Dget_space_status(ds.getId(), &status) < 0 || status != H5D_SPACE_STATUS_ALLOCATED) {
    Fail(what + " declares data that the file does not store");
  }
}

// Chunked storage: libhdf5 calls a compressed dataset "partly allocated" (its stored bytes are
// fewer than its elements'), so count the chunks instead: every chunk the shape spans must be
// stored, and every filter must be one this libhdf5 can decode.
void Reader::RequireAllChunks(const H5::DataSet& ds, const H5::DSetCreatPropList& plist,
                              const std::string& what) const {
  const hid_t pl = plist.getId();
  const int nfilters = H5Pget_nfilters(pl);
  for (int i = 0; i < nfilters; ++i) {
    unsigned flags = 0, config = 0;
    std::size_t nvalues = 0;
    char name[64] = {};
    const H5Z_filter_t id = H5Pget_filter2(pl, static_cast<unsigned>(i), &flags, &nvalues,
                                           nullptr, sizeof name, name, &config);
    if (id < 0 || H5Zfilter_avail(id) <= 0) {
      std::string shown;
      for (const char* c = name; *c && shown.size() < 40; ++c) {
        shown += std::isprint(static_cast<unsigned char>(*c)) ? *c : '?';
      }
      Fail(fmt::format("{} is stored through HDF5 filter {} ('{}'), which this libhdf5 cannot "
                       "decode",
                       what, static_cast<long>(id), shown));
    }
  }
  const H5::DataSpace space = ds.getSpace();
  const int rank = space.getSimpleExtentNdims();
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0))), chunk(dims.size());
  space.getSimpleExtentDims(dims.data());
  if (rank <= 0 || H5Pget_chunk(pl, rank, chunk.data()) != rank) {
    Fail(what + " is chunked without a readable chunk shape");
  }
  // Chunks the shape spans; saturates (a shape that large is refused by the caller's cap).
  hsize_t expected = 1;
  for (int k = 0; k < rank; ++k) {
    if (chunk[k] == 0) Fail(what + " has a chunk dimension of 0");
    const hsize_t along = dims[k] / chunk[k] + (dims[k] % chunk[k] != 0);
    if (along == 0) return;  // an empty axis: nothing to store
    expected = along > std::numeric_limits<hsize_t>::max() / expected
                   ? std::numeric_limits<hsize_t>::max()
                   : expected * along;
  }
  hsize_t stored = 0;
  if (H5Dget_num_chunks(ds.getId(), space.getId(), &stored) < 0) {
    Fail(what + ": cannot count its stored chunks");
  }
  if (stored < expected) {
    Fail(fmt::format("{} declares data that the file does not store ({} of {} chunks written)",
                     what, stored, expected));
  }
}

}  // namespace brdfit::hdf5
