// brdfit.Table (NumPy views of a core::Table), brdfit.load (pipeline/inputs.h: files and
// nbrdf:NAME) and Table.save (io/table_io.h).
#include <pybind11/stl.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/table.h"
#include "fit/bin_measure.h"
#include "io/table_io.h"
#include "pipeline/inputs.h"
#include "python/bindings.h"

namespace brdfit::python {
namespace {

std::vector<py::ssize_t> GridShape(const Grid& g) {
  return {g.n_theta_h, g.n_theta_d, g.n_phi_d};
}

// values[i_theta_h, i_theta_d, i_phi_d, channel]: a writable view of the table's storage
// (core/table.h's index layout is exactly C order of this shape).
py::array Values(py::object self) {
  Table& t = self.cast<Table&>();
  std::vector<py::ssize_t> shape = GridShape(t.grid);
  shape.push_back(3);
  return py::array_t<double>(shape, t.rgb.data(), self);
}

// valid[i_theta_h, i_theta_d, i_phi_d] as bool: a view of the 0/1 bytes.
py::array Valid(py::object self) {
  Table& t = self.cast<Table&>();
  return py::array(py::dtype("bool"), GridShape(t.grid), t.valid.data(), self);
}

// Cell-centre angles of one axis (radians; core/table.h: the centre in index coordinates).
template <class F>
py::array_t<double> Axis(int n, F angle_at) {
  py::array_t<double> a(n);
  for (int i = 0; i < n; ++i) a.mutable_data()[i] = angle_at(i + 0.5);
  return a;
}

py::array_t<double> CellMeasures(const Table& t) {
  const Grid& g = t.grid;
  py::array_t<double> a(GridShape(g));
  double* o = a.mutable_data();
  for (int ih = 0; ih < g.n_theta_h; ++ih)
    for (int id = 0; id < g.n_theta_d; ++id)
      for (int ip = 0; ip < g.n_phi_d; ++ip) o[g.Index(ih, id, ip)] = CellMeasure(g, ih, id, ip);
  return a;
}

py::dict ProvenanceDict(const Provenance& p) {
  py::dict d;
  d["source"] = p.source;
  d["generator"] = p.generator;
  d["model"] = p.model;
  d["parameters_json"] = p.parameters_json;
  d["seed"] = p.seed;
  d["noise"] = p.noise;
  d["missing_fraction"] = p.missing_fraction;
  return d;
}

Provenance ProvenanceOf(const py::dict& d) {
  Provenance p;
  for (auto [key, value] : d) {
    const std::string k = py::str(key);
    try {
      if (k == "source") p.source = value.cast<std::string>();
      else if (k == "generator") p.generator = value.cast<std::string>();
      else if (k == "model") p.model = value.cast<std::string>();
      else if (k == "parameters_json") {
        p.parameters_json = value.cast<std::string>();
        // The HDF5 reader refuses a table whose parameters are not JSON: never write one.
        if (!p.parameters_json.empty() && !nlohmann::json::accept(p.parameters_json)) {
          throw InputError("provenance['parameters_json'] is not JSON");
        }
      } else if (k == "seed")
        p.seed = value.cast<std::uint64_t>();
      else if (k == "noise") p.noise = value.cast<double>();
      else if (k == "missing_fraction") p.missing_fraction = value.cast<double>();
      else throw InputError("provenance: unknown key '" + k + "'");
    } catch (const py::cast_error&) {
      throw py::type_error("provenance['" + k + "']: wrong type (seed: int >= 0; noise, "
                           "missing_fraction: float; the others: str)");
    }
  }
  return p;
}

// Table.from_arrays: checked as the HDF5 reader checks a file (io/hdf5_table.cc): the shapes
// agree, and every valid cell holds finite values.
Table FromArrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& values,
                 const py::object& valid_in, const std::string& mapping, const py::dict& prov) {
  if (values.ndim() != 4 || values.shape(3) != 3) {
    throw InputError("values must have shape (n_theta_h, n_theta_d, n_phi_d, 3)");
  }
  for (int k = 0; k < 3; ++k) {
    if (values.shape(k) < 1 || values.shape(k) > 100000) {
      throw InputError("values: every grid axis needs 1 to 100000 bins");
    }
  }
  const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast> valid =
      py::module_::import("numpy").attr("asarray")(valid_in, "bool").attr("astype")("uint8");
  if (valid.ndim() != 3 || valid.shape(0) != values.shape(0) || valid.shape(1) != values.shape(1) ||
      valid.shape(2) != values.shape(2)) {
    throw InputError("valid must have shape values.shape[:3]");
  }
  Grid g;
  g.n_theta_h = static_cast<int>(values.shape(0));
  g.n_theta_d = static_cast<int>(values.shape(1));
  g.n_phi_d = static_cast<int>(values.shape(2));
  g.theta_h_mapping = FromString<ThetaHMapping>(mapping);
  Table t = Table::Empty(g);
  std::copy(values.data(), values.data() + values.size(), t.rgb.begin());
  std::copy(valid.data(), valid.data() + valid.size(), t.valid.begin());
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    if (!t.valid[i]) continue;
    for (int c = 0; c < 3; ++c) {
      // A valid cell holds a BRDF value: finite and >= 0 (the readers of MERL and HDF5 tables
      // hold them to the same); a measurement that is not one is marked invalid, never kept.
      const double v = t.rgb[3 * i + c];
      if (!std::isfinite(v) || v < 0) {
        int ih, id, ip;
        g.Unindex(i, &ih, &id, &ip);
        throw InputError("values[" + std::to_string(ih) + ", " + std::to_string(id) + ", " +
                         std::to_string(ip) + ", " + std::to_string(c) + "] is " +
                         (v < 0 ? "negative" : "not finite") +
                         " in a valid cell (mark the cell invalid)");
      }
    }
  }
  t.provenance = ProvenanceOf(prov);
  if (t.provenance.source.empty()) t.provenance.source = "arrays";
  return t;
}

}  // namespace

