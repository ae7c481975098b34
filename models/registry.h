// Name -> model lookup, for the CLI boundary only (synth, info, reports). Inner loops use the
// model types directly (see models/catalog.h); nothing here is called per sample in a fit.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "models/catalog.h"

namespace brdfit {

struct ModelInfo {
  std::string name;                      // "lambert+ggx"
  std::string doc;                       // one line: paper, form, options
  bool energy_conserving = false;        // albedo <= 1 for unit weights (sums: weights sum <= 1)
  std::vector<ParamSpec> params;         // in parameter-vector order
  std::vector<std::string> param_names;  // qualified for sums: "lambert.kd_r", "ggx.alpha"
  // f_r (1/sr, no cosine) at a geometry, double precision.
  std::function<void(const double* params, const Geometry& g, double rgb[3])> eval;

  std::vector<double> DefaultParams() const {
    std::vector<double> p;
    for (const auto& s : params) p.push_back(s.init);
    return p;
  }
};

template <class M>
ModelInfo MakeModelInfo() {
  ModelInfo info;
  info.name = ModelName<M>();
  if constexpr (requires { M::Doc(); }) {
    info.doc = M::Doc();
  } else {
    info.doc = std::string(M::kDoc);
  }
  info.energy_conserving = M::kEnergyConserving;
  info.params.assign(M::kParams.begin(), M::kParams.end());
  if constexpr (requires { M::QualifiedParamNames(); }) {
    info.param_names = M::QualifiedParamNames();
  } else {
    for (const auto& p : M::kParams) info.param_names.emplace_back(p.name);
  }
  info.eval = [](const double* p, const Geometry& g, double rgb[3]) { M::Eval(p, g, rgb); };
  return info;
}

inline const std::vector<ModelInfo>& AllModels() {
  static const std::vector<ModelInfo> models = [] {
    std::vector<ModelInfo> out;
    ForEachModel([&](auto m) { out.push_back(MakeModelInfo<typename decltype(m)::type>()); });
    return out;
  }();
  return models;
}

// nullptr if unknown.
inline const ModelInfo* FindModel(std::string_view name) {
  for (const auto& m : AllModels()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// Every registered name, in the registry's order.
inline std::vector<std::string> AllModelNames() {
  std::vector<std::string> names;
  for (const auto& m : AllModels()) names.push_back(m.name);
  return names;
}

// Comma-separated list of every registered name, for error messages.
inline std::string ModelNames() {
  std::string s;
  for (const auto& m : AllModels()) s += (s.empty() ? "" : ", ") + m.name;
  return s;
}

}  // namespace brdfit
