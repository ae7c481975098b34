// brdfit.fit: one model fitted to one table as `brdfit fit` fits it (the same option parsing,
// pipeline/fit_settings.h; the same PrepareTable + FitPrepared as pipeline/batch_fit.cc; the
// same entry and JSON writer, io/fit_report.h FitParamsJson), with the GIL released.
#include <pybind11/stl.h>

#include <chrono>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/input_name.h"
#include "core/provenance.h"
#include "fit/fitter.h"
#include "io/fit_report.h"
#include "pipeline/batch_fit.h"
#include "pipeline/fit_settings.h"
#include "python/bindings.h"

namespace brdfit::python {
namespace {

// One fit: the report entry `brdfit fit` would write, and its parameters JSON.
struct PyFitResult {
  FitReportEntry entry;
  std::string json;  // FitParamsJson({entry}): what `brdfit fit --json` writes for this fit
};

py::object ParsedFit(const PyFitResult& r) {
  const py::object parsed = py::module_::import("json").attr("loads")(r.json);
  return parsed["fits"][py::int_(0)];
}

// One field of it (an object, never an accessor into a temporary).
py::object ParsedField(const PyFitResult& r, const char* key) {
  const py::object fit = ParsedFit(r);
  return fit[key];
}

PyFitResult Fit(const Table& table, const std::string& source, const std::string& model, const std::string& diffuse,
                const pipeline::FitSettings& settings) {
  pipeline::BatchFitRequest req;  // only its samples and fit options are used
  pipeline::ApplyFitSettings(settings, &req.samples, &req.fit);
  const std::vector<pipeline::ModelRun> runs =
      pipeline::ResolveModelRuns({model}, diffuse, !settings.loss.empty());
  if (runs.size() != 1) {
    throw InputError("model '" + model + "' is " + std::to_string(runs.size()) +
                     " fits; brdfit.fit fits one model (call it once per candidate)");
  }
  if (runs[0].kind == pipeline::TaskKind::kFactor) {
    throw InputError("brdfit.fit fits analytic models; a factorization is brdfit.factor(...)");
  }
  FitOptions fo = req.fit;
  if (runs[0].loss) fo.loss = *runs[0].loss;
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  PyFitResult out;
  {
    py::gil_scoped_release nogil;
    const auto t0 = Clock::now();
    const PreparedTable prepared = PrepareTable(table, req.samples, req.fit);
    const double prepare_ms = ms(t0);
    FitResult r = FitPrepared(runs[0].model, prepared, fo);
    r.times.prepare = prepare_ms;
    out.entry = {source,
                 MaterialName(source),
                 OptionsJson(req.samples, fo),
                 std::move(r),
                 false,
                 {},
                 TableContentHash(table),
                 false,
                 std::nullopt};
    std::vector<FitReportEntry> one{out.entry};
    pipeline::MarkChosenFits(one);  // as the CLI marks the fits of a report before writing
    out.entry = one[0];
    out.json = FitParamsJson(one);
  }
  return out;
}

py::dict Timings(const FitTimes& t) {
  py::dict d;
  for (const FitTimeField& f : kFitTimeFields) d[f.name] = t.*f.value;
  return d;
}

}  // namespace

void BindFit(py::module_& m) {
  py::class_<PyFitResult>(m, "FitResult",
                          "One fit, as `brdfit fit` writes it (io/fit_report.h FitParamsJson)")
      .def_property_readonly("model", [](const PyFitResult& r) { return r.entry.result.model; })
      .def_property_readonly("source", [](const PyFitResult& r) { return r.entry.source; })
      .def_property_readonly("material", [](const PyFitResult& r) { return r.entry.material; })
      .def_property_readonly("status",
                             [](const PyFitResult& r) { return ToString(r.entry.result.status); })
      .def_property_readonly("message", [](const PyFitResult& r) { return r.entry.result.message; })
      .def_property_readonly("param_names",
                             [](const PyFitResult& r) { return r.entry.result.param_names; })
      .def_property_readonly("params",
                             [](const PyFitResult& r) {
                               py::dict d;
                               const FitResult& f = r.entry.result;
                               for (std::size_t i = 0; i < f.params.size(); ++i)
                                 d[py::str(f.param_names[i])] = f.params[i];
                               return d;
                             },
                             "{qualified name: value} in parameter order")
      .def_property_readonly("metrics", [](const PyFitResult& r) { return ParsedField(r, "metrics"); },
                             "the \"metrics\" object of the CLI's JSON")
      .def_property_readonly("options", [](const PyFitResult& r) { return ParsedField(r, "options"); })
      .def_property_readonly("iterations", [](const PyFitResult& r) { return r.entry.result.iterations; })
      .def_property_readonly("timings", [](const PyFitResult& r) { return Timings(r.entry.result.times); },
                             "milliseconds; load_ms is 0 (the table was in memory)")
      .def_property_readonly("json", [](const PyFitResult& r) { return r.json; },
                             "the text `brdfit fit --json` writes for this one fit")
      .def("as_dict", &ParsedFit, "the fit's object of the CLI's JSON")
      .def("eval",
           [](const PyFitResult& r, py::handle wi, py::handle wo) {
             const ModelInfo* mi = FindModel(r.entry.result.model);
             if (!mi) throw InputError("unknown model '" + r.entry.result.model + "'");
             return py::cast(mi, py::return_value_policy::reference)
                 .attr("eval")(py::cast(r.entry.result.params), wi, wo);
           },
           py::arg("wi"), py::arg("wo"), "the fitted model at (N, 3) directions (Model.eval)")
      .def("__repr__", [](const PyFitResult& r) {
        return "<brdfit.FitResult " + r.entry.material + " " + r.entry.result.model + " " +
               ToString(r.entry.result.status) + ">";
      });

  m.def(
      "fit",
      [](const py::object& table_obj, const std::string& model, const std::optional<std::string>& loss,
         const std::string& budget, const std::string& diffuse, bool cosine,
         const std::string& robust, double robust_scale, double cutoff,
         const std::string& weighting, std::uint64_t seed, int multistart, int max_iterations,
         int threads, const std::string& polish) {
        pipeline::FitSettings s;
        s.polish = polish;
        s.loss = loss.value_or("");
        s.budget = budget;
        s.no_cosine = !cosine;
        s.robust = robust;
        s.robust_scale = robust_scale;
        s.cutoff = cutoff;
        s.weighting = weighting;
        s.seed = seed;
        s.multistart = multistart;
        s.max_iterations = max_iterations;
        s.threads = threads;
        // The entry's source, as `brdfit fit INPUT` records INPUT: the input load() read, else
        // the table's provenance (synthetic tables, arrays).
        const Table& table = table_obj.cast<const Table&>();
        const py::object input = py::getattr(table_obj, "input", py::none());
        const std::string source =
            input.is_none() ? table.provenance.source : input.cast<std::string>();
        return Fit(table, source, model, diffuse, s);
      },
      py::arg("table"), py::arg("model") = "lambert+ggx", py::arg("loss") = py::none(),
      py::arg("budget") = pipeline::FitSettings{}.budget, py::arg("diffuse") = "lambert", py::arg("cosine") = true,
      py::arg("robust") = "none", py::arg("robust_scale") = pipeline::FitSettings{}.robust_scale,
      py::arg("cutoff") = pipeline::FitSettings{}.cutoff, py::arg("weighting") = "bin-measure",
      py::arg("seed") = 1, py::arg("multistart") = 1,
      py::arg("max_iterations") = pipeline::FitSettings{}.max_iterations, py::arg("threads") = 1,
      py::arg("polish") = pipeline::FitSettings{}.polish,
      "Fits one model as `brdfit fit TABLE --model MODEL ...` does (same defaults: loss rel, "
      "diffuse lambert, budget stride:32, polish rendered); the GIL is released while it runs");
}

}  // namespace brdfit::python
