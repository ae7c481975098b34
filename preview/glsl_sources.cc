#include "preview/glsl_sources.h"

#include <stdexcept>

namespace brdfit::preview {

std::string_view GlslSource(std::string_view path) {
  for (const auto& f : EmbeddedGlsl()) {
    if (f.path == path) return f.text;
  }
  throw std::out_of_range("no embedded shader source '" + std::string(path) + "'");
}

}  // namespace brdfit::preview
