// Vectorized evaluation helpers of python/bindings.h (templates: any f of directions or angles).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "core/error.h"
#include "models/geometry.h"

namespace brdfit::python {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <class F>
py::array_t<double> EvalDirections(py::handle wi_in, py::handle wo_in, F&& f) {
  const std::vector<Vec3> wi = DirectionsOf(Array::ensure(wi_in), "wi");
  const std::vector<Vec3> wo = DirectionsOf(Array::ensure(wo_in), "wo");
  if (wi.size() != wo.size() && wi.size() != 1 && wo.size() != 1) {
    throw InputError("wi has " + std::to_string(wi.size()) + " directions and wo " +
                     std::to_string(wo.size()) + " (expected the same number, or one)");
  }
  const std::size_t n = std::max(wi.size(), wo.size());
  py::array_t<double> out({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(3)});
  double* o = out.mutable_data();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = wi[wi.size() == 1 ? 0 : k];
    const Vec3& b = wo[wo.size() == 1 ? 0 : k];
    if (a.z <= 0 || b.z <= 0) {
      o[3 * k] = o[3 * k + 1] = o[3 * k + 2] = 0;
      continue;
    }
    const std::array<double, 3> v = f(a, b);
    for (int c = 0; c < 3; ++c) o[3 * k + c] = v[c];
  }
  return out;
}

template <class F>
py::array_t<double> EvalHalfDiff(py::handle theta_h, py::handle theta_d, py::handle phi_d, F&& f) {
  const py::module_ np = py::module_::import("numpy");
  const py::tuple b = np.attr("broadcast_arrays")(np.attr("asarray")(theta_h, "float64"),
                                                 np.attr("asarray")(theta_d, "float64"),
                                                 np.attr("asarray")(phi_d, "float64"));
  const Array th = np.attr("ascontiguousarray")(b[0]);
  const Array td = np.attr("ascontiguousarray")(b[1]);
  const Array pd = np.attr("ascontiguousarray")(b[2]);
  std::vector<py::ssize_t> shape(th.shape(), th.shape() + th.ndim());
  shape.push_back(3);
  py::array_t<double> out(shape);
  double* o = out.mutable_data();
  const py::ssize_t n = th.size();
  for (py::ssize_t k = 0; k < n; ++k) {
    const HalfDiffAngles a{th.data()[k], td.data()[k], pd.data()[k]};
    if (!std::isfinite(a.theta_h) || !std::isfinite(a.theta_d) || !std::isfinite(a.phi_d)) {
      throw InputError("angle " + std::to_string(k) + " is not finite");
    }
    const std::array<double, 3> v = f(a);
    for (int c = 0; c < 3; ++c) o[3 * k + c] = v[c];
  }
  return out;
}

}  // namespace brdfit::python
