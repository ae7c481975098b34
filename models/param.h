// Parameter tables: every model publishes its parameters with names, units, bounds and
// defaults, so the fitter, the CLI (`brdfit models`), the synthesizer and the GLSL twins all
// read one source of truth.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <tuple>

namespace brdfit {

// How a parameter enters the model. kWeightR/G/B: the model's value in that channel is LINEAR in
// the parameter and it has no constant term (colour weights of lobes). The fitter uses this to
// solve weights by linear least squares at fixed shape parameters (variable projection
// initialization). Everything else is kShape.
enum class ParamRole { kShape, kWeightR, kWeightG, kWeightB };

struct ParamSpec {
  std::string_view name;  // e.g. "kd_r", "alpha"
  std::string_view unit;  // "1" (dimensionless), "1/sr", "rad", ...
  double lower;           // bounds the fitter enforces
  double upper;
  double init;            // default / initial value
  bool log_scale;         // optimize log(value) (strictly positive parameters such as alpha)
  std::string_view doc;   // one line for `brdfit models`
  ParamRole role = ParamRole::kShape;
};

// A model M is a stateless type with
//   static constexpr std::string_view kName;
//   static constexpr std::array<ParamSpec, N> kParams;
//   template <class T> static void Eval(const T* params, const Geometry& g, T rgb[3]);
// Eval returns f_r in 1/sr per linear-RGB channel, WITHOUT the cosine factor. It must be
// finite (and have finite derivatives) for every parameter vector inside the bounds and every
// geometry with cos_i > 0 and cos_o > 0.
template <class M>
inline constexpr std::size_t kNumParams = std::tuple_size_v<decltype(M::kParams)>;

}  // namespace brdfit