void BindTable(py::module_& m) {
  // dynamic_attr: load() records the input it read as `input` (a fit's "source", as the CLI's).
  py::class_<Table>(m, "Table", py::dynamic_attr(),
                    "A tabulated isotropic BRDF on a (theta_h, theta_d, phi_d) grid "
                    "(core/table.h): f_r in 1/sr per linear-RGB channel, no cosine.")
      .def_property_readonly("values", &Values,
                             "(n_theta_h, n_theta_d, n_phi_d, 3) float64 view (writable); "
                             "meaningless where not valid")
      .def_property_readonly("valid", &Valid, "(n_theta_h, n_theta_d, n_phi_d) bool view")
      .def_property_readonly("shape", [](const Table& t) {
        return py::make_tuple(t.grid.n_theta_h, t.grid.n_theta_d, t.grid.n_phi_d);
      })
      .def_property_readonly("theta_h_mapping",
                             [](const Table& t) { return ToString(t.grid.theta_h_mapping); })
      .def_property_readonly("theta_h", [](const Table& t) {
        return Axis(t.grid.n_theta_h, [&](double u) { return t.grid.ThetaHAt(u); });
      }, "cell-centre theta_h of each bin, radians")
      .def_property_readonly("theta_d", [](const Table& t) {
        return Axis(t.grid.n_theta_d, [&](double u) { return t.grid.ThetaDAt(u); });
      }, "cell-centre theta_d of each bin, radians")
      .def_property_readonly("phi_d", [](const Table& t) {
        return Axis(t.grid.n_phi_d, [&](double u) { return t.grid.PhiDAt(u); });
      }, "cell-centre phi_d of each bin, radians")
      .def_property_readonly("cell_measure", &CellMeasures,
                             "measure of each cell in (wi, wo) space, sr^2 (fit/bin_measure.h)")
      .def_property_readonly("provenance", [](const Table& t) { return ProvenanceDict(t.provenance); })
      .def_property_readonly("num_valid", &Table::CountValid)
      .def_static("from_arrays", &FromArrays, py::arg("values"), py::arg("valid"),
                  py::arg("theta_h_mapping") = "sqrt", py::arg("provenance") = py::dict(),
                  "A table from arrays shaped as Table.values and Table.valid (copied)")
      .def("save",
           [](const Table& t, const std::string& path) {
             py::gil_scoped_release nogil;
             SaveTable(t, path);
           },
           py::arg("path"), "Writes .h5 (brdfit HDF5 table) or .binary (MERL grid only), atomically")
      .def("copy", [](const Table& t) { return Table(t); })
      .def("__eq__", [](const Table& a, const Table& b) { return a == b; })
      .def("__repr__", [](const Table& t) {
        return "<brdfit.Table " + std::to_string(t.grid.n_theta_h) + "x" +
               std::to_string(t.grid.n_theta_d) + "x" + std::to_string(t.grid.n_phi_d) + " " +
               ToString(t.grid.theta_h_mapping) + ", " + std::to_string(t.CountValid()) +
               " valid, source '" + t.provenance.source + "'>";
      });
  m.def(
      "load",
      [](const std::string& input) {
        Table t;
        {
          py::gil_scoped_release nogil;
          t = pipeline::LoadInput(input);
        }
        py::object o = py::cast(std::move(t));
        o.attr("input") = input;
        return o;
      },
      py::arg("input"),
      "Loads a MERL .binary or brdfit .h5 table, or tabulates an RGL .bsdf file or nbrdf:NAME "
      "on the MERL grid");
}

}  // namespace brdfit::python
