// The list of every registered model, as types. The registry (models/registry.h) and the
// fitter's static dispatch (fit/) both iterate this one list, so a model added here is
// available to `brdfit models`, `synth`, `fit` and the preview at once.
//
// The catalog holds what users fit or render: every single model and Lambert plus each
// specular lobe, two-lobe GGX and two/three-lobe Lafortune. Each entry costs one Ceres autodiff
// instantiation in fit/, so variants that reproduce tutorials (Schlick-k choices, legacy
// normalizations, anisotropic Ward, ...) are types outside the catalog, tested in
// tests/models/tutorial_variants.h (docs/models.md).
#pragma once

#include <string>
#include <tuple>
#include <type_traits>

#include "models/abc.h"
#include "models/beckmann.h"
#include "models/blinn_phong.h"
#include "models/burley.h"
#include "models/cook_torrance.h"
#include "models/ggx.h"
#include "models/lafortune.h"
#include "models/lambert.h"
#include "models/oren_nayar.h"
#include "models/phong.h"
#include "models/sgd.h"
#include "models/sheen.h"
#include "models/sum.h"
#include "models/ue4.h"
#include "models/ward.h"

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

using ModelCatalog = std::tuple<
    // single lobes
    Lambert, OrenNayar, Burley, Phong, BlinnPhong, Ward, WardDuer, Beckmann, Ggx, GgxHc,
    CookTorrance, Lafortune, Ue4,
    // diffuse + specular
    Sum<Lambert, Phong>, Sum<Lambert, BlinnPhong>, Sum<Lambert, Ward>, Sum<Lambert, Beckmann>,
    Sum<Lambert, Ggx>, Sum<Lambert, CookTorrance>, Sum<Lambert, Lafortune>,
    // multi-lobe
    Sum<Lambert, Ggx, Ggx>, Sum<Lambert, Lafortune, Lafortune>,
    Sum<Lambert, Lafortune, Lafortune, Lafortune>,
    // added after the first release: appended, so that the earlier entries keep their index
    // (and their fit/problem_instances_*.cc shard)
    GgxF0, Sum<Lambert, GgxF0>, Sum<Lambert, GgxHc>, Abc, Sum<Lambert, Abc>, Sgd, Sum<Lambert, Sgd>,
    // rough diffuse bodies under a GGX lobe: for fabrics and matte paints, whose grazing
    // brightening Lambert cannot hold (docs/accuracy.md)
    Sum<OrenNayar, Ggx>, Sum<Burley, Ggx>,
    // a sheen lobe for cloth: the grazing highlight of fibres (docs/accuracy.md)
    Sheen, Sum<Lambert, Sheen>, Sum<Lambert, Ggx, Sheen>, Sum<Burley, Ggx, Sheen>,
    // the rough bodies Blender Cycles evaluates (Diffuse BSDF, Principled diffuse), so that a
    // rough body under a GGX lobe exports to Blender exactly (docs/exports.md)
    OrenNayarFujii, Burley2012, Sum<OrenNayarFujii, Ggx>, Sum<Burley2012, Ggx>>;

// Calls f(std::type_identity<M>{}) for every model type M in the catalog.
template <class F>
void ForEachModel(F&& f) {
  std::apply([&](auto... m) { (f(std::type_identity<decltype(m)>{}), ...); }, ModelCatalog{});
}

}  // namespace brdfit
