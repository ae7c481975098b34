// Derivatives of every sum in the catalog; see gradient_checks.h.
#include <gtest/gtest.h>

#include "tests/models/gradient_checks.h"

namespace brdfit::test {
namespace {

// GradientChecker at 40 random valid points, finite values and derivatives at the singular
// corners, Jet value == double value.
TEST(ModelGradients, Sums) {
  CheckCatalogDerivatives<true>();
}

}  // namespace
}  // namespace brdfit::test
