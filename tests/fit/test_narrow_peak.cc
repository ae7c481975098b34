// Peaks narrower than the judge's pixels (fit/narrow_peak.h): detected from the model's own
// values, scored at the second lattice as well, and not chosen over a clean fit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/model_choice.h"
#include "fit/fitter.h"
#include "fit/narrow_peak.h"
#include "fit/rendered_error.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

const ModelInfo& Model(const std::string& name) {
  const ModelInfo* m = FindModel(name);
  if (!m) throw std::runtime_error("no model " + name);
  return *m;
}

// One GGX lobe, f = D G / (4 cos_i cos_o) (Walter et al. 2007, Eq. 20; plain ggx has no
// Fresnel), at theta_d = 0 where wi = wo = h: D(0) / D(t) = cos^4 t (1 + tan^2 t / alpha^2)^2
// (Eq. 33), the cosines give cos^2 t, and G(t) = 1 - O(alpha^2 tan^2 t) (below 5e-5 here).
TEST(NarrowPeak, SharpnessOfOneGgxLobeIsItsNdfRatio) {
  const ModelInfo& ggx = Model("ggx");
  for (const double alpha : {0.005, 0.02, 0.05, 0.3}) {
    SCOPED_TRACE(alpha);
    const std::vector<double> p = Params("ggx", {"alpha=" + std::to_string(alpha)});
    const double t = 2.0 / 64;
    const double expected =
        std::pow(std::cos(t), 6) * std::pow(1 + std::tan(t) * std::tan(t) / (alpha * alpha), 2);
    EXPECT_NEAR(PeakSharpness(ggx, p, 64), expected, 1e-4 * expected);
  }
}

TEST(NarrowPeak, ADiffuseBodyOrABroadLobeIsNotNarrow) {
  EXPECT_NEAR(PeakSharpness(Model("lambert"), Params("lambert", {}), 64), 1.0, 1e-12);
  EXPECT_LT(PeakSharpness(Model("lambert+ggx"), Params("lambert+ggx", {"alpha=0.2"}), 64),
            kNarrowPeakRatio);
  // A narrow lobe: GGX alpha 1e-3 is a spike at any judge resolution.
  EXPECT_GT(PeakSharpness(Model("lambert+ggx"), Params("lambert+ggx", {"alpha=0.001"}), 64),
            kNarrowPeakRatio);
}

// The failure the check exists for: a table of lambert+ggx (alpha 0.2) and a fit that adds a
// near-delta second GGX lobe to the true parameters. The default lattice (64 px, even) never
// puts a pixel centre on the spike, so the spiky fit scores as well as the true one there; the
// odd lattice puts one on the front light's mirror highlight.
struct SpikeCase {
  Table table = SynthModel("lambert+ggx",
                           Params("lambert+ggx", {"kd_r=0.3", "kd_g=0.2", "kd_b=0.1", "ks_r=0.4",
                                                  "ks_g=0.4", "ks_b=0.4", "alpha=0.2"}),
                           Grid::Merl());
  PreparedTable prepared = PrepareTable(table, SampleOptions{}, FitOptions{});
  const ModelInfo& clean_model = Model("lambert+ggx");
  const ModelInfo& spiky_model = Model("lambert+ggx+ggx");
  FitResult Fit(const ModelInfo& m, const std::vector<std::string>& assignments) const {
    FitResult r;
    r.model = m.name;
    r.param_names = m.param_names;
    r.params = Params(m.name, assignments);
    r.at_bound.assign(r.params.size(), false);
    r.status = FitStatus::kConverged;
    r.metrics.ok = true;
    r.metrics.rendered = ScoreRendered(prepared.rendered, ModelBrdf(m, r.params));
    return r;
  }
  // A clean fit, but a worse one than the spiky fit's 64 px score: alpha 15 % off.
  FitResult Clean() const {
    return Fit(clean_model, {"kd_r=0.3", "kd_g=0.2", "kd_b=0.1", "ks_r=0.4", "ks_g=0.4", "ks_b=0.4",
                             "alpha=0.23"});
  }
  FitResult Spiky() const {
    return Fit(spiky_model, {"kd_r=0.3", "kd_g=0.2", "kd_b=0.1", "ggx1.ks_r=0.4", "ggx1.ks_g=0.4",
                             "ggx1.ks_b=0.4", "ggx1.alpha=0.2", "ggx2.ks_r=1.5", "ggx2.ks_g=1.5",
                             "ggx2.ks_b=1.5", "ggx2.alpha=0.0001"});
  }
};

