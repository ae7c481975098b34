// The parts of the `brdfit` Python module (docs/python.md), one file each; module.cc calls them
// in this order. Errors cross as Python exceptions with the CLI's messages: InputError ->
// brdfit.InputError (a ValueError), OutputError -> brdfit.OutputError (an OSError).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "models/registry.h"

namespace brdfit::python {

namespace py = pybind11;

void BindTable(py::module_& m);     // python/py_table.cc: Table, load, save
void BindModels(py::module_& m);    // python/py_models.cc: models(), Model.eval, synth
void BindFit(py::module_& m);       // python/py_fit.cc: fit, FitResult
void BindFactor(py::module_& m);    // python/py_factor.cc: factor, Factorization

// A model's parameter vector from a dict {name: value} (qualified or unambiguous unqualified
// names, the rest at their defaults) or a sequence of every value in order; checked as the
// readers check parameters (core/model_params.h CheckModelParams). Throws InputError.
std::vector<double> ParamsOf(const ModelInfo& model, py::handle params);

// Unit directions from an (N, 3) or (3,) array; rows of zero length or non-finite entries are
// refused (InputError naming `what` and the row).
std::vector<Vec3> DirectionsOf(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                               const char* what);

// Evaluates f(wi, wo) -> rgb for directions broadcast between (N, 3) and (3,): an (N, 3) array.
// Pairs with a direction at or below the horizon (z <= 0) give 0.
template <class F>
py::array_t<double> EvalDirections(py::handle wi_in, py::handle wo_in, F&& f);

// Evaluates f(HalfDiffAngles) -> rgb over theta_h, theta_d, phi_d broadcast as NumPy does:
// an array of the broadcast shape + (3,).
template <class F>
py::array_t<double> EvalHalfDiff(py::handle theta_h, py::handle theta_d, py::handle phi_d, F&& f);

}  // namespace brdfit::python

#include "python/bindings_eval.h"
