// The GLSL parameter block of a lobe, generated at shader-assembly time from the C++ model's
// kParams (models/param.h): one float field per parameter, same names, same order. A twin
// (models/glsl/<name>.glsl) reads its parameters by name (p.alpha), so it never restates the
// layout, and the generated EvalBrdf fills the block from the lobe's slice of uParams.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "models/param.h"

namespace brdfit::preview {

// "ggx-hc" -> "brdfit_ggx_hc_params".
std::string GlslParamStructName(const std::string& lobe_name);

// struct <GlslParamStructName> { float <name>; ... };  with each parameter's unit, bounds and
// doc as a comment. Throws std::invalid_argument if a name is not a GLSL identifier.
std::string GlslParamStruct(const std::string& lobe_name, const std::vector<ParamSpec>& params);

// "<struct>(uParams[offset], ..., uParams[offset + count - 1])".
std::string GlslParamConstructor(const std::string& lobe_name, const std::string& uniform,
                                 std::size_t offset, std::size_t count);

}  // namespace brdfit::preview