TEST(NarrowPeak, ASpikeBetweenPixelCentresIsScoredAtTheSecondLattice) {
  const SpikeCase c;
  ASSERT_FALSE(c.prepared.rendered_check.Empty());
  EXPECT_EQ(c.prepared.rendered_check.counts.resolution, kRenderedCheckResolution);
  FitResult clean = c.Clean();
  FitResult spiky = c.Spiky();
  ASSERT_TRUE(clean.metrics.rendered.ok);
  ASSERT_TRUE(spiky.metrics.rendered.ok);
  // The hiding: at 64 px the spiky fit (the true parameters plus the spike) outscores the
  // clean one, and would be chosen.
  const double clean_s = RenderedScoreDb(clean.metrics.rendered);
  const double hidden_s = RenderedScoreDb(spiky.metrics.rendered);
  EXPECT_GT(hidden_s, clean_s + ModelChoiceOptions{}.tolerance_db);
  const std::optional<ModelChoice> unchecked = ChooseFit({&clean, &spiky});
  ASSERT_TRUE(unchecked);
  EXPECT_EQ(unchecked->index, 1u);

  const RenderedError clean_before = clean.metrics.rendered;
  EXPECT_EQ(CheckNarrowPeak(c.clean_model, c.prepared.rendered_check, &clean), NarrowPeak::kNone);
  EXPECT_EQ(clean.metrics.rendered.resolution, clean_before.resolution);
  EXPECT_TRUE(clean.message.empty());

  EXPECT_EQ(CheckNarrowPeak(c.spiky_model, c.prepared.rendered_check, &spiky),
            NarrowPeak::kLowered);
  ASSERT_TRUE(spiky.metrics.rendered.ok);
  EXPECT_EQ(spiky.metrics.rendered.resolution, kRenderedCheckResolution);
  // Found: far below the clean fit (the spike puts ~10^7 / sr on the centre pixel).
  EXPECT_LT(RenderedScoreDb(spiky.metrics.rendered), clean_s - 20.0);
  EXPECT_NE(spiky.message.find("narrower than a pixel"), std::string::npos) << spiky.message;
  EXPECT_NE(spiky.message.find("47 px"), std::string::npos) << spiky.message;

  // And the choice takes the clean fit.
  const std::optional<ModelChoice> choice = ChooseFit({&clean, &spiky});
  ASSERT_TRUE(choice);
  EXPECT_EQ(choice->index, 0u);
}

// A fit the second lattice scores no worse keeps its metric: the check only ever lowers a
// score. A narrow but true lobe (a table of GGX alpha 0.01 fitted by itself) is such a fit.
TEST(NarrowPeak, ATrueNarrowLobeKeepsItsScoreWhereTheSecondLatticeAgrees) {
  const std::vector<double> p = Params("lambert+ggx", {"alpha=0.01"});
  const Table t = SynthModel("lambert+ggx", p, Grid::Merl());
  const PreparedTable prepared = PrepareTable(t, SampleOptions{}, FitOptions{});
  const ModelInfo& m = Model("lambert+ggx");
  FitResult r;
  r.model = m.name;
  r.params = p;
  r.status = FitStatus::kConverged;
  r.metrics.rendered = ScoreRendered(prepared.rendered, ModelBrdf(m, p));
  ASSERT_TRUE(r.metrics.rendered.ok);
  const RenderedError second = ScoreRendered(prepared.rendered_check, ModelBrdf(m, p));
  ASSERT_TRUE(second.ok);
  const bool second_worse = RenderedScoreDb(second) < RenderedScoreDb(r.metrics.rendered);
  EXPECT_EQ(CheckNarrowPeak(m, prepared.rendered_check, &r),
            second_worse ? NarrowPeak::kLowered : NarrowPeak::kKept);
  EXPECT_EQ(r.metrics.rendered.resolution, second_worse ? kRenderedCheckResolution : 64);
  // Either way the fit of the true model stays near the cap: its images equal the table's up
  // to the lookup's interpolation.
  EXPECT_GT(RenderedScoreDb(r.metrics.rendered), 30.0);
}

}  // namespace
}  // namespace brdfit
