#include "io/hdf5_table.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "core/error.h"
#include "io/hdf5_storage.h"
#include "io/input_file.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

constexpr std::array<const char*, 3> kChannelNames = {"R", "G", "B"};
// Largest grid a file may declare (guards allocations against corrupt shapes): 2^26 cells,
// 46x MERL's grid, 1.7 GB in memory. A hostile file can declare any shape in a few bytes
// (chunked datasets with nothing written, or filters such as scale-offset that store a
// constant chunk in a header), so this cap is what bounds the allocation.
constexpr std::size_t kMaxCells = std::size_t{1} << 26;
// Longest fixed-length string attribute (provenance parameters are JSON of a few hundred bytes).
constexpr std::size_t kMaxStringBytes = std::size_t{1} << 20;

void QuietHdf5() {
  static const bool once = [] {
    H5::Exception::dontPrint();  // errors become exceptions with messages, not stderr dumps
    return true;
  }();
  (void)once;
}

// ---- writing ----------------------------------------------------------------------------

void WriteStringAttr(const H5::H5Object& obj, const char* name, const std::string& value) {
  const H5::StrType type(H5::PredType::C_S1, value.size() + 1);  // NUL-terminated
  H5::Attribute a = obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  a.write(type, value.c_str());
}

template <class T>
void WriteScalarAttr(const H5::H5Object& obj, const char* name, const H5::PredType& file_type,
                     const H5::PredType& mem_type, T value) {
  H5::Attribute a = obj.createAttribute(name, file_type, H5::DataSpace(H5S_SCALAR));
  a.write(mem_type, &value);
}

// Dataset creation properties: no access/modification timestamps, so equal tables give
// byte-identical files.
H5::DSetCreatPropList NoTimestamps() {
  H5::DSetCreatPropList dcpl;
  H5Pset_obj_track_times(dcpl.getId(), 0);
  return dcpl;
}

std::string AxisDefinition(const char* axis, ThetaHMapping m) {
  if (std::string(axis) == "theta_h") {
    return m == ThetaHMapping::kSqrt ? "centre of bin i: (pi/2) ((i + 0.5) / n)^2 (MERL sqrt)"
                                     : "centre of bin i: (pi/2) (i + 0.5) / n";
  }
  if (std::string(axis) == "theta_d") return "centre of bin i: (pi/2) (i + 0.5) / n";
  return "centre of bin i: pi (i + 0.5) / n (folded by reciprocity to [0, pi))";
}

void WriteAxis(const H5::Group& axes, const char* name, const std::vector<double>& centres,
               const char* mapping, const std::string& definition) {
  const hsize_t dims[1] = {centres.size()};
  H5::DataSet ds =
      axes.createDataSet(name, H5::PredType::IEEE_F64LE, H5::DataSpace(1, dims), NoTimestamps());
  ds.write(centres.data(), H5::PredType::NATIVE_DOUBLE);
  WriteStringAttr(ds, "units", "rad");
  WriteStringAttr(ds, "mapping", mapping);
  WriteStringAttr(ds, "definition", definition);
}

