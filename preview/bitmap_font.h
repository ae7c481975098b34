// A built-in 5x7 bitmap font (drawn for brdfit) for image labels: digits, upper-case letters
// (lower case is drawn upper case) and common punctuation. No font files, no font library, so
// labelled images are identical on every machine (golden tests).
#pragma once

#include <array>
#include <string_view>

#include "core/image.h"

namespace brdfit::preview {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7;

// Draws text with its top-left corner at (x, y), each font pixel a scale x scale block, one
// blank column between glyphs. Unknown characters draw as '?'. Clipped to the image.
void DrawText(Image* img, int x, int y, std::string_view text, int scale,
              const std::array<float, 3>& rgb);
// Width in pixels of DrawText's output.
int TextWidth(std::string_view text, int scale);
// Fills a rectangle (clipped), alpha 1.
void FillRect(Image* img, int x0, int y0, int w, int h, const std::array<float, 3>& rgb);

}  // namespace brdfit::preview
