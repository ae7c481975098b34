// Which GLSL evaluates each lobe of a catalog model, and where the lobe's parameters sit in the
// model's parameter vector. Built from the catalog types (models/catalog.h), so a composite
// such as lambert+ggx maps to its lobes. Each lobe's parameter block is generated from its
// kParams (preview/glsl_params.h); a microfacet lobe's entry point is generated from its term
// types (preview/glsl_microfacet.h), any other lobe's is its twin models/glsl/<name>.glsl.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace brdfit::preview {

struct GlslLobe {
  std::string name;                      // lobe registry name, "ggx"
  std::string file;                      // "models/glsl/ggx.glsl", or the terms' file
  std::string function;                  // "brdfit_ggx"
  std::string params_struct;             // "brdfit_ggx_params"
  std::vector<std::string> param_names;  // the lobe's kParams names, in order
  std::string param_block;               // generated: struct <params_struct> {...};
  std::string entry_point;               // generated entry point; empty when `file` has it
  std::size_t offset;                    // first parameter of the lobe in the model's vector
  std::size_t count;                     // number of parameters of the lobe
};

// The lobes of a registered model, in parameter order. Throws InputError if the model is
// unknown; std::runtime_error if a lobe's GLSL file is not embedded.
std::vector<GlslLobe> GlslLobes(const std::string& model_name);

// "oren-nayar" -> "brdfit_oren_nayar".
std::string GlslFunctionName(const std::string& lobe_name);

}  // namespace brdfit::preview
