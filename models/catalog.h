// The list of every registered model, as types. The registry (models/registry.h) and the
// fitter's static dispatch (fit/) both iterate this one list, so a model added here is
// available to `brdfit models`, `synth`, `fit` and the preview at once.
#pragma once

#include <string>
#include <tuple>

#include "models/ggx.h"
#include "models/lambert.h"
#include "models/sum.h"

namespace brdfit {

// Registry name of a model type: kName for single models, "a+b" for sums.
template <class M>
std::string ModelName() {
  if constexpr (requires { M::Name(); }) {
    return M::Name();
  } else {
    return std::string(M::kName);
  }
}

using ModelCatalog = std::tuple<Lambert, Ggx, Sum<Lambert, Ggx>>;

// Calls f(std::type_identity<M>{}) for every model type M in the catalog.
template <class F>
void ForEachModel(F&& f) {
  std::apply([&](auto... m) { (f(std::type_identity<decltype(m)>{}), ...); }, ModelCatalog{});
}

}  // namespace brdfit
