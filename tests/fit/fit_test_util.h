// Helpers for the fit tests: synthetic tables from catalog models.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/model_params.h"
#include "core/synth.h"
#include "core/table.h"
#include "fit/model_ops.h"
#include "models/registry.h"

namespace brdfit::testing {

// Parameters of a catalog model from "name=value" assignments over its defaults.
inline std::vector<double> Params(const std::string& model,
                                  const std::vector<std::string>& assignments) {
  const ModelInfo* m = FindModel(model);
  if (m == nullptr) throw InputError("test: unknown model " + model);
  return ResolveModelParams(*m, assignments);
}

// A table of the model at every cell centre above the horizon (core/synth.h), with optional
// log-normal multiplicative noise and holes.
inline Table SynthModel(const std::string& model, const std::vector<double>& params,
                        const Grid& grid, double noise = 0, double missing = 0,
                        std::uint64_t seed = 7) {
  const ModelInfo* m = FindModel(model);
  if (m == nullptr) throw InputError("test: unknown model " + model);
  SynthOptions o;
  o.noise = noise;
  o.missing_fraction = missing;
  o.seed = seed;
  return SynthesizeTable(
      grid, [&](const Geometry& g, double rgb[3]) { m->eval(params.data(), g, rgb); }, o);
}

// Every model's fit ops, as the engine registers them (fit/model_ops.h).
inline std::vector<internal::ModelOps> AllModelOps() {
  std::vector<internal::ModelOps> ops;
  internal::RegisterModels0(ops);
  internal::RegisterModels1(ops);
  internal::RegisterModels2(ops);
  return ops;
}

// A small grid for unit tests (MERL's sqrt theta_h mapping, coarser bins).
inline Grid SmallGrid() {
  return Grid{30, 30, 60, ThetaHMapping::kSqrt};
}

}  // namespace brdfit::testing
