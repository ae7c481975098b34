// brdfit.models() / brdfit.model(name): the registry (models/registry.h) with parameter specs
// and vectorized evaluation; brdfit.synth (core/synth.h, as `brdfit synth --model`).
#include <fmt/core.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/model_params.h"
#include "core/synth.h"
#include "python/bindings.h"

namespace brdfit::python {

std::vector<double> ParamsOfChecked(const ModelInfo& model, py::handle params);

std::vector<double> ParamsOf(const ModelInfo& model, py::handle params) {
  try {
    return ParamsOfChecked(model, params);
  } catch (const py::cast_error&) {
    throw py::type_error("params of " + model.name +
                         ": expected a dict {name: number} or a sequence of numbers");
  }
}

std::vector<double> ParamsOfChecked(const ModelInfo& model, py::handle params) {
  std::vector<double> p = model.DefaultParams();
  if (params.is_none()) {
  } else if (py::isinstance<py::dict>(params)) {
    std::vector<bool> given(p.size(), false);
    for (auto [key, value] : params.cast<py::dict>()) {
      const std::string name = py::str(key);
      const std::size_t i = FindParamIndex(model, name);
      if (given[i]) throw InputError("parameter " + model.param_names[i] + " given twice");
      given[i] = true;
      p[i] = value.cast<double>();
    }
  } else {
    p = params.cast<std::vector<double>>();
  }
  const std::string why = CheckModelParams(model.name, p);
  if (!why.empty()) throw InputError(why);
  return p;
}

std::vector<Vec3> DirectionsOf(const Array& a, const char* what) {
  if (!a) throw InputError(std::string(what) + " must be an array of numbers");
  if (!((a.ndim() == 2 && a.shape(1) == 3) || (a.ndim() == 1 && a.shape(0) == 3))) {
    throw InputError(std::string(what) + " must have shape (N, 3) or (3,)");
  }
  const std::size_t n = a.ndim() == 2 ? static_cast<std::size_t>(a.shape(0)) : 1;
  std::vector<Vec3> out(n);
  const double* d = a.data();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 v{d[3 * k], d[3 * k + 1], d[3 * k + 2]};
    const double len = std::sqrt(Dot(v, v));
    if (!std::isfinite(len) || !(len > 0)) {
      throw InputError(std::string(what) + "[" + std::to_string(k) +
                       "] is not a finite non-zero vector");
    }
    out[k] = (1.0 / len) * v;
  }
  return out;
}

namespace {

const ModelInfo& Model(const std::string& name) {
  const ModelInfo* m = FindModel(name);
  if (!m) throw InputError("unknown model '" + name + "'; known models: " + ModelNames());
  return *m;
}

std::array<double, 3> EvalAt(const ModelInfo& m, const std::vector<double>& p, const Geometry& g) {
  std::array<double, 3> rgb{0, 0, 0};
  if (g.cos_i <= 0 || g.cos_o <= 0) return rgb;  // the models' domain (models/param.h)
  m.eval(p.data(), g, rgb.data());
  return rgb;
}

py::dict SpecDict(const ModelInfo& m, std::size_t i) {
  const ParamSpec& s = m.params[i];
  py::dict d;
  d["name"] = m.param_names[i];
  d["short_name"] = std::string(s.name);
  d["unit"] = std::string(s.unit);
  d["lower"] = s.lower;
  d["upper"] = s.upper;
  d["default"] = s.init;
  d["log_scale"] = s.log_scale;
  d["doc"] = std::string(s.doc);
  return d;
}

}  // namespace

