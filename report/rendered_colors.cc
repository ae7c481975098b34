#include "report/rendered_colors.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace brdfit::report {

double ErrorScaleT(double e) {
  if (!(e > kErrorScaleMin)) return 0;
  return std::min(1.0, std::log10(e / kErrorScaleMin) / std::log10(kErrorScaleMax / kErrorScaleMin));
}

Srgb ErrorColor(double s) {
  const double t = ErrorScaleT(std::abs(s));
  const Srgb& full = s > 0 ? kErrorBrighter : kErrorDarker;
  Srgb c{};
  for (int i = 0; i < 3; ++i) c[i] = (1 - t) + t * full[i];  // exact at t = 0 and t = 1
  return c;
}

std::string HexColor(const Srgb& c) {
  auto b = [](double v) { return static_cast<int>(std::lround(255 * std::clamp(v, 0.0, 1.0))); };
  return fmt::format("#{:02x}{:02x}{:02x}", b(c[0]), b(c[1]), b(c[2]));
}

}  // namespace brdfit::report
