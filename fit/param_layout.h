// How the fitter sees a model's parameter table: which parameters are linear colour weights
// (grouped into lobes), which are shape parameters, and the optimization space
// (x = log p for log_scale parameters, x = p otherwise) with its bounds.
#pragma once

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "models/param.h"

namespace brdfit {

struct ParamLayout {
  std::vector<ParamSpec> specs;
  // Linear colour weights, one (R, G, B) index triple per lobe, in order of appearance: the
  // i-th kWeightR, the i-th kWeightG and the i-th kWeightB parameter form lobe i.
  std::vector<std::array<int, 3>> lobes;
  std::vector<int> shape;  // every other parameter
  std::vector<double> lower_opt, upper_opt;

  // Throws std::logic_error if the weight roles do not form complete RGB triples or a bound is
  // unusable (log_scale with lower <= 0, lower >= upper).
  static ParamLayout Of(std::span<const ParamSpec> specs);

  std::size_t size() const { return specs.size(); }
  double ToOpt(std::size_t i, double p) const { return specs[i].log_scale ? std::log(p) : p; }
  double FromOpt(std::size_t i, double x) const { return specs[i].log_scale ? std::exp(x) : x; }
};

}  // namespace brdfit
