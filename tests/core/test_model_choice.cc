// core/model_choice.h: the rule that marks a table's recommended fit, checked case by case
// against its definition (S = PSNR - 20 x median luminance error; the fewest parameters within
// the tolerance of the best S).
#include "core/model_choice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace brdfit {
namespace {

FitResult Fit(const std::string& model, std::size_t num_params, double psnr, double median,
              FitStatus status = FitStatus::kConverged) {
  FitResult r;
  r.model = model;
  r.params.assign(num_params, 0.5);
  r.status = status;
  r.metrics.rendered.ok = true;
  r.metrics.rendered.psnr_db = psnr;
  r.metrics.rendered.median_rel_error = median;
  return r;
}

std::vector<const FitResult*> Ptrs(const std::vector<FitResult>& v) {
  std::vector<const FitResult*> p;
  for (const auto& r : v) p.push_back(&r);
  return p;
}

TEST(ModelChoice, ScoreIsPsnrMinusTwentyTimesTheMedianError) {
  EXPECT_DOUBLE_EQ(*RenderedScoreDb(Fit("a", 3, 40, 0.10)), 38.0);
  FitResult failed = Fit("a", 3, 40, 0.1, FitStatus::kFailed);
  EXPECT_FALSE(RenderedScoreDb(failed));
  FitResult unscored = Fit("a", 3, 40, 0.1);
  unscored.metrics.rendered.ok = false;
  EXPECT_FALSE(RenderedScoreDb(unscored));
}

TEST(ModelChoice, PsnrBeyondSixtyDbCountsAsSixty) {
  EXPECT_DOUBLE_EQ(*RenderedScoreDb(Fit("a", 3, 73, 0.01)), 59.8);
  EXPECT_DOUBLE_EQ(*RenderedScoreDb(Fit("a", 3, 59, 0.01)), 58.8);
  // Two fits past the cap: the median error and then the parameter count decide.
  const std::vector<FitResult> fits = {Fit("big", 10, 73, 0.002), Fit("small", 7, 67, 0.004)};
  const auto c = ChooseFit(Ptrs(fits));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->index, 1u);
}

TEST(ModelChoice, BestScoreWinsWhenNothingSimplerIsClose) {
  const std::vector<FitResult> fits = {Fit("small", 7, 33, 0.10), Fit("big", 11, 40, 0.05)};
  const auto c = ChooseFit(Ptrs(fits));
  ASSERT_TRUE(c);
  EXPECT_EQ(c->index, 1u);
  EXPECT_DOUBLE_EQ(c->score_db, 39.0);
  EXPECT_NE(c->reason.find("best rendered score of 2 fit(s)"), std::string::npos) << c->reason;
}

TEST(ModelChoice, FewerParametersWinWithinTheTolerance) {
  // S: 38.0 (11 params), 37.6 (7 params, within 0.5 dB), 37.4 (4 params, not within).
  const std::vector<FitResult> fits = {Fit("big", 11, 40, 0.10), Fit("mid", 7, 39.6, 0.10),
                                       Fit("tiny", 4, 39.4, 0.10)};
  const auto c = ChooseFit(Ptrs(fits));
  ASSERT_TRUE(c);
  EXPECT_EQ(fits[c->index].model, "mid");
  EXPECT_NE(c->reason.find("7 parameters against 11 for the best-scoring big"), std::string::npos)
      << c->reason;
  // A wider tolerance admits the 4-parameter fit; none keeps the best.
  EXPECT_EQ(fits[ChooseFit(Ptrs(fits), {1.0})->index].model, "tiny");
  EXPECT_EQ(fits[ChooseFit(Ptrs(fits), {0.0})->index].model, "big");
}

TEST(ModelChoice, TiesGoToTheHigherScoreThenTheName) {
  const std::vector<FitResult> fits = {Fit("b", 7, 40, 0.1), Fit("a", 7, 40, 0.1),
                                       Fit("c", 7, 40.2, 0.1)};
  EXPECT_EQ(fits[ChooseFit(Ptrs(fits))->index].model, "c");
  const std::vector<FitResult> tied = {Fit("b", 7, 40, 0.1), Fit("a", 7, 40, 0.1)};
  EXPECT_EQ(tied[ChooseFit(Ptrs(tied))->index].model, "a");
}

TEST(ModelChoice, FailedAndUnscoredFitsTakeNoPart) {
  std::vector<FitResult> fits = {Fit("failed", 3, 90, 0, FitStatus::kFailed),
                                 Fit("unscored", 3, 90, 0), Fit("ok", 9, 30, 0.2)};
  fits[1].metrics.rendered.ok = false;
  EXPECT_EQ(fits[ChooseFit(Ptrs(fits))->index].model, "ok");
  fits.pop_back();
  EXPECT_FALSE(ChooseFit(Ptrs(fits)));
  EXPECT_FALSE(ChooseFit({}));
}

// A fit whose body is off in a channel (RenderedError::body_color_error above 0.25) is set
// aside while another fit's body holds, whatever its S; when every fit's is off, the rule is the
// plain one. Not computed (NaN, a report written before it) holds.
TEST(ModelChoice, AFitWhoseBodyColourIsOffIsChosenOnlyWhenEveryFitsIs) {
  std::vector<FitResult> fits = {Fit("zeroed", 7, 45, 0.05), Fit("holds", 9, 40, 0.08),
                                 Fit("old", 4, 30, 0.3)};
  fits[0].metrics.rendered.body_color_error = 1.0;
  fits[1].metrics.rendered.body_color_error = 0.25;  // at the tolerance: holds
  fits[2].metrics.rendered.body_color_error = std::nan("");
  EXPECT_FALSE(BodyColorHolds(fits[0].metrics.rendered));
  EXPECT_TRUE(BodyColorHolds(fits[1].metrics.rendered));
  EXPECT_TRUE(BodyColorHolds(fits[2].metrics.rendered));
  const auto c = ChooseFit(Ptrs(fits));
  ASSERT_TRUE(c);
  EXPECT_EQ(fits[c->index].model, "holds");
  EXPECT_NE(c->reason.find("best rendered score of 3 fit(s)"), std::string::npos) << c->reason;
  EXPECT_NE(c->reason.find("1 fit(s) set aside: the body's colour off by more than 25 %"),
            std::string::npos)
      << c->reason;
  // Every body off: the best S again, and nothing said about bodies.
  fits[1].metrics.rendered.body_color_error = 0.5;
  fits.pop_back();
  const auto all_off = ChooseFit(Ptrs(fits));
  ASSERT_TRUE(all_off);
  EXPECT_EQ(fits[all_off->index].model, "zeroed");
  EXPECT_EQ(all_off->reason.find("set aside"), std::string::npos) << all_off->reason;
}

}  // namespace
}  // namespace brdfit
