// Parameter names at the CLI boundary (core/model_params.h).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/model_params.h"

namespace brdfit {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

const ModelInfo& LambertGgx() {
  const ModelInfo* m = FindModel("lambert+ggx");
  EXPECT_NE(m, nullptr);
  return *m;
}

TEST(ModelParams, QualifiedAndUnambiguousBareNames) {
  const ModelInfo& m = LambertGgx();
  const auto p = ResolveModelParams(m, {"ggx.alpha=0.25", "kd_g=0.125", "lambert.kd_r=0"});
  auto at = [&](const char* name) { return p[FindParamIndex(m, name)]; };
  EXPECT_EQ(at("ggx.alpha"), 0.25);
  EXPECT_EQ(at("alpha"), 0.25);
  EXPECT_EQ(at("lambert.kd_g"), 0.125);
  EXPECT_EQ(at("kd_r"), 0.0);
  EXPECT_EQ(at("ks_b"), m.params[FindParamIndex(m, "ks_b")].init);  // untouched: default
}

TEST(ModelParams, SingleModelAcceptsItsOwnPrefix) {
  const ModelInfo* ggx = FindModel("ggx");
  ASSERT_NE(ggx, nullptr);
  EXPECT_EQ(FindParamIndex(*ggx, "ggx.alpha"), FindParamIndex(*ggx, "alpha"));
  EXPECT_THROW(FindParamIndex(*ggx, "lambert.alpha"), InputError);
}

TEST(ModelParams, UnknownNameListsTheValidOnes) {
  EXPECT_THAT([] { FindParamIndex(LambertGgx(), "beta"); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("unknown parameter 'beta' for model lambert+ggx; valid: "),
                        HasSubstr("lambert.kd_r (kd_r)"), HasSubstr("ggx.alpha (alpha)"))));
}

TEST(ModelParams, AmbiguousBareNameListsTheQualifiedChoices) {
  ModelInfo two;  // shaped like lambert+ggx+ggx
  two.name = "ggx+ggx";
  ParamSpec alpha{"alpha", "1", 1e-4, 1, 0.1, true, "", ParamRole::kShape};
  two.params = {alpha, alpha};
  two.param_names = {"ggx1.alpha", "ggx2.alpha"};
  EXPECT_THAT([&] { FindParamIndex(two, "alpha"); },
              ThrowsMessage<InputError>(
                  "parameter 'alpha' is ambiguous for model ggx+ggx; use one of ggx1.alpha, "
                  "ggx2.alpha"));
  EXPECT_EQ(FindParamIndex(two, "ggx2.alpha"), 1u);
  EXPECT_EQ(ValidParamNames(two), "ggx1.alpha, ggx2.alpha");
}

TEST(ModelParams, BadValuesBoundsAndRepeats) {
  const ModelInfo& m = LambertGgx();
  EXPECT_THAT([&] { ResolveModelParams(m, {"alpha=2"}); },
              ThrowsMessage<InputError>(HasSubstr("outside the bounds [0.0001, 1]")));
  EXPECT_THAT([&] { ResolveModelParams(m, {"alpha=0.1x"}); },
              ThrowsMessage<InputError>(HasSubstr("'0.1x' is not a finite number")));
  EXPECT_THROW(ResolveModelParams(m, {"alpha=nan"}), InputError);
  EXPECT_THROW(ResolveModelParams(m, {"alpha"}), InputError);
  EXPECT_THAT(
      [&] {
        ResolveModelParams(m, {"alpha=0.2", "ggx.alpha=0.3"});
      },
      ThrowsMessage<InputError>("--param ggx.alpha given twice"));
}

TEST(ModelParams, JsonHasQualifiedNamesInParameterOrder) {
  const ModelInfo& m = LambertGgx();
  std::vector<double> p = m.DefaultParams();
  p[FindParamIndex(m, "alpha")] = 0.5;
  const std::string j = ParamsToJson(m, p);
  EXPECT_EQ(j.find("\"lambert.kd_r\""), 1u);
  EXPECT_THAT(j, HasSubstr("\"ggx.alpha\":0.5"));
  EXPECT_LT(j.find("kd_b"), j.find("ks_r"));
}

}  // namespace
}  // namespace brdfit
