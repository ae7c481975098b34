// Fuzz harness: float RGB OpenEXR textures (io/exr_texture.h, the factorization's p and q).
// The input is the whole file. OpenEXR is built without sanitizers: coverage guides through our
// checks (header, window, channels), ASan sees the buffers we size from the header.
// After a successful read: size invariants and an exact write -> read round trip (the writer
// stores FLOAT channels losslessly, so every float comes back bit for bit).
#include <cstring>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/exr_texture.h"

namespace brdfit::fuzz {

int FuzzExr(const std::uint8_t* data, std::size_t size) {
  const auto path = WriteScratch("in.exr", data, size);
  ExrAttributes attributes;
  RgbImage image;
  try {
    image = ReadRgbExr(path, &attributes);
  } catch (const InputError&) {
    return 0;
  }
  CheckInvariant(image.width > 0 && image.height > 0, "empty image accepted");
  if (image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * image.height) {
    Violation("buffer of " + std::to_string(image.rgb.size()) + " floats for " +
              std::to_string(image.width) + " x " + std::to_string(image.height));
  }

  const auto out = ScratchDir() / "out.exr";
  try {
    WriteRgbExr(out, image, attributes);
  } catch (const InputError&) {
    return 0;  // an attribute name the writer refuses (reserved by OpenEXR): documented
  }
  ExrAttributes back_attributes;
  const RgbImage back = ReadRgbExr(out, &back_attributes);
  CheckInvariant(back.width == image.width && back.height == image.height, "round trip size");
  CheckInvariant(std::memcmp(back.rgb.data(), image.rgb.data(), image.rgb.size() * 4) == 0,
                 "round trip changed a pixel");
  CheckInvariant(back_attributes == attributes, "round trip changed the string attributes");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzExr)
