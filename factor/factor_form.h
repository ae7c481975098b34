// A FactoredBrdf's form as stored and drawn: its label and cost (core/factor_form.h).
#pragma once

#include "core/factor_form.h"
#include "factor/factor_eval.h"

namespace brdfit {

// Parameterization, diffuse (FactoredBrdf::has_diffuse) and every term's texture sizes.
FactorForm FormOf(const FactoredBrdf& brdf);

inline FactorCost CostOf(const FactoredBrdf& brdf) {
  return ComputeFactorCost(FormOf(brdf));
}

}  // namespace brdfit