void WriteFile(const Table& t, const fs::path& file, const fs::path& dest) {
  const Grid& g = t.grid;
  std::unique_ptr<H5::H5File> created;
  try {
    created = std::make_unique<H5::H5File>(file.string(), H5F_ACC_TRUNC);
  } catch (const H5::Exception& e) {
    throw OutputError(dest, "cannot create temporary file " + file.string() +
                                " (HDF5: " + e.getDetailMsg() + ")");
  }
  H5::H5File& f = *created;
  WriteStringAttr(f, "format", kHdf5TableFormat);
  WriteScalarAttr(f, "format_version", H5::PredType::STD_I32LE, H5::PredType::NATIVE_INT32,
                  std::int32_t{kHdf5TableVersion});

  const hsize_t vdims[4] = {hsize_t(g.n_theta_h), hsize_t(g.n_theta_d), hsize_t(g.n_phi_d), 3};
  H5::DataSet values =
      f.createDataSet("values", H5::PredType::IEEE_F64LE, H5::DataSpace(4, vdims), NoTimestamps());
  values.write(t.rgb.data(), H5::PredType::NATIVE_DOUBLE);
  WriteStringAttr(values, "units", "1/sr");
  WriteStringAttr(values, "description",
                  "BRDF f_r without the cosine factor, linear RGB; [theta_h][theta_d][phi_d][RGB]; "
                  "meaningful only where valid == 1");

  H5::DataSet valid =
      f.createDataSet("valid", H5::PredType::STD_U8LE, H5::DataSpace(3, vdims), NoTimestamps());
  valid.write(t.valid.data(), H5::PredType::NATIVE_UINT8);
  WriteStringAttr(valid, "description", "1 = valid sample, 0 = masked (invalid or missing)");

  H5::Group axes = f.createGroup("axes");
  std::vector<double> c;
  for (int i = 0; i < g.n_theta_h; ++i) c.push_back(g.ThetaHAt(i + 0.5));
  WriteAxis(axes, "theta_h", c, ToString(g.theta_h_mapping),
            AxisDefinition("theta_h", g.theta_h_mapping));
  c.clear();
  for (int i = 0; i < g.n_theta_d; ++i) c.push_back(g.ThetaDAt(i + 0.5));
  WriteAxis(axes, "theta_d", c, "linear", AxisDefinition("theta_d", g.theta_h_mapping));
  c.clear();
  for (int i = 0; i < g.n_phi_d; ++i) c.push_back(g.PhiDAt(i + 0.5));
  WriteAxis(axes, "phi_d", c, "linear", AxisDefinition("phi_d", g.theta_h_mapping));

  const Provenance& p = t.provenance;
  H5::Group prov = f.createGroup("provenance");
  WriteStringAttr(prov, "source", p.source);
  WriteStringAttr(prov, "generator", p.generator);
  WriteStringAttr(prov, "model", p.model);
  WriteStringAttr(prov, "parameters", p.parameters_json);
  WriteScalarAttr(prov, "seed", H5::PredType::STD_U64LE, H5::PredType::NATIVE_UINT64, p.seed);
  WriteScalarAttr(prov, "noise", H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE, p.noise);
  WriteScalarAttr(prov, "missing_fraction", H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE,
                  p.missing_fraction);
}

// ---- reading ----------------------------------------------------------------------------

class Reader {
 public:
  explicit Reader(const fs::path& path) : path_(path) {}

  [[noreturn]] void Fail(const std::string& problem) const { throw InputError(path_, problem); }

  H5::Attribute Attr(const H5::H5Object& obj, const std::string& where, const char* name) const {
    if (!obj.attrExists(name)) Fail(fmt::format("missing attribute '{}' on {}", name, where));
    return obj.openAttribute(name);
  }
  // One element of at most max_bytes: libhdf5 sizes its conversion buffers by the declared
  // element size (fuzz_hdf5_table: a float type of 1.7 GB per element), and the C++ API reads
  // a string attribute as one element whatever its extent
  // (fuzz/regressions/hdf5_table/crafted-vlen-string-array-attr.h5: stack overflow).
  void CheckElement(const H5::AbstractDs& obj, const std::string& what, std::size_t max_bytes,
                    bool scalar) const {
    const H5::DataType type = obj.getDataType();
    if (!(type.getClass() == H5T_STRING && type.isVariableStr()) && type.getSize() > max_bytes) {
      Fail(fmt::format("{} has {}-byte elements (at most {})", what, type.getSize(), max_bytes));
    }
    if (scalar && obj.getSpace().getSimpleExtentNpoints() != 1) {
      Fail(fmt::format("{} must hold a single value", what));
    }
  }

  // Before reading a dataset: its storage must hold every element (io/hdf5_storage.h).
  void CheckStored(const H5::DataSet& ds, const std::string& what) const {
    if (const std::string why = DamagedStorage(ds); !why.empty()) {
      Fail(what + " is damaged: " + why);
    }
  }

  std::string StringAttr(const H5::H5Object& obj, const std::string& where,
                         const char* name) const {
    H5::Attribute a = Attr(obj, where, name);
    if (a.getTypeClass() != H5T_STRING) Fail(fmt::format("{}@{} is not a string", where, name));
    CheckElement(a, fmt::format("{}@{}", where, name), kMaxStringBytes, true);
    std::string s;
    a.read(a.getStrType(), s);
    return s;
  }
  template <class T>
  T ScalarAttr(const H5::H5Object& obj, const std::string& where, const char* name,
               const H5::PredType& mem_type, H5T_class_t cls) const {
    H5::Attribute a = Attr(obj, where, name);
    if (a.getTypeClass() != cls || a.getSpace().getSimpleExtentNpoints() != 1) {
      Fail(fmt::format("{}@{} has the wrong type", where, name));
    }
    CheckElement(a, fmt::format("{}@{}", where, name), 8, true);
    T v{};
    a.read(mem_type, &v);
    return v;
  }
  H5::DataSet Dataset(const H5::Group& parent, const std::string& name, H5T_class_t cls,
                      std::vector<hsize_t>* dims) const {
    if (!parent.nameExists(name)) Fail("missing dataset /" + name);
    H5::DataSet ds = parent.openDataSet(name);
    if (ds.getTypeClass() != cls) Fail(fmt::format("dataset /{} has the wrong type", name));
    CheckElement(ds, "dataset /" + name, 8, false);
    const H5::DataSpace space = ds.getSpace();
    dims->resize(space.getSimpleExtentNdims());
    space.getSimpleExtentDims(dims->data());
    return ds;
  }

