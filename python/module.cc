// `import brdfit` (docs/python.md): tables, models, fits and factorizations of the C++ library
// as Python objects with NumPy arrays. A thin layer: every call goes to pipeline/ or below.
#include <pybind11/pybind11.h>

#include "core/error.h"
#include "python/bindings.h"

namespace py = pybind11;

PYBIND11_MODULE(brdfit, m) {
  m.doc() = "brdfit: fit analytic BRDF models to tabulated measurements (docs/python.md)";
  m.attr("__version__") = BRDFIT_VERSION;  // the CMake project version, as `brdfit --version`
  // Bad input (a file, an option, an array): the message the CLI prints after "brdfit: error:".
  py::register_exception<brdfit::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<brdfit::OutputError>(m, "OutputError", PyExc_OSError);
  brdfit::python::BindTable(m);
  brdfit::python::BindModels(m);
  brdfit::python::BindFit(m);
  brdfit::python::BindFactor(m);
}
