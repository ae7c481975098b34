// HDF5 access shared by the formats of io/ (tables, fit reports, NBRDF networks): attribute and
// dataset writers that give equal files for equal contents, and a reader of files we did not
// write that checks what libhdf5 would trust (fuzz findings, docs/reliability.md) and throws
// InputError naming the file and the object.
#pragma once

#include <H5Cpp.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace brdfit::hdf5 {

// libhdf5 errors become exceptions with messages, not stderr dumps (once per thread: libhdf5's
// error printing is per thread, and batch fits read and write in worker threads).
void Quiet();

// "HDF5: <function>: <detail>", for an InputError or OutputError naming the file.
std::string Describe(const H5::Exception& e);

// ---- writing ------------------------------------------------------------------------------

// Writes the HDF5 file that fill() builds to dest atomically. The file is built in memory (the
// core driver, no backing store), then its image is written with every write and the close
// checked (io/atomic_file.h): libhdf5 writing to a full disk fails in H5Fclose, which the C++
// API only prints, and a damaged file was renamed into place and the process crashed at exit.
// Throws OutputError naming dest (H5::Exception from fill() too).
void WriteFileImageAtomically(const std::filesystem::path& dest,
                              const std::function<void(H5::H5File& f)>& fill,
                              const H5::FileCreatPropList& fcpl = H5::FileCreatPropList::DEFAULT);

// Dataset creation properties without timestamps: equal contents give equal bytes.
H5::DSetCreatPropList NoTimestamps();

// Scalar attributes, little-endian in the file.
void WriteStringAttr(const H5::H5Object& obj, const char* name, const std::string& value);
void WriteDoubleAttr(const H5::H5Object& obj, const char* name, double value);     // F64LE
void WriteIntAttr(const H5::H5Object& obj, const char* name, std::int64_t value);  // I64LE
void WriteInt32Attr(const H5::H5Object& obj, const char* name, std::int32_t value);
void WriteUint64Attr(const H5::H5Object& obj, const char* name, std::uint64_t value);

// A dataset of shape dims from data (row-major, mem_type), without timestamps; nothing is
// written when it has no elements.
H5::DataSet WriteDataset(const H5::Group& parent, const char* name, const H5::PredType& file_type,
                         const H5::PredType& mem_type, const std::vector<hsize_t>& dims,
                         const void* data);
// A 1-D F64LE dataset.
H5::DataSet WriteDoubles(const H5::Group& parent, const char* name, const std::vector<double>& v);

// ---- reading ------------------------------------------------------------------------------

// Objects are named by `where`, their parent's path ("/" for the root): "/entries/00000@source"
// for an attribute, "/axes/theta_h" for a dataset.
class Reader {
 public:
  // Errors read "<file>: <prefix><problem>" (prefix: e.g. the archive member holding the file).
  explicit Reader(std::filesystem::path file, std::string prefix = "");

  [[noreturn]] void Fail(const std::string& problem) const;

  // The file, read-only: "no such file", "not an HDF5 file" or "... cannot be opened".
  H5::H5File Open() const;

  // Attributes holding one value of at most 8 bytes (strings: 1 MiB), of the class read.
  std::string String(const H5::H5Object& obj, const std::string& where, const char* name) const;
  double Double(const H5::H5Object& obj, const std::string& where,
                const char* name) const;  // finite
  std::int64_t Int(const H5::H5Object& obj, const std::string& where, const char* name) const;
  std::int32_t Int32(const H5::H5Object& obj, const std::string& where, const char* name) const;
  std::uint64_t Uint64(const H5::H5Object& obj, const std::string& where, const char* name) const;

  // Fails unless parent/name is a hard link: an external link would be followed into another
  // file (any path the file names), a soft one elsewhere in this file. Group() and Dataset()
  // check it before opening.
  void RequireHardLink(const H5::Group& parent, const std::string& where,
                       const std::string& name) const;

  H5::Group Group(const H5::Group& parent, const std::string& where, const std::string& name) const;

  // A dataset of class cls with elements of at most 8 bytes; *dims receives its shape.
  H5::DataSet Dataset(const H5::Group& parent, const std::string& where, const std::string& name,
                      H5T_class_t cls, std::vector<hsize_t>* dims) const;

  // Every element of ds (n of them, as mem_type) into out, once its storage is known to hold
  // them: libhdf5 1.10.8 reads a damaged compact dataset by copying from a null buffer and
  // crashes (fuzz/regressions/hdf5_table/damaged-*). Chunked (possibly compressed) storage has
  // no fixed size and is left to libhdf5. `what` names ds in errors.
  void ReadChecked(const H5::DataSet& ds, const std::string& what, const H5::PredType& mem_type,
                   void* out) const;
  // ReadChecked() as doubles, each finite.
  std::vector<double> ReadFinite(const H5::DataSet& ds, const std::string& what) const;

  // Fails unless ds's storage is allocated: a declared shape with nothing stored reads back as
  // fill values, so a few bytes of file could make the caller allocate a huge array
  // (fuzz/regressions/hdf5_table/crafted-unwritten-values.h5). Check before allocating.
  // Chunked storage (compressed or not): every chunk the shape spans stored, every filter
  // decodable.
  void RequireAllocated(const H5::DataSet& ds, const std::string& what) const;

 private:
  void RequireAllChunks(const H5::DataSet& ds, const H5::DSetCreatPropList& plist,
                        const std::string& what) const;
  H5::Attribute Attr(const H5::H5Object& obj, const std::string& where, const char* name,
                     H5T_class_t cls, const char* class_name) const;
  template <class T>
  T Scalar(const H5::H5Object& obj, const std::string& where, const char* name,
           const H5::PredType& mem_type) const;

  std::filesystem::path file_;
  std::string prefix_;
};

// "where/name" with where "/" for the root: "/values", "/axes/theta_h".
std::string Join(const std::string& where, const std::string& name);

}  // namespace brdfit::hdf5