  Table Read() const {
    H5::H5File f;
    try {
      f.openFile(path_.string(), H5F_ACC_RDONLY);
    } catch (const H5::Exception&) {
      Fail("has the HDF5 signature but cannot be opened (truncated or corrupt)");
    }
    const std::string format = StringAttr(f, "/", "format");
    if (format != kHdf5TableFormat) {
      Fail(fmt::format("format is '{}', expected '{}'", format, kHdf5TableFormat));
    }
    const auto version =
        ScalarAttr<std::int32_t>(f, "/", "format_version", H5::PredType::NATIVE_INT32, H5T_INTEGER);
    if (version != kHdf5TableVersion) {
      Fail(fmt::format("format_version {} is not supported (this brdfit reads {})", version,
                       kHdf5TableVersion));
    }

    std::vector<hsize_t> vdims, mdims;
    H5::DataSet values = Dataset(f, "values", H5T_FLOAT, &vdims);
    H5::DataSet valid = Dataset(f, "valid", H5T_INTEGER, &mdims);
    if (vdims.size() != 4 || vdims[3] != 3) {
      Fail("dataset /values must have shape [n_theta_h][n_theta_d][n_phi_d][3]");
    }
    if (mdims.size() != 3 || mdims[0] != vdims[0] || mdims[1] != vdims[1] || mdims[2] != vdims[2]) {
      Fail("dataset /valid must have shape [n_theta_h][n_theta_d][n_phi_d] matching /values");
    }
    for (int k = 0; k < 3; ++k) {
      if (vdims[k] < 1) Fail("dataset /values has an empty axis");
    }
    // Overflow-safe: the product of three hsize_t can wrap to a small number
    // (fuzz/regressions/hdf5_table/crafted-product-overflow.h5).
    if (vdims[0] > kMaxCells || vdims[1] > kMaxCells / vdims[0] ||
        vdims[2] > kMaxCells / (vdims[0] * vdims[1])) {
      Fail(fmt::format("grid {}x{}x{} is too large (at most {} cells)", vdims[0], vdims[1],
                       vdims[2], kMaxCells));
    }
    // A declared shape with no stored data reads back as fill values: a few kB of file could
    // make us allocate the cap (fuzz/regressions/hdf5_table/crafted-unwritten-values.h5).
    for (const auto& [ds, name] : {std::pair{&values, "values"}, std::pair{&valid, "valid"}}) {
      H5D_space_status_t status;
      if (H5Dget_space_status(ds->getId(), &status) < 0 || status != H5D_SPACE_STATUS_ALLOCATED) {
        Fail(fmt::format("dataset /{} declares data that the file does not store", name));
      }
    }

    Grid g;
    g.n_theta_h = static_cast<int>(vdims[0]);
    g.n_theta_d = static_cast<int>(vdims[1]);
    g.n_phi_d = static_cast<int>(vdims[2]);
    if (!f.nameExists("axes")) Fail("missing group /axes");
    const H5::Group axes = f.openGroup("axes");
    const std::string mapping =
        StringAttr(ReadAxisDataset(axes, "theta_h", g.n_theta_h), "/axes/theta_h", "mapping");
    if (mapping == "sqrt") {
      g.theta_h_mapping = ThetaHMapping::kSqrt;
    } else if (mapping == "linear") {
      g.theta_h_mapping = ThetaHMapping::kLinear;
    } else {
      Fail(fmt::format("/axes/theta_h mapping is '{}', expected sqrt or linear", mapping));
    }
    CheckAxis(axes, "theta_h", g.n_theta_h, [&](double u) { return g.ThetaHAt(u); });
    CheckAxis(axes, "theta_d", g.n_theta_d, [&](double u) { return g.ThetaDAt(u); });
    CheckAxis(axes, "phi_d", g.n_phi_d, [&](double u) { return g.PhiDAt(u); });
    for (const char* name : {"theta_d", "phi_d"}) {
      const std::string m =
          StringAttr(axes.openDataSet(name), std::string("/axes/") + name, "mapping");
      if (m != "linear") Fail(fmt::format("/axes/{} mapping is '{}', expected linear", name, m));
    }

    Table t = Table::Empty(g);
    CheckStored(values, "dataset /values");
    CheckStored(valid, "dataset /valid");
    values.read(t.rgb.data(), H5::PredType::NATIVE_DOUBLE);
    valid.read(t.valid.data(), H5::PredType::NATIVE_UINT8);
    for (std::size_t i = 0; i < g.NumCells(); ++i) {
      if (t.valid[i] > 1) Fail(fmt::format("/valid[{}] is {}, expected 0 or 1", i, t.valid[i]));
      if (!t.valid[i]) continue;
      for (int c = 0; c < 3; ++c) {
        const double v = t.rgb[3 * i + c];
        if (!std::isfinite(v)) {
          int ih, id, ip;
          g.Unindex(i, &ih, &id, &ip);
          Fail(fmt::format("{} at valid cell {} (theta_h {}, theta_d {}, phi_d {}), channel {}",
                           std::isnan(v) ? "NaN" : "Inf", i, ih, id, ip, kChannelNames[c]));
        }
      }
    }

    if (!f.nameExists("provenance")) Fail("missing group /provenance");
    const H5::Group prov = f.openGroup("provenance");
    Provenance& p = t.provenance;
    p.source = StringAttr(prov, "/provenance", "source");
    p.generator = StringAttr(prov, "/provenance", "generator");
    p.model = StringAttr(prov, "/provenance", "model");
    p.parameters_json = StringAttr(prov, "/provenance", "parameters");
    p.seed = ScalarAttr<std::uint64_t>(prov, "/provenance", "seed", H5::PredType::NATIVE_UINT64,
                                       H5T_INTEGER);
    p.noise =
        ScalarAttr<double>(prov, "/provenance", "noise", H5::PredType::NATIVE_DOUBLE, H5T_FLOAT);
    p.missing_fraction = ScalarAttr<double>(prov, "/provenance", "missing_fraction",
                                            H5::PredType::NATIVE_DOUBLE, H5T_FLOAT);
    return t;
  }

