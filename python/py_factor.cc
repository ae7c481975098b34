// brdfit.factor: the homomorphic factorization (factor/factor.h, McCool et al. 2001) of a table,
// options checked as `brdfit factor` checks them (pipeline/factor_settings.h), with the GIL
// released; textures as NumPy arrays, an eval, and the metrics the CLI prints.
#include <pybind11/stl.h>

#include <string>

#include "factor/factor.h"
#include "factor/factor_metrics.h"
#include "io/metrics_json.h"
#include "pipeline/factor_settings.h"
#include "python/bindings.h"

namespace brdfit::python {
namespace {

// The docstring of Factorization.metrics: its keys.
const char* MetricsDoc() {
  static const std::string doc = "ln_ratio_rmse, " + ErrorMetricNames() +
                                 " and rendered (docs/accuracy.md), as `brdfit factor` prints "
                                 "them; empty with metrics=False";
  return doc.c_str();
}

struct PyFactorization {
  Factorization f;
  py::dict metrics;
};

// An (height, width, 3) float32 copy of a texture (row 0 first, core/rgb_image.h).
py::array_t<float> TextureArray(const RgbImage& img) {
  py::array_t<float> a({img.height, img.width, 3});
  std::copy(img.rgb.begin(), img.rgb.end(), a.mutable_data());
  return a;
}

py::dict Stats(const FactorStats& s) {
  py::dict d;
  d["grid_cells"] = s.grid_cells;
  d["valid_cells"] = s.valid_cells;
  d["usable_cells"] = s.usable_cells;
  d["nonpositive_cells"] = s.nonpositive_cells;
  d["used_cells"] = s.used_cells;
  d["clamped_texels"] = s.clamped_texels;
  d["solve_log_rms"] = s.solve_log_rms;
  d["refine_iterations"] = s.refine_iterations;
  d["seconds"] = s.seconds;
  return d;
}

}  // namespace

void BindFactor(py::module_& m) {
  py::class_<PyFactorization>(m, "Factorization",
                              "f = d + sum_k p_k q_k (factor/factor_eval.h, docs/factorization.md)")
      .def_property_readonly("param",
                             [](const PyFactorization& r) { return ToString(r.f.brdf.param()); })
      .def_property_readonly("rank", [](const PyFactorization& r) { return r.f.brdf.rank(); })
      .def_property_readonly("resolution",
                             [](const PyFactorization& r) { return r.f.options.resolution; })
      .def_property_readonly(
          "diffuse", [](const PyFactorization& r) { return r.f.brdf.diffuse(); },
          "the diffuse value d, 1/sr per channel (0 without --diffuse)")
      .def_property_readonly(
          "textures",
          [](const PyFactorization& r) {
            py::list l;
            for (const FactorTerm& t : r.f.brdf.terms())
              l.append(py::make_tuple(TextureArray(t.p), TextureArray(t.q)));
            return l;
          },
          "[(p, q)] per product, (height, width, 3) float32 arrays")
      .def_property_readonly("stats", [](const PyFactorization& r) { return Stats(r.f.stats); })
      .def_readonly("metrics", &PyFactorization::metrics, MetricsDoc())
      .def(
          "eval",
          [](const PyFactorization& r, py::handle wi, py::handle wo) {
            return EvalDirections(
                wi, wo, [&](const Vec3& a, const Vec3& b) { return r.f.brdf.Eval(a, b); });
          },
          py::arg("wi"), py::arg("wo"), "f_r from the float32 textures at (N, 3) directions")
      .def(
          "eval_halfdiff",
          [](const PyFactorization& r, py::handle th, py::handle td, py::handle pd) {
            return EvalHalfDiff(th, td, pd,
                                [&](const HalfDiffAngles& a) { return r.f.brdf.Eval(a); });
          },
          py::arg("theta_h"), py::arg("theta_d"), py::arg("phi_d"));

  m.def(
      "factor",
      [](const Table& table, const std::string& param, int res, bool diffuse, int rank,
         bool refine, const std::string& refine_loss, int refine_iterations, double lambda,
         const std::string& weighting, double max_theta, bool metrics) {
        const FactorOptions o = pipeline::MakeFactorOptions({param, res, lambda, weighting,
                                                             max_theta, diffuse, rank, refine,
                                                             refine_iterations, refine_loss});
        PyFactorization out;
        FitMetrics fm;
        RenderedError re;
        double ln_rmse = 0;
        {
          py::gil_scoped_release nogil;
          out.f = Factor(table, o);
          if (metrics) {
            fm = ScoreFactorization(table, out.f.brdf);
            ln_rmse = FactorLnRatioRmse(table, out.f.brdf, o.max_theta);
            re = ScoreFactorizationRendered(table, out.f.brdf);
          }
        }
        if (metrics) {
          out.metrics["ln_ratio_rmse"] = ln_rmse;
          for (const ErrorMetricField& f : kErrorMetrics) out.metrics[f.name] = fm.*f.value;
          out.metrics["rendered"] =
              py::module_::import("json").attr("loads")(RenderedErrorJson(re).dump());
        }
        return out;
      },
      py::arg("table"), py::arg("param") = "mccool", py::arg("res") = 64,
      py::arg("diffuse") = false, py::arg("rank") = 1, py::arg("refine") = false,
      py::arg("refine_loss") = "rel",
      py::arg("refine_iterations") = pipeline::FactorSettings{}.refine_iterations,
      py::arg("lambda_") = pipeline::FactorSettings{}.lambda, py::arg("weighting") = "solid-angle",
      py::arg("max_theta") = 90.0, py::arg("metrics") = true,
      "Factorizes a table as `brdfit factor --param P --res N ...` (one form; max_theta in "
      "degrees); the GIL is released while it runs");
}

}  // namespace brdfit::python
