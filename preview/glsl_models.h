// Which GLSL twin (models/glsl/<name>.glsl) evaluates each lobe of a catalog model, and where
// the lobe's parameters sit in the model's parameter vector. Built from the catalog types
// (models/catalog.h), so a composite such as lambert+ggx maps to its lobes' twins.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace brdfit::preview {

struct GlslLobe {
  std::string name;      // lobe registry name, "ggx"
  std::string file;      // "models/glsl/ggx.glsl"
  std::string function;  // "brdfit_ggx"
  std::size_t offset;    // first parameter of the lobe in the model's vector
  std::size_t count;     // number of parameters of the lobe
};

// The lobes of a registered model, in parameter order. Throws InputError if the model is
// unknown; std::runtime_error if a lobe has no embedded twin.
std::vector<GlslLobe> GlslLobes(const std::string& model_name);

// "oren-nayar" -> "brdfit_oren_nayar".
std::string GlslFunctionName(const std::string& lobe_name);

}  // namespace brdfit::preview
