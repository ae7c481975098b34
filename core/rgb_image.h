// A float32 RGB texture in memory (the factorization's textures; stored as OpenEXR by
// io/exr_texture.h).
#pragma once

#include <cstddef>
#include <vector>

namespace brdfit {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // 3 * width * height, interleaved RGB, row-major (row 0 first)

  static RgbImage Filled(int width, int height, float value) {
    return {width, height, std::vector<float>(3 * static_cast<std::size_t>(width) * height, value)};
  }
  float* At(int i, int j) { return &rgb[3 * (static_cast<std::size_t>(j) * width + i)]; }
  const float* At(int i, int j) const {
    return &rgb[3 * (static_cast<std::size_t>(j) * width + i)];
  }
  bool operator==(const RgbImage&) const = default;
};

}  // namespace brdfit
