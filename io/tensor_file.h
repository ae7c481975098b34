// The "tensor file" container of Mitsuba and of the RGL material database's `.bsdf` files
// (Dupuy & Jakob 2018, "An Adaptive Parameterization for Efficient Material Acquisition and
// Rendering", ACM TOG 37(6); layout as the authors' loader and Mitsuba 2's TensorFile read it),
// little-endian throughout:
//
//   "tensor_file\0" (12 bytes), version major 1, minor 0 (2 bytes), field count (u32),
//   per field: name length (u16), name, rank (u16), dtype (u8), data offset from the start of
//   the file (u64), rank extents (u64 each); then the fields' data, row-major (last index
//   fastest), at their offsets.
//
// dtype codes: 1 u8, 2 i8, 3 u16, 4 i16, 5 u32, 6 i32, 7 u64, 8 i64, 9 f16, 10 f32, 11 f64.
// Reading is strict: every byte of every field inside the file, no two fields of one name, no
// extent product that overflows; each problem is an InputError naming the file and the field.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace brdfit {

enum class TensorType : std::uint8_t {
  kUInt8 = 1,
  kInt8 = 2,
  kUInt16 = 3,
  kInt16 = 4,
  kUInt32 = 5,
  kInt32 = 6,
  kUInt64 = 7,
  kInt64 = 8,
  kFloat16 = 9,
  kFloat32 = 10,
  kFloat64 = 11,
};

std::size_t TensorTypeBytes(TensorType t);
const char* TensorTypeName(TensorType t);

struct TensorField {
  std::string name;
  TensorType dtype = TensorType::kFloat32;
  std::vector<std::uint64_t> shape;
  std::vector<std::uint8_t> bytes;  // the raw data, little-endian, row-major

  std::uint64_t Count() const;
  // The values as double: float32, float64 and the integer types (exact up to 2^53). Float16 is
  // refused (InputError naming the field) since no `.bsdf` field uses it.
  std::vector<double> AsDoubles(const std::filesystem::path& file) const;
  std::string ShapeString() const;  // "[2, 6, 32, 32]"
};

struct TensorFile {
  std::vector<TensorField> fields;  // in the order of the file's header

  const TensorField* Find(const std::string& name) const;
};

// The 12 bytes every tensor file starts with.
inline constexpr char kTensorFileMagic[12] = {'t', 'e', 'n', 's', 'o', 'r',
                                              '_', 'f', 'i', 'l', 'e', '\0'};

TensorFile ReadTensorFile(const std::filesystem::path& path);
// Parses a tensor file held in memory; `path` names it in messages.
TensorFile ParseTensorFile(const std::vector<char>& bytes, const std::filesystem::path& path);

// Serializes fields (header, then the data in order, each at the next offset).
std::vector<char> SerializeTensorFile(const TensorFile& file);
// Writes atomically (io/atomic_file.h); OutputError on failure.
void WriteTensorFile(const TensorFile& file, const std::filesystem::path& path);

// Field constructors for writers.
TensorField Float32Field(std::string name, std::vector<std::uint64_t> shape,
                         const std::vector<double>& values);
TensorField UInt8Field(std::string name, std::vector<std::uint64_t> shape,
                       const std::vector<std::uint8_t>& values);

}  // namespace brdfit
