#include "io/tensor_file.h"

#include <bit>
#include <cstring>
#include <limits>
#include <set>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace brdfit {

static_assert(std::endian::native == std::endian::little, "tensor files are little-endian");

std::size_t TensorTypeBytes(TensorType t) {
  switch (t) {
    case TensorType::kUInt8:
    case TensorType::kInt8:
      return 1;
    case TensorType::kUInt16:
    case TensorType::kInt16:
    case TensorType::kFloat16:
      return 2;
    case TensorType::kUInt32:
    case TensorType::kInt32:
    case TensorType::kFloat32:
      return 4;
    case TensorType::kUInt64:
    case TensorType::kInt64:
    case TensorType::kFloat64:
      return 8;
  }
  return 0;
}

const char* TensorTypeName(TensorType t) {
  switch (t) {
    case TensorType::kUInt8:
      return "uint8";
    case TensorType::kInt8:
      return "int8";
    case TensorType::kUInt16:
      return "uint16";
    case TensorType::kInt16:
      return "int16";
    case TensorType::kUInt32:
      return "uint32";
    case TensorType::kInt32:
      return "int32";
    case TensorType::kUInt64:
      return "uint64";
    case TensorType::kInt64:
      return "int64";
    case TensorType::kFloat16:
      return "float16";
    case TensorType::kFloat32:
      return "float32";
    case TensorType::kFloat64:
      return "float64";
  }
  return "invalid";
}

std::uint64_t TensorField::Count() const {
  std::uint64_t n = 1;
  for (std::uint64_t e : shape) n *= e;
  return n;
}

std::string TensorField::ShapeString() const {
  std::string s = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(shape[i]);
  }
  return s + "]";
}

namespace {

template <typename T>
void AppendAs(const std::vector<std::uint8_t>& bytes, std::vector<double>* out) {
  const std::size_t n = bytes.size() / sizeof(T);
  out->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    (*out)[i] = static_cast<double>(v);
  }
}

// Sequential little-endian reads of the header; every read is bounds-checked.
class HeaderReader {
 public:
  HeaderReader(const std::vector<char>& bytes, const std::filesystem::path& path)
      : bytes_(bytes), path_(path) {}
  template <typename T>
  T Read(const std::string& what) {
    if (bytes_.size() - pos_ < sizeof(T) || pos_ > bytes_.size()) {
      throw InputError(path_, "tensor file truncated in its header (" + what + " at byte " +
                                  std::to_string(pos_) + " of " + std::to_string(bytes_.size()) +
                                  ")");
    }
    T v;
    std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string ReadString(std::size_t n, const std::string& what) {
    if (bytes_.size() - pos_ < n) {
      throw InputError(path_, "tensor file truncated in its header (" + what + ")");
    }
    std::string s(bytes_.data() + pos_, n);
    pos_ += n;
    return s;
  }
  std::size_t pos() const { return pos_; }

 private:
  const std::vector<char>& bytes_;
  const std::filesystem::path& path_;
  std::size_t pos_ = 0;
};

bool PrintableName(const std::string& s) {
  for (unsigned char c : s) {
    if (c < 0x20 || c > 0x7e) return false;
  }
  return !s.empty();
}

}  // namespace

std::vector<double> TensorField::AsDoubles(const std::filesystem::path& file) const {
  std::vector<double> out;
  switch (dtype) {
    case TensorType::kUInt8:
      AppendAs<std::uint8_t>(bytes, &out);
      break;
    case TensorType::kInt8:
      AppendAs<std::int8_t>(bytes, &out);
      break;
    case TensorType::kUInt16:
      AppendAs<std::uint16_t>(bytes, &out);
      break;
    case TensorType::kInt16:
      AppendAs<std::int16_t>(bytes, &out);
      break;
    case TensorType::kUInt32:
      AppendAs<std::uint32_t>(bytes, &out);
      break;
    case TensorType::kInt32:
      AppendAs<std::int32_t>(bytes, &out);
      break;
    case TensorType::kUInt64:
      AppendAs<std::uint64_t>(bytes, &out);
      break;
    case TensorType::kInt64:
      AppendAs<std::int64_t>(bytes, &out);
      break;
    case TensorType::kFloat32:
      AppendAs<float>(bytes, &out);
      break;
    case TensorType::kFloat64:
      AppendAs<double>(bytes, &out);
      break;
    case TensorType::kFloat16:
      throw InputError(file, "field '" + name + "' is float16, which brdfit does not read");
  }
  return out;
}

