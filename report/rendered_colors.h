// Colours of the rendered-image metric's images in reports (docs/accuracy.md, "Images in the
// report"): the background and pixel states, and the colour scale of the relative luminance
// error map. Display-referred sRGB values in [0, 1]; pipeline/rendered_views.h paints with them
// and the HTML legend (report/html_report.h) is drawn from them, so the two cannot disagree.
//
// Error scale: s = (Y_a - Y_m) / Y_m, |s| the metric's relative luminance error. With
// t = clamp(log10(|s| / 1 %) / 2, 0, 1) (1 % -> 0, 10 % -> 0.5, >= 100 % -> 1), the colour is
// white + t (full - white), full = kErrorBrighter for s > 0 (the approximation too bright) and
// kErrorDarker for s < 0: white up to 1 %, linear in log |s| up to full colour at 100 %.
#pragma once

#include <array>
#include <string>

namespace brdfit::report {

using Srgb = std::array<double, 3>;

inline constexpr Srgb kViewBackground = {0.19, 0.19, 0.19};  // off the sphere
inline constexpr Srgb kViewUnlit = {0, 0, 0};                // on the sphere, unlit
inline constexpr Srgb kViewMasked = {0.85, 0.15, 0.85};      // lit, measurement masked
inline constexpr Srgb kViewBelowFloor = {0.5, 0.5, 0.5};     // error map: Y_m at the floor
inline constexpr Srgb kErrorBrighter = {0.80, 0.08, 0.08};
inline constexpr Srgb kErrorDarker = {0.08, 0.25, 0.80};
inline constexpr double kErrorScaleMin = 0.01, kErrorScaleMax = 1.0;  // |s| at t = 0 and 1

// t of the scale for |s| (NaN -> 0).
double ErrorScaleT(double abs_rel_error);
// The colour of a signed relative error s.
Srgb ErrorColor(double signed_rel_error);
// "#rrggbb" of a colour (round(255 v)).
std::string HexColor(const Srgb& c);

}  // namespace brdfit::report