void BindModels(py::module_& m) {
  py::class_<ModelInfo>(m, "Model", "A registered analytic BRDF (models/registry.h)")
      .def_readonly("name", &ModelInfo::name)
      .def_readonly("doc", &ModelInfo::doc)
      .def_readonly("energy_conserving", &ModelInfo::energy_conserving)
      .def_readonly("param_names", &ModelInfo::param_names, "qualified: 'ggx.alpha'")
      .def_property_readonly("params",
                             [](const ModelInfo& mi) {
                               py::list l;
                               for (std::size_t i = 0; i < mi.params.size(); ++i) l.append(SpecDict(mi, i));
                               return l;
                             },
                             "parameter specs: name, unit, lower, upper, default, log_scale, doc")
      .def_property_readonly("defaults",
                             [](const ModelInfo& mi) {
                               py::dict d;
                               for (std::size_t i = 0; i < mi.params.size(); ++i)
                                 d[py::str(mi.param_names[i])] = mi.params[i].init;
                               return d;
                             })
      .def("eval",
           [](const ModelInfo& mi, py::handle params, py::handle wi, py::handle wo) {
             const std::vector<double> p = ParamsOf(mi, params);
             return EvalDirections(wi, wo, [&](const Vec3& a, const Vec3& b) {
               return EvalAt(mi, p, MakeGeometry(a, b));
             });
           },
           py::arg("params"), py::arg("wi"), py::arg("wo"),
           "f_r (1/sr, no cosine) at unit directions (local frame, z = normal) given as (N, 3) "
           "or (3,) arrays: an (N, 3) array; 0 where a direction is at or below the horizon")
      .def("eval_halfdiff",
           [](const ModelInfo& mi, py::handle params, py::handle th, py::handle td, py::handle pd) {
             const std::vector<double> p = ParamsOf(mi, params);
             return EvalHalfDiff(th, td, pd, [&](const HalfDiffAngles& a) {
               return EvalAt(mi, p, MakeGeometry(a));
             });
           },
           py::arg("params"), py::arg("theta_h"), py::arg("theta_d"), py::arg("phi_d"),
           "f_r at Rusinkiewicz angles (radians, broadcast as NumPy does), phi_h = 0")
      .def("__repr__", [](const ModelInfo& mi) { return "<brdfit.Model " + mi.name + ">"; });

  m.def(
      "models",
      [] {
        std::vector<const ModelInfo*> out;
        for (const ModelInfo& mi : AllModels()) out.push_back(&mi);
        return out;
      },
      py::return_value_policy::reference, "Every registered model, in catalog order");
  m.def("model", &Model, py::arg("name"), py::return_value_policy::reference,
        "The registered model of that name");
  m.def(
      "synth",
      [](const std::string& model, py::handle params, std::array<int, 3> grid,
         const std::string& mapping, double noise, double missing, std::uint64_t seed) {
        const ModelInfo& mi = Model(model);
        const std::vector<double> p = ParamsOf(mi, params);
        for (int n : grid) {
          if (n < 1 || n > 100000) throw InputError("grid: every axis needs 1 to 100000 bins");
        }
        Grid g;
        g.n_theta_h = grid[0];
        g.n_theta_d = grid[1];
        g.n_phi_d = grid[2];
        g.theta_h_mapping = FromString<ThetaHMapping>(mapping);
        // The checks and messages of `brdfit synth` (cli/cmd_synth.cc).
        if (!(noise >= 0 && noise <= 10)) {
          throw InputError(fmt::format("--noise {}: expected a sigma in [0, 10] (log-normal)", noise));
        }
        if (!(missing >= 0 && missing <= 1)) {
          throw InputError(fmt::format("--missing {}: expected a fraction in [0, 1]", missing));
        }
        SynthOptions so;
        so.noise = noise;
        so.missing_fraction = missing;
        so.seed = seed;
        Table t;
        {
          py::gil_scoped_release nogil;
          t = SynthesizeTable(
              g, [&](const Geometry& geo, double rgb[3]) { mi.eval(p.data(), geo, rgb); }, so);
        }
        // As `brdfit synth --model` (cli/cmd_synth.cc): the model and its parameters.
        t.provenance.model = mi.name;
        t.provenance.parameters_json = ParamsToJson(mi, p);
        return t;
      },
      py::arg("model"), py::arg("params") = py::none(),
      py::arg("grid") = std::array<int, 3>{90, 90, 180}, py::arg("theta_h_mapping") = "sqrt",
      py::arg("noise") = 0.0, py::arg("missing") = 0.0, py::arg("seed") = 0,
      "A synthetic table of a model at the cell centres, as `brdfit synth --model`");
}

}  // namespace brdfit::python
