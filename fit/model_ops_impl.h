// Per-model template glue: included only by fit/problem_instances_*.cc.
#pragma once

#include <tuple>
#include <utility>

#include "fit/block_cost.h"
#include "fit/lafortune_gradient.h"
#include "fit/model_ops.h"
#include "fit/pixel_cost.h"
#include "fit/sample_geometry.h"
#include "models/catalog.h"
#include "models/registry.h"
#include "models/sum.h"

namespace brdfit::internal {

template <class M>
ceres::CostFunction* MakeBlock(const Samples& s, const LossData& l, const ParamLayout& layout,
                               const ceres::LossFunction* robust, std::size_t begin,
                               std::size_t end) {
  return new BlockCost<M>(s, l, layout, robust, begin, end);
}

template <class M>
ceres::CostFunction* MakePixelBlock(const PolishPixels& px, const ParamLayout& layout,
                                    std::size_t begin, std::size_t end) {
  return new PixelCost<M>(px, layout, begin, end);
}

template <class M>
void EvalDouble(const double* p, const Geometry& g, double rgb[3]) {
  M::Eval(p, g, rgb);
}

template <class M>
void EvalSamples(const double* p, const Samples& samples, std::size_t begin, std::size_t end,
                 double* rgb) {
  ForEachSampleGeometry(samples, begin, end, [&](std::size_t s, const Geometry& g) {
    M::Eval(p, g, rgb + 3 * (s - begin));
  });
}

// A component's basis column (fit/grid_init.h): M::Eval at each geometry.
template <class M>
void EvalColumn(const double* p, const Geometry* g, std::size_t n, double* rgb,
                std::size_t stride) {
  for (std::size_t s = 0; s < n; ++s) M::Eval(p, g[s], rgb + s * stride);
}
// Lafortune's: the same values with what depends on cxy and n alone computed once per column
// (fit/lafortune_gradient.h).
template <>
inline void EvalColumn<Lafortune>(const double* p, const Geometry* g, std::size_t n, double* rgb,
                                  std::size_t stride) {
  LafortuneColumn(p, g, n, rgb, stride);
}

// The lobes of a sum, each with its own evaluator and parameter slice; a model that is not a
// sum is one component.
template <class M>
struct ComponentsOf {
  static std::vector<ComponentOps> Get() {
    return {{&EvalDouble<M>, 0, kNumParams<M>, &EvalColumn<M>}};
  }
};
template <class... Lobes>
struct ComponentsOf<Sum<Lobes...>> {
  static std::vector<ComponentOps> Get() {
    std::vector<ComponentOps> out;
    std::size_t i = 0;
    ((out.push_back(
          {&EvalDouble<Lobes>, Sum<Lobes...>::kOffsets[i], kNumParams<Lobes>, &EvalColumn<Lobes>}),
      ++i),
     ...);
    return out;
  }
};

// Registers the catalog models whose index is Shard modulo kShards.
template <std::size_t Shard>
void RegisterShard(std::vector<ModelOps>& out) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          if constexpr (I % kShards == Shard) {
            using M = std::tuple_element_t<I, ModelCatalog>;
            const ModelInfo info = MakeModelInfo<M>();
            out.push_back({I, info.name, info.param_names, ParamLayout::Of(M::kParams),
                           &EvalDouble<M>, ComponentsOf<M>::Get(), &MakeBlock<M>,
                           &MakePixelBlock<M>, &EvalSamples<M>});
          }
        }(),
        ...);
  }
  (std::make_index_sequence<std::tuple_size_v<ModelCatalog>>{});
}

}  // namespace brdfit::internal
