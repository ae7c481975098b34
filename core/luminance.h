// Rec. 709 luminance of linear RGB (ITU-R BT.709-6, item 3.3; the sRGB primaries of
// IEC 61966-2-1): the one weighting brdfit gives a colour's brightness. T is double, or a
// ceres::Jet in the rendered polish.
#pragma once

namespace brdfit {

template <class T>
T Rec709Luminance(const T* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

}  // namespace brdfit
