// Display transform, C++ twin of preview/glsl/tonemap.frag: exposure and tone mapping (Three.js
// r8x's set), clamp to [0, 1], then the output encoding. The GPU pass is
// what the renderer uses; this twin is the oracle its test compares with.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/enum_names.h"

namespace brdfit::preview {

enum class ToneMap { kLinear = 0, kReinhard = 1, kUncharted2 = 2, kCineon = 3 };
enum class Encoding { kLinear = 0, kSrgb = 1, kGamma2 = 2 };

inline constexpr auto kToneMapNames =
    MakeEnumNames<ToneMap>("tone map", {{ToneMap::kLinear, "linear"},
                                        {ToneMap::kReinhard, "reinhard"},
                                        {ToneMap::kUncharted2, "uncharted2"},
                                        {ToneMap::kCineon, "cineon"}});
inline constexpr auto kEncodingNames = MakeEnumNames<Encoding>(
    "output encoding",
    {{Encoding::kSrgb, "srgb"}, {Encoding::kGamma2, "gamma2"}, {Encoding::kLinear, "linear"}});
constexpr const auto& EnumNamesOf(ToneMap) {
  return kToneMapNames;
}
constexpr const auto& EnumNamesOf(Encoding) {
  return kEncodingNames;
}

struct DisplaySettings {
  ToneMap tone_map = ToneMap::kLinear;
  double exposure = 1.0;
  double white_point = 1.0;  // Uncharted2 only
  Encoding encoding = Encoding::kSrgb;
};

namespace detail {
// Hable 2010, "Filmic Tonemapping Operators" (Uncharted 2), as in Three.js r8x:
// A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30.
inline double Uncharted2Helper(double x) {
  return std::max(((x * (0.15 * x + 0.10 * 0.50) + 0.20 * 0.02) /
                   (x * (0.15 * x + 0.50) + 0.20 * 0.30)) -
                      0.02 / 0.30,
                  0.0);
}
}  // namespace detail

// One channel of linear radiance -> display value in [0, 1].
inline double ToneMapChannel(double c, const DisplaySettings& s) {
  c *= s.exposure;
  switch (s.tone_map) {
    case ToneMap::kLinear:
      break;
    case ToneMap::kReinhard:  // Reinhard et al. 2002, "Photographic Tone Reproduction", eq. 3
      c = c / (1.0 + c);
      break;
    case ToneMap::kUncharted2:
      c = detail::Uncharted2Helper(c) / detail::Uncharted2Helper(s.white_point);
      break;
    case ToneMap::kCineon: {  // Hejl and Burgess-Dawson, optimized Cineon fit (Three.js)
      c = std::max(0.0, c - 0.004);
      c = std::pow((c * (6.2 * c + 0.5)) / (c * (6.2 * c + 1.7) + 0.06), 2.2);
      break;
    }
  }
  c = std::clamp(c, 0.0, 1.0);
  switch (s.encoding) {
    case Encoding::kLinear:
      return c;
    case Encoding::kSrgb:  // IEC 61966-2-1
      return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    case Encoding::kGamma2:  // Three.js's default GAMMA_FACTOR 2
      return std::sqrt(c);
  }
  return c;
}

}  // namespace brdfit::preview
