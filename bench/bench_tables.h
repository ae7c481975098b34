// Tables shared by the benchmark programs.
#pragma once

#include <vector>

#include "core/synth.h"
#include "io/model_params.h"
#include "models/registry.h"

namespace brdfit::bench {

// Lambert + GGX (alpha 0.08, warm colours) on the full MERL grid with 5 % log-normal noise and
// 10 % holes, seed 1: the synthetic table of bench_fit and bench_metrics.
inline Table SyntheticLambertGgxTable() {
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = ResolveModelParams(
      m, {"kd_r=0.2", "kd_g=0.1", "kd_b=0.05", "ks_r=0.5", "ks_g=0.4", "ks_b=0.3", "alpha=0.08"});
  SynthOptions o;
  o.noise = 0.05;
  o.missing_fraction = 0.1;
  o.seed = 1;
  return SynthesizeTable(
      Grid::Merl(), [&](const Geometry& g, double rgb[3]) { m.eval(p.data(), g, rgb); }, o);
}

}  // namespace brdfit::bench