 private:
  H5::DataSet ReadAxisDataset(const H5::Group& axes, const char* name, int n) const {
    std::vector<hsize_t> dims;
    const std::string full = std::string("axes/") + name;
    if (!axes.nameExists(name)) Fail("missing dataset /" + full);
    H5::DataSet ds = axes.openDataSet(name);
    if (ds.getTypeClass() != H5T_FLOAT) Fail(fmt::format("dataset /{} has the wrong type", full));
    CheckElement(ds, "dataset /" + full, 8, false);
    const H5::DataSpace space = ds.getSpace();
    dims.resize(space.getSimpleExtentNdims());
    space.getSimpleExtentDims(dims.data());
    if (dims.size() != 1 || dims[0] != static_cast<hsize_t>(n)) {
      Fail(fmt::format("dataset /{} must have {} entries (one per bin)", full, n));
    }
    return ds;
  }

  // The stored centres must be the grid's cell centres (the file's axis definition).
  template <class F>
  void CheckAxis(const H5::Group& axes, const char* name, int n, F angle_at) const {
    H5::DataSet ds = ReadAxisDataset(axes, name, n);
    CheckStored(ds, std::string("dataset /axes/") + name);
    std::vector<double> c(n);
    ds.read(c.data(), H5::PredType::NATIVE_DOUBLE);
    for (int i = 0; i < n; ++i) {
      const double expected = angle_at(i + 0.5);
      if (!(std::fabs(c[i] - expected) <= 1e-9)) {
        Fail(
            fmt::format("/axes/{}[{}] is {}, expected the bin centre {}", name, i, c[i], expected));
      }
    }
  }

  fs::path path_;
};

}  // namespace

Table ReadHdf5Table(const fs::path& path) {
  QuietHdf5();
  CheckInputFile(path);
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(path, "not an HDF5 file");
  try {
    return Reader(path).Read();
  } catch (const H5::Exception& e) {
    throw InputError(path, "HDF5: " + e.getFuncName() + ": " + e.getDetailMsg());
  }
}

void WriteHdf5Table(const Table& t, const fs::path& path) {
  QuietHdf5();
  if (t.rgb.size() != 3 * t.grid.NumCells() || t.valid.size() != t.grid.NumCells()) {
    throw std::invalid_argument("WriteHdf5Table: table arrays do not match its grid");
  }
  WriteFileAtomically(path, [&](const fs::path& tmp) {
    try {
      WriteFile(t, tmp, path);
    } catch (const H5::FileIException& e) {
      throw OutputError(path, "cannot create temporary file " + tmp.string() +
                                  " (HDF5: " + e.getDetailMsg() + ")");
    } catch (const H5::Exception& e) {
      throw OutputError(path, "HDF5: " + e.getFuncName() + ": " + e.getDetailMsg());
    }
  });
}

}  // namespace brdfit
