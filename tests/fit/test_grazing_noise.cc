// Grazing data (docs/accuracy.md, "Grazing data"): the least reliable cells of a measurement
// are those where the light or the view is near the horizon. The table fit drops them (the
// 80-degree cut-off on theta_i and theta_o, fit/samples.h); the rendered judge and its polish
// see every lit pixel of the sphere (n.l and n.v above 1e-3), whose grazing pixels are few and
// weighted by n.l. A synthetic table whose cells beyond 80 degrees are noisy and biased must be
// fitted as the clean one is, by the defaults (rel loss and the rendered polish).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fit/fitter.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

// Every valid cell with theta_i or theta_o beyond `from_deg` multiplied by
// bias * exp(sigma z), z standard normal per cell and channel (seeded): the brightening and
// scatter of grazing measurements.
Table WithGrazingNoise(Table t, double from_deg, double bias, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  const double c = std::cos(from_deg * kPi / 180);
  std::size_t touched = 0;
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (!t.valid[i]) continue;
    const Geometry g = MakeGeometry(t.grid.CellCentre(i));
    if (g.cos_i >= c && g.cos_o >= c) continue;
    for (int k = 0; k < 3; ++k) t.Value(i)[k] *= bias * std::exp(sigma * z(rng));
    ++touched;
  }
  EXPECT_GT(touched, t.grid.NumCells() / 20) << "the noise must reach a real share of the table";
  return t;
}

TEST(GrazingNoise, TheDefaultFitOfANoisyGrazingTableIsTheCleanOnesFit) {
  const std::string model = "lambert+ggx";
  const std::vector<double> truth = Params(
      model, {"kd_r=0.3", "kd_g=0.2", "kd_b=0.1", "ks_r=0.5", "ks_g=0.5", "ks_b=0.5", "alpha=0.2"});
  const Table clean = SynthModel(model, truth, Grid::Merl());
  SampleOptions so;
  so.budget = DefaultFitBudget();
  const FitOptions fo;  // brdfit fit's defaults
  const FitResult rc = FitTable(model, clean, so, fo);
  ASSERT_FALSE(rc.Failed()) << rc.message;
  for (const double bias : {1.0, 2.0}) {
    SCOPED_TRACE("bias " + std::to_string(bias));
    const Table noisy = WithGrazingNoise(clean, 80.0, bias, 0.5, 5);
    const FitResult rn = FitTable(model, noisy, so, fo);
    ASSERT_FALSE(rn.Failed()) << rn.message;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      // Against the truth, and against the clean table's fit (the polish's own optimum).
      EXPECT_NEAR(rn.params[i], truth[i], 0.03 * truth[i]) << rn.param_names[i];
      EXPECT_NEAR(rn.params[i], rc.params[i], 0.03 * truth[i]) << rn.param_names[i];
    }
    // The judge sees the grazing pixels: its score falls with the measured images' noise, but
    // the rendered error of the front region, whose pixels are mostly inside the cut-off, stays.
    ASSERT_TRUE(rn.metrics.rendered.ok);
    std::printf(
        "bias %.1f: alpha %.4f (clean %.4f), kd_r %.4f (clean %.4f), S regions front "
        "%.2f dB side %.2f dB rim %.2f dB\n",
        bias, rn.params[6], rc.params[6], rn.params[0], rc.params[0],
        rn.metrics.rendered.regions[0].psnr_db, rn.metrics.rendered.regions[1].psnr_db,
        rn.metrics.rendered.regions[2].psnr_db);
  }
}

}  // namespace
}  // namespace brdfit
