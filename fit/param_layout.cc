#include "fit/param_layout.h"

#include <stdexcept>

namespace brdfit {

ParamLayout ParamLayout::Of(std::span<const ParamSpec> specs) {
  ParamLayout l;
  l.specs.assign(specs.begin(), specs.end());
  std::array<std::vector<int>, 3> by_channel;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const ParamSpec& s = specs[i];
    switch (s.role) {
      case ParamRole::kWeightR:
        by_channel[0].push_back(static_cast<int>(i));
        break;
      case ParamRole::kWeightG:
        by_channel[1].push_back(static_cast<int>(i));
        break;
      case ParamRole::kWeightB:
        by_channel[2].push_back(static_cast<int>(i));
        break;
      case ParamRole::kShape:
        l.shape.push_back(static_cast<int>(i));
        break;
    }
    if (!(s.lower < s.upper) || (s.log_scale && !(s.lower > 0))) {
      throw std::logic_error("parameter " + std::string(s.name) + " has unusable bounds");
    }
    l.lower_opt.push_back(s.log_scale ? std::log(s.lower) : s.lower);
    l.upper_opt.push_back(s.log_scale ? std::log(s.upper) : s.upper);
  }
  if (by_channel[0].size() != by_channel[1].size() ||
      by_channel[0].size() != by_channel[2].size()) {
    throw std::logic_error("colour weight roles do not form RGB triples");
  }
  for (std::size_t k = 0; k < by_channel[0].size(); ++k) {
    l.lobes.push_back({by_channel[0][k], by_channel[1][k], by_channel[2][k]});
  }
  return l;
}

}  // namespace brdfit
