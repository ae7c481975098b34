// A float RGBA image, rows top to bottom. Linear radiance or display-referred values,
// depending on the stage that produced it.
#pragma once

#include <cstddef>
#include <vector>

namespace brdfit {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // 4 * width * height

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0.0f) {}
  float* At(int x, int y) { return &rgba[4 * (static_cast<std::size_t>(y) * width + x)]; }
  const float* At(int x, int y) const {
    return &rgba[4 * (static_cast<std::size_t>(y) * width + x)];
  }
};

}  // namespace brdfit
