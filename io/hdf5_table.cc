#include "io/hdf5_table.h"

#include <H5Cpp.h>
#include <fmt/core.h>
#include <hdf5.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/hdf5_util.h"

namespace brdfit {

namespace fs = std::filesystem;

namespace {

constexpr std::array<const char*, 3> kChannelNames = {"R", "G", "B"};
// Largest grid a file may declare (guards allocations against corrupt shapes): 2^26 cells,
// 46x MERL's grid, 1.7 GB in memory. A hostile file can declare any shape in a few bytes
// (chunked datasets with nothing written, or filters such as scale-offset that store a
// constant chunk in a header), so this cap is what bounds the allocation.
constexpr std::size_t kMaxCells = std::size_t{1} << 26;
using hdf5::WriteStringAttr;

// ---- writing ----------------------------------------------------------------------------

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
  const H5::DataSet ds = hdf5::WriteDoubles(axes, name, centres);
  WriteStringAttr(ds, "units", "rad");
  WriteStringAttr(ds, "mapping", mapping);
  WriteStringAttr(ds, "definition", definition);
}

void WriteFile(const Table& t, H5::H5File& f) {
  const Grid& g = t.grid;
  WriteStringAttr(f, "format", kHdf5TableFormat);
  hdf5::WriteInt32Attr(f, "format_version", kHdf5TableVersion);

  const std::vector<hsize_t> vdims = {hsize_t(g.n_theta_h), hsize_t(g.n_theta_d),
                                      hsize_t(g.n_phi_d), 3};
  const H5::DataSet values = hdf5::WriteDataset(f, "values", H5::PredType::IEEE_F64LE,
                                                H5::PredType::NATIVE_DOUBLE, vdims, t.rgb.data());
  WriteStringAttr(values, "units", "1/sr");
  WriteStringAttr(values, "description",
                  "BRDF f_r without the cosine factor, linear RGB; [theta_h][theta_d][phi_d][RGB]; "
                  "meaningful only where valid == 1");

  const H5::DataSet valid =
      hdf5::WriteDataset(f, "valid", H5::PredType::STD_U8LE, H5::PredType::NATIVE_UINT8,
                         {vdims[0], vdims[1], vdims[2]}, t.valid.data());
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
  hdf5::WriteUint64Attr(prov, "seed", p.seed);
  hdf5::WriteDoubleAttr(prov, "noise", p.noise);
  hdf5::WriteDoubleAttr(prov, "missing_fraction", p.missing_fraction);
}

// ---- reading ----------------------------------------------------------------------------

class Reader : public hdf5::Reader {
 public:
  using hdf5::Reader::Reader;

  Table Read() const {
    const H5::H5File f = Open();
    const std::string format = String(f, "/", "format");
    if (format != kHdf5TableFormat) {
      Fail(fmt::format("format is '{}', expected '{}'", format, kHdf5TableFormat));
    }
    const std::int32_t version = Int32(f, "/", "format_version");
    if (version != kHdf5TableVersion) {
      Fail(fmt::format("format_version {} is not supported (this brdfit reads {})", version,
                       kHdf5TableVersion));
    }

    std::vector<hsize_t> vdims, mdims;
    const H5::DataSet values = Dataset(f, "/", "values", H5T_FLOAT, &vdims);
    const H5::DataSet valid = Dataset(f, "/", "valid", H5T_INTEGER, &mdims);
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
    RequireAllocated(values, "dataset /values");
    RequireAllocated(valid, "dataset /valid");

    Grid g;
    g.n_theta_h = static_cast<int>(vdims[0]);
    g.n_theta_d = static_cast<int>(vdims[1]);
    g.n_phi_d = static_cast<int>(vdims[2]);
    const H5::Group axes = Group(f, "/", "axes");
    const std::string mapping =
        String(AxisDataset(axes, "theta_h", g.n_theta_h), "/axes/theta_h", "mapping");
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
      const std::string m = String(axes.openDataSet(name), std::string("/axes/") + name, "mapping");
      if (m != "linear") Fail(fmt::format("/axes/{} mapping is '{}', expected linear", name, m));
    }

    Table t = Table::Empty(g);
    ReadChecked(values, "dataset /values", H5::PredType::NATIVE_DOUBLE, t.rgb.data());
    ReadChecked(valid, "dataset /valid", H5::PredType::NATIVE_UINT8, t.valid.data());
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

    const std::string pw = "/provenance";
    const H5::Group prov = Group(f, "/", "provenance");
    Provenance& p = t.provenance;
    p.source = String(prov, pw, "source");
    p.generator = String(prov, pw, "generator");
    p.model = String(prov, pw, "model");
    p.parameters_json = String(prov, pw, "parameters");
    // `brdfit info --json` embeds it as JSON; empty when the generator had none.
    if (!p.parameters_json.empty() && !nlohmann::json::accept(p.parameters_json)) {
      Fail("/provenance@parameters is not JSON");
    }
    p.seed = Uint64(prov, pw, "seed");
    p.noise = Double(prov, pw, "noise");
    p.missing_fraction = Double(prov, pw, "missing_fraction");
    return t;
  }

 private:
  H5::DataSet AxisDataset(const H5::Group& axes, const char* name, int n) const {
    std::vector<hsize_t> dims;
    H5::DataSet ds = Dataset(axes, "/axes", name, H5T_FLOAT, &dims);
    if (dims.size() != 1 || dims[0] != static_cast<hsize_t>(n)) {
      Fail(fmt::format("dataset /axes/{} must have {} entries (one per bin)", name, n));
    }
    return ds;
  }

  // The stored centres must be the grid's cell centres (the file's axis definition).
  template <class F>
  void CheckAxis(const H5::Group& axes, const char* name, int n, F angle_at) const {
    std::vector<double> c(n);
    ReadChecked(AxisDataset(axes, name, n), std::string("dataset /axes/") + name,
                H5::PredType::NATIVE_DOUBLE, c.data());
    for (int i = 0; i < n; ++i) {
      const double expected = angle_at(i + 0.5);
      if (!(std::fabs(c[i] - expected) <= 1e-9)) {
        Fail(
            fmt::format("/axes/{}[{}] is {}, expected the bin centre {}", name, i, c[i], expected));
      }
    }
  }
};

}  // namespace

Table ReadHdf5Table(const fs::path& path) {
  try {
    return Reader(path).Read();
  } catch (const H5::Exception& e) {
    throw InputError(path, hdf5::Describe(e));
  }
}

void WriteHdf5Table(const Table& t, const fs::path& path) {
  hdf5::Quiet();
  if (t.rgb.size() != 3 * t.grid.NumCells() || t.valid.size() != t.grid.NumCells()) {
    throw std::invalid_argument("WriteHdf5Table: table arrays do not match its grid");
  }
  // Built in memory, written with every write checked (io/hdf5_util.h).
  hdf5::WriteFileImageAtomically(path, [&](H5::H5File& f) { WriteFile(t, f); });
}

}  // namespace brdfit
