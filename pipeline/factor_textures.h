// A factorization as the preview draws it (preview/material.h): every term's textures as RGBA
// images, the diffuse value, and FactoredBrdf::Eval for the CPU reference renderer.
#pragma once

#include <memory>

#include "factor/factor_eval.h"
#include "preview/material.h"

namespace brdfit::pipeline {

// Throws InputError if the rank exceeds what the preview's shader holds
// (preview::kMaxFactorTextureTerms).
std::shared_ptr<const preview::FactorTextures> ToFactorTextures(FactoredBrdf brdf);

}  // namespace brdfit::pipeline
