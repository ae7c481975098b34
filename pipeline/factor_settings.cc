#include "pipeline/factor_settings.h"

#include <fmt/core.h>

#include <cmath>

#include "core/error.h"

namespace brdfit::pipeline {

FactorOptions MakeFactorOptions(const FactorSettings& o) {
  FactorOptions f;
  f.param = FactorParamFromString(o.param);
  f.resolution = o.resolution;
  f.lambda = o.lambda;
  f.weighting = FromString<FactorWeighting>(o.weighting);
  if (!(o.max_theta_deg > 0 && o.max_theta_deg <= 90)) {
    throw InputError(fmt::format("--max-theta {} outside (0, 90]", o.max_theta_deg));
  }
  f.max_theta = o.max_theta_deg * kPi / 180;
  if (o.resolution < 4 || o.resolution > 1024) {
    throw InputError(fmt::format("--res {} outside [4, 1024]", o.resolution));
  }
  if (!(o.lambda > 0) || !std::isfinite(o.lambda)) {
    throw InputError(fmt::format("--lambda {} must be a positive number", o.lambda));
  }
  if (o.rank < 1 || o.rank > kMaxFactorRank) {
    throw InputError(fmt::format("--rank {} outside [1, {}]", o.rank, kMaxFactorRank));
  }
  if (o.refine_iterations < 1 || o.refine_iterations > kMaxRefineIterations) {
    throw InputError(fmt::format("--refine-iterations {} outside [1, {}]", o.refine_iterations,
                                 kMaxRefineIterations));
  }
  f.diffuse = o.diffuse;
  f.rank = o.rank;
  f.refine = o.refine;
  f.refine_iterations = o.refine_iterations;
  f.refine_loss = FromString<RefineLoss>(o.refine_loss);
  return f;
}

}  // namespace brdfit::pipeline
