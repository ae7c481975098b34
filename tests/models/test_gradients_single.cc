// Derivatives of every single (non-sum) catalog model; see gradient_checks.h.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <array>
#include <string_view>
#include <type_traits>

#include "tests/models/gradient_checks.h"

namespace brdfit::test {
namespace {

// A model whose Jet derivative is wrong on purpose (d/dp1 is missing): the check must fail.
struct BrokenDerivative {
  static constexpr std::string_view kName = "broken";
  static constexpr std::array<ParamSpec, 2> kParams = {{
      {"w", "1", 0.1, 1.0, 0.5, false, "", ParamRole::kShape},
      {"alpha", "1", 0.1, 1.0, 0.5, false, "", ParamRole::kShape},
  }};
  template <class T>
  static void Eval(const T* p, const Geometry& g, T rgb[3]) {
    T detached = p[1];
    if constexpr (!std::is_same_v<T, double>) detached.v.setZero();
    for (int c = 0; c < 3; ++c) rgb[c] = p[0] * detached * g.cos_i;
  }
};

TEST(ModelGradients, CheckerDetectsAWrongDerivative) {
  EXPECT_NONFATAL_FAILURE(CheckGradients<BrokenDerivative>(1), "broken");
}

// GradientChecker at 40 random valid points, finite values and derivatives at the singular
// corners, Jet value == double value.
TEST(ModelGradients, SingleModels) {
  CheckCatalogDerivatives<false>();
}

}  // namespace
}  // namespace brdfit::test