const TensorField* TensorFile::Find(const std::string& name) const {
  for (const TensorField& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

TensorFile ParseTensorFile(const std::vector<char>& bytes, const std::filesystem::path& path) {
  if (bytes.size() < sizeof(kTensorFileMagic) ||
      std::memcmp(bytes.data(), kTensorFileMagic, sizeof(kTensorFileMagic)) != 0) {
    throw InputError(path, "not a tensor file (it does not start with \"tensor_file\\0\")");
  }
  HeaderReader in(bytes, path);
  in.ReadString(sizeof(kTensorFileMagic), "signature");
  const auto major = in.Read<std::uint8_t>("version");
  const auto minor = in.Read<std::uint8_t>("version");
  if (major != 1 || minor != 0) {
    throw InputError(path, "tensor file version " + std::to_string(major) + "." +
                               std::to_string(minor) + " is not 1.0, the one brdfit reads");
  }
  const auto n_fields = in.Read<std::uint32_t>("field count");
  // A field header takes at least 2 + 1 + 2 + 1 + 8 bytes: more fields than fit are a lie.
  if (n_fields > bytes.size() / 14) {
    throw InputError(path, "tensor file claims " + std::to_string(n_fields) +
                               " fields, more than its " + std::to_string(bytes.size()) +
                               " bytes can hold");
  }
  TensorFile file;
  std::set<std::string> names;
  for (std::uint32_t k = 0; k < n_fields; ++k) {
    const std::string where = "field " + std::to_string(k + 1) + " of " + std::to_string(n_fields);
    const auto name_length = in.Read<std::uint16_t>(where + ": name length");
    TensorField f;
    f.name = in.ReadString(name_length, where + ": name");
    if (!PrintableName(f.name)) {
      throw InputError(
          path, where + " has an empty or unprintable name '" + PrintableExcerpt(f.name, 40) + "'");
    }
    if (!names.insert(f.name).second) {
      throw InputError(path, "field '" + f.name + "' appears twice");
    }
    const auto rank = in.Read<std::uint16_t>(where + ": rank");
    const auto dtype = in.Read<std::uint8_t>(where + ": dtype");
    const auto offset = in.Read<std::uint64_t>(where + ": offset");
    if (dtype < 1 || dtype > 11) {
      throw InputError(path, "field '" + f.name + "' has unknown dtype code " +
                                 std::to_string(dtype) + " (1..11 are defined)");
    }
    f.dtype = static_cast<TensorType>(dtype);
    if (rank > 16) {
      throw InputError(path, "field '" + f.name + "' has rank " + std::to_string(rank) +
                                 " (at most 16 is read)");
    }
    std::uint64_t byte_count = TensorTypeBytes(f.dtype);
    for (std::uint16_t d = 0; d < rank; ++d) {
      const auto extent = in.Read<std::uint64_t>("field '" + f.name + "': shape");
      if (extent != 0 && byte_count > std::numeric_limits<std::uint64_t>::max() / extent) {
        throw InputError(path, "field '" + f.name + "' has a shape whose size overflows");
      }
      byte_count *= extent;
      f.shape.push_back(extent);
    }
    if (offset > bytes.size() || byte_count > bytes.size() - offset) {
      throw InputError(path, "field '" + f.name + "' " + f.ShapeString() + " " +
                                 TensorTypeName(f.dtype) + " needs bytes " +
                                 std::to_string(offset) + ".." +
                                 std::to_string(offset + byte_count) + " but the file has " +
                                 std::to_string(bytes.size()) + " (truncated?)");
    }
    f.bytes.assign(bytes.begin() + static_cast<std::ptrdiff_t>(offset),
                   bytes.begin() + static_cast<std::ptrdiff_t>(offset + byte_count));
    file.fields.push_back(std::move(f));
  }
  return file;
}

TensorFile ReadTensorFile(const std::filesystem::path& path) {
  return ParseTensorFile(ReadWholeFile(path), path);
}

std::vector<char> SerializeTensorFile(const TensorFile& file) {
  std::size_t header = sizeof(kTensorFileMagic) + 2 + 4;
  std::size_t total = 0;
  for (const TensorField& f : file.fields) {
    header += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
    total += f.bytes.size();
  }
  std::vector<char> out(header + total);
  std::size_t pos = 0;
  auto put = [&out, &pos](const void* p, std::size_t n) {
    if (n) std::memcpy(out.data() + pos, p, n);
    pos += n;
  };
  put(kTensorFileMagic, sizeof(kTensorFileMagic));
  const std::uint8_t version[2] = {1, 0};
  put(version, 2);
  const auto n = static_cast<std::uint32_t>(file.fields.size());
  put(&n, 4);
  std::uint64_t offset = header;
  for (const TensorField& f : file.fields) {
    const auto len = static_cast<std::uint16_t>(f.name.size());
    const auto rank = static_cast<std::uint16_t>(f.shape.size());
    const auto dtype = static_cast<std::uint8_t>(f.dtype);
    put(&len, 2);
    put(f.name.data(), f.name.size());
    put(&rank, 2);
    put(&dtype, 1);
    put(&offset, 8);
    for (std::uint64_t e : f.shape) put(&e, 8);
    offset += f.bytes.size();
  }
  for (const TensorField& f : file.fields) put(f.bytes.data(), f.bytes.size());
  return out;
}

void WriteTensorFile(const TensorFile& file, const std::filesystem::path& path) {
  const std::vector<char> bytes = SerializeTensorFile(file);
  WriteBytesAtomically(path, bytes.data(), bytes.size());
}

TensorField Float32Field(std::string name, std::vector<std::uint64_t> shape,
                         const std::vector<double>& values) {
  TensorField f{std::move(name), TensorType::kFloat32, std::move(shape), {}};
  f.bytes.resize(values.size() * 4);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float v = static_cast<float>(values[i]);
    std::memcpy(f.bytes.data() + 4 * i, &v, 4);
  }
  return f;
}

TensorField UInt8Field(std::string name, std::vector<std::uint64_t> shape,
                       const std::vector<std::uint8_t>& values) {
  return TensorField{std::move(name), TensorType::kUInt8, std::move(shape), values};
}

}  // namespace brdfit
