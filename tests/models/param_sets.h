// Parameter-vector sets for the per-model tests (oracles, white furnace).
#pragma once

#include <algorithm>
#include <vector>

namespace brdfit::test {

using ParamSets = std::vector<std::vector<double>>;

// Parameter vectors: RGB weights (0.2, 0.5, 0.9) followed by each shape tuple.
inline ParamSets WithWeights(const ParamSets& shapes) {
  ParamSets out;
  for (const auto& s : shapes) {
    std::vector<double> p = {0.2, 0.5, 0.9};
    p.insert(p.end(), s.begin(), s.end());
    out.push_back(p);
  }
  return out;
}

// The sets of a sum from its lobes' sets: the k-th joins lobe i's set (k + i) mod (its count),
// so every set of every lobe appears and repeated lobes differ, without the full product.
inline ParamSets JoinLobeSets(const std::vector<ParamSets>& lobes) {
  std::size_t count = 0;
  for (const auto& s : lobes) count = std::max(count, s.size());
  ParamSets out(count);
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t i = 0; i < lobes.size(); ++i) {
      const auto& p = lobes[i][(k + i) % lobes[i].size()];
      out[k].insert(out[k].end(), p.begin(), p.end());
    }
  return out;
}

}  // namespace brdfit::test
