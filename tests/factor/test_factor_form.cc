// The stored form of a factorization: its label and what drawing it costs (core/factor_form.h,
// factor/factor_form.h).
#include <gtest/gtest.h>

#include <stdexcept>

#include "factor/factor_form.h"
#include "tests/factor/factor_test_util.h"

namespace brdfit {
namespace {

FactorForm Form(const char* param, bool diffuse, std::vector<FactorForm::Term> terms) {
  return {param, diffuse, std::move(terms)};
}

TEST(FactorCost, McCoolFetchesTwoPerTermPerLightAndOnePerTermPerFragment) {
  // Two terms of 64^2 and 32^2 textures, and a diffuse RGB.
  const FactorCost c =
      ComputeFactorCost(Form("mccool", true, {{{64, 64}, {64, 64}}, {{32, 32}, {32, 32}}}));
  EXPECT_EQ(c.texture_bytes, 12u * (2 * 64 * 64 + 2 * 32 * 32) + 12u);
  EXPECT_EQ(c.fetches_per_light, 4);
  EXPECT_EQ(c.fetches_per_fragment, 2);
}

TEST(FactorCost, HalfDiffFetchesTwoPerTermPerLightOnly) {
  const FactorCost c = ComputeFactorCost(Form("halfdiff", false, {{{16, 16}, {16, 8}}}));
  EXPECT_EQ(c.texture_bytes, 12u * (16 * 16 + 16 * 8));  // no diffuse value stored
  EXPECT_EQ(c.fetches_per_light, 2);
  EXPECT_EQ(c.fetches_per_fragment, 0);
  const FactorCost c3 = ComputeFactorCost(
      Form("halfdiff", true, {{{8, 8}, {8, 4}}, {{8, 8}, {8, 4}}, {{8, 8}, {8, 4}}}));
  EXPECT_EQ(c3.fetches_per_light, 6);
  EXPECT_EQ(c3.texture_bytes, 3 * 12u * (64 + 32) + 12u);
}

TEST(FactorCost, UnknownFormsAreRefused) {
  EXPECT_THROW(ComputeFactorCost(Form("svd", false, {{{8, 8}, {8, 8}}})), std::invalid_argument);
  EXPECT_THROW(ComputeFactorCost(Form("mccool", false, {{{-8, 8}, {8, 8}}})),
               std::invalid_argument);
}

TEST(FactorCost, OfAFactoredBrdfCountsEveryTermsTextures) {
  const FactoredBrdf b =
      testing::HandBuiltFactoredBrdf(FactorParam::kMcCool, 3, {0.01, 0.02, 0.03}, 32);
  std::size_t floats = 0;
  for (const FactorTerm& t : b.terms()) floats += t.p.rgb.size() + t.q.rgb.size();
  const FactorCost c = CostOf(b);
  EXPECT_EQ(c.texture_bytes, 4 * floats + 12);
  EXPECT_EQ(c.fetches_per_light, 6);
  EXPECT_EQ(c.fetches_per_fragment, 3);
  const FactorForm f = FormOf(b);
  EXPECT_EQ(f.rank(), 3);
  EXPECT_EQ(f.terms[1].p.width, 16);  // the hand-built terms halve in size
}

TEST(FactorCost, LabelShowsDiffuseAndRank) {
  EXPECT_EQ(FactorFormLabel(Form("mccool", false, {{}})), "mccool");  // the rank-1 name
  EXPECT_EQ(FactorFormLabel(Form("mccool", true, {{}})), "mccool+d");
  EXPECT_EQ(FactorFormLabel(Form("halfdiff", false, {{}, {}})), "halfdiff r2");
  EXPECT_EQ(FactorFormLabel(Form("mccool", true, {{}, {}, {}, {}})), "mccool+d r4");
  EXPECT_EQ(FactorFormLabel(
                FormOf(testing::HandBuiltFactoredBrdf(FactorParam::kHalfDiff, 2, {0, 0, 0.5}))),
            "halfdiff+d r2");
}

TEST(FactorCost, Texts) {
  EXPECT_EQ(BytesText(768), "768 B");
  EXPECT_EQ(BytesText(98316), "96.0 KiB");
  EXPECT_EQ(BytesText(3 * 1024 * 1024 / 2), "1.50 MiB");
  EXPECT_EQ(FactorCostText({98316, 4, 2}), "96.0 KiB, 4 fetches per light + 2 per fragment");
  EXPECT_EQ(FactorCostText({768, 2, 0}), "768 B, 2 fetches per light");
}

}  // namespace
}  // namespace brdfit
