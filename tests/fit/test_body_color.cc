// The body's colour (docs/accuracy.md, "The body's colour"): a fit must not zero or cast a
// channel of a dark, saturated body. A dark red rough body (Oren-Nayar, sigma 0.5 rad: it
// darkens toward the rim and brightens in retro-reflection, which Lambert cannot) under a white
// GGX lobe, fitted with lambert+ggx by the defaults (rel loss and the rendered polish): the
// body keeps every channel, its colour within the tolerance of core/model_choice.h, and its
// channel ratios those of the truth.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/model_choice.h"
#include "fit/fitter.h"
#include "fit/rendered_error.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

TEST(BodyColor, ADarkSaturatedBodyKeepsEveryChannel) {
  const std::string truth_model = "oren-nayar+ggx";
  const std::vector<double> truth =
      Params(truth_model, {"kd_r=0.05", "kd_g=0.012", "kd_b=0.004", "sigma=0.5", "ks_r=0.4",
                           "ks_g=0.4", "ks_b=0.4", "alpha=0.15"});
  const Table table = SynthModel(truth_model, truth, Grid::Merl());
  SampleOptions so;
  so.budget = DefaultFitBudget();
  const FitOptions fo;  // brdfit fit's defaults
  const FitResult r = FitTable("lambert+ggx", table, so, fo);
  ASSERT_FALSE(r.Failed()) << r.message;
  ASSERT_TRUE(r.metrics.rendered.ok) << r.metrics.rendered.problem;
  std::printf("kd %.5f %.5f %.5f (truth 0.05 0.012 0.004), body colour error %.3f, S %.2f dB\n",
              r.params[0], r.params[1], r.params[2], r.metrics.rendered.body_color_error,
              *RenderedScoreDb(r));
  EXPECT_TRUE(BodyColorHolds(r.metrics.rendered)) << r.metrics.rendered.body_color_error;
  EXPECT_EQ(r.message.find("body's colour"), std::string::npos) << r.message;
  for (int c = 0; c < 3; ++c) EXPECT_GT(r.params[c], 0) << r.param_names[c];
  // The hue: blue and green against red as the truth's (0.08 and 0.24), within 25 %.
  EXPECT_NEAR(r.params[2] / r.params[0], 0.004 / 0.05, 0.25 * 0.004 / 0.05);
  EXPECT_NEAR(r.params[1] / r.params[0], 0.012 / 0.05, 0.25 * 0.012 / 0.05);
}

}  // namespace
}  // namespace brdfit
