// Shader sources compiled into the library (preview/glsl/*, models/glsl/*), so the binary
// renders without the source tree. Keys are paths relative to the repository root.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace brdfit::preview {

struct GlslFile {
  std::string_view path;  // "models/glsl/ggx.glsl"
  std::string_view text;
};

const std::vector<GlslFile>& EmbeddedGlsl();

// The text of one embedded file; throws std::out_of_range naming the path if absent.
std::string_view GlslSource(std::string_view path);

}  // namespace brdfit::preview
