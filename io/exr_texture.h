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

#include "core/rgb_image.h"

namespace brdfit {

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
