// Model parameters by name (synth, Python, fit reports, render caches): "name=value" with
// qualified names ("ggx.alpha", "lambert.kd_r") or unqualified ones ("alpha") when exactly one
// parameter of the model has that name. Errors list the valid names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "models/registry.h"

namespace brdfit {

// Index of a parameter in the model's parameter vector. Throws InputError for an unknown name
// (listing every valid name) or an ambiguous unqualified one (listing the qualified choices).
std::size_t FindParamIndex(const ModelInfo& model, std::string_view name);

// The model's defaults with each "name=value" applied. Values must parse as finite numbers and
// lie inside the parameter's bounds; a parameter may be given once. Throws InputError.
std::vector<double> ResolveModelParams(const ModelInfo& model,
                                       const std::vector<std::string>& assignments);

// {"lambert.kd_r": 0.5, ...} in parameter order (qualified names), as compact JSON.
std::string ParamsToJson(const ModelInfo& model, const std::vector<double>& params);

// Why `params` cannot be the parameters of `model` ("" if they can): the model is registered,
// there is one value per parameter, each finite and inside its bounds. Readers of files that
// hold parameters (fit reports, fit parameters JSON, render caches) refuse what this refuses:
// a value of 1e300 crashed the renderer.
std::string CheckModelParams(const std::string& model, const std::vector<double>& params);

// Why `names` are not `model`'s qualified parameter names in order ("" if they are). The
// model must be registered.
std::string CheckModelParamNames(const ModelInfo& model, const std::vector<std::string>& names);

// "lambert.kd_r (kd_r), ..., ggx.alpha (alpha)": every accepted spelling.
std::string ValidParamNames(const ModelInfo& model);

}  // namespace brdfit
