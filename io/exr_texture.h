// Float32 RGB textures as OpenEXR files (docs/formats.md, "Factorization files").
//
// Channels R, G, B, pixel type FLOAT, ZIP compression (lossless): write -> read returns every
// float bit for bit. String attributes are stored as OpenEXR string attributes in the header.
// Row 0 of the image is the first scan line of the file (the EXR data window's min y).
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
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

using ExrAttributes = std::map<std::string, std::string>;

// Writes atomically (temporary file + rename). Throws OutputError on failure and InputError
// if the image is empty or its buffer size does not match.
void WriteRgbExr(const std::filesystem::path& path, const RgbImage& image,
                 const ExrAttributes& attributes);

// Reads an RGB EXR (HALF or UINT channels are converted to float). String attributes of the
// header are returned in *attributes (other attribute types are skipped). Throws InputError
// naming the file: missing, not an OpenEXR file, missing R/G/B channel, damaged.
RgbImage ReadRgbExr(const std::filesystem::path& path, ExrAttributes* attributes = nullptr);

}  // namespace brdfit
