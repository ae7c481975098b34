// Composite models: a sum of lobes, each with its own RGB weights and shape parameters.
// Sum<Lambert, Ggx> is "lambert+ggx"; parameters are the lobes' parameters concatenated.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "models/geometry.h"
#include "models/param.h"

namespace brdfit {

namespace detail {
template <std::size_t N, std::size_t M>
constexpr std::array<ParamSpec, N + M> Concat(const std::array<ParamSpec, N>& a,
                                              const std::array<ParamSpec, M>& b) {
  std::array<ParamSpec, N + M> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = a[i];
  for (std::size_t i = 0; i < M; ++i) out[N + i] = b[i];
  return out;
}
template <class... Lobes>
constexpr auto ConcatParams() {
  if constexpr (sizeof...(Lobes) == 0) {
    return std::array<ParamSpec, 0>{};
  } else {
    return []<class First, class... Rest>(std::type_identity<First>, std::type_identity<Rest>...) {
      return Concat(First::kParams, ConcatParams<Rest...>());
    }(std::type_identity<Lobes>{}...);
  }
}
}  // namespace detail

namespace detail {
template <class L>
constexpr bool LobeHasWeights() {
  if constexpr (requires { L::kHasWeights; }) {
    return L::kHasWeights;
  } else {
    return true;
  }
}
}  // namespace detail

template <class... Lobes>
struct Sum {
  // A lobe without linear weights (ggx-f0) is a constant term of the sum, so the sum's other
  // weights are not linear without a constant term (models/param.h ParamRole): all its
  // parameters are then shape parameters, as in the weightless lobe.
  static constexpr std::array<ParamSpec, (kNumParams<Lobes> + ...)> kParams = [] {
    auto params = detail::ConcatParams<Lobes...>();
    if (!(detail::LobeHasWeights<Lobes>() && ...)) {
      for (auto& p : params) p.role = ParamRole::kShape;
    }
    return params;
  }();
  static constexpr std::size_t kNumLobes = sizeof...(Lobes);
  // Offset of each lobe's parameters in the concatenated vector.
  static constexpr std::array<std::size_t, sizeof...(Lobes)> kOffsets = [] {
    std::array<std::size_t, sizeof...(Lobes)> off{};
    std::size_t i = 0, acc = 0;
    ((off[i++] = acc, acc += kNumParams<Lobes>), ...);
    return off;
  }();

  // A sum conserves energy when every lobe does and the lobes' weights sum to <= 1 per channel.
  // A lobe whose albedo is not scaled by linear weights (kHasWeights false: ggx-f0, whose
  // albedo reaches ~1 whatever its parameters) leaves nothing for the other lobes, so a sum
  // with it makes no such claim.
  static constexpr bool kEnergyConserving =
      (Lobes::kEnergyConserving && ...) && (detail::LobeHasWeights<Lobes>() && ...);

  // Registry-style name, e.g. "lambert+ggx".
  static std::string Name() {
    std::string n;
    ((n += (n.empty() ? "" : "+"), n += std::string(Lobes::kName)), ...);
    return n;
  }
  // One-line description (each lobe is documented under its own name).
  static std::string Doc() {
    std::string d;
    ((d += (d.empty() ? "" : " + "), d += std::string(Lobes::kName)), ...);
    return "sum of lobes " + d + ", each with its own RGB weights";
  }

  // Parameter names qualified by lobe: "lambert.kd_r", "ggx.alpha"; a repeated lobe gets an
  // index ("ggx1.alpha", "ggx2.alpha").
  static std::vector<std::string> QualifiedParamNames() {
    std::vector<std::string> lobe_names = {std::string(Lobes::kName)...};
    std::vector<std::string> out;
    std::size_t li = 0;
    (
        [&] {
          std::string prefix = lobe_names[li];
          int count = 0, index = 0;
          for (std::size_t k = 0; k < lobe_names.size(); ++k) {
            if (lobe_names[k] == lobe_names[li]) {
              ++count;
              if (k <= li) ++index;
            }
          }
          if (count > 1) prefix += std::to_string(index);
          for (const auto& p : Lobes::kParams) out.push_back(prefix + "." + std::string(p.name));
          ++li;
        }(),
        ...);
    return out;
  }

  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    rgb[0] = rgb[1] = rgb[2] = T(0.0);
    std::size_t li = 0;
    (
        [&] {
          T lobe[3];
          Lobes::Eval(p + kOffsets[li++], g, lobe);
          for (int c = 0; c < 3; ++c) rgb[c] += lobe[c];
        }(),
        ...);
  }
};

}  // namespace brdfit
