#include "factor/factor_form.h"

namespace brdfit {

FactorForm FormOf(const FactoredBrdf& brdf) {
  FactorForm f;
  f.parameterization = ToString(brdf.param());
  f.diffuse = brdf.has_diffuse();
  for (const FactorTerm& t : brdf.terms()) {
    f.terms.push_back({{t.p.width, t.p.height}, {t.q.width, t.q.height}});
  }
  return f;
}

}  // namespace brdfit
