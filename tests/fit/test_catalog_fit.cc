// The fitter over the whole catalog: the assumptions it makes about every model (linear colour
// weights, mirror symmetry), that every model fits a table of itself, failure paths, determinism
// and robust losses.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fit/fitter.h"
#include "fit_test_util.h"
#include "models/registry.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SmallGrid;
using testing::SynthModel;

// Random parameters inside the bounds (log-uniform for log_scale ones, shape parameters kept in
// the middle half so that no lobe is degenerate).
std::vector<double> RandomParams(const ModelInfo& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> p;
  for (const ParamSpec& s : m.params) {
    double t = u(rng);
    if (s.role == ParamRole::kShape) t = 0.25 + 0.5 * t;
    const double hi = s.role == ParamRole::kShape ? s.upper : std::min(s.upper, 1.0);
    p.push_back(s.log_scale ? std::exp(std::log(s.lower) + t * (std::log(hi) - std::log(s.lower)))
                            : s.lower + t * (hi - s.lower));
  }
  return p;
}

TEST(Catalog, EveryRegisteredModelIsFittable) {
  std::vector<std::string> names;
  for (const ModelInfo& m : AllModels()) names.push_back(m.name);
  EXPECT_EQ(FittableModels(), names);
  EXPECT_TRUE(IsFittable("lambert+ggx"));
  EXPECT_FALSE(IsFittable("no-such-model"));
}

// grid_init.h assumes channel c is jointly linear in the channel-c weights of all lobes with no
// constant term, and independent of the other channels' weights.
TEST(Catalog, ColourWeightsAreLinearAndPerChannel) {
  std::mt19937 rng(5);
  const Grid g = SmallGrid();
  for (const ModelInfo& m : AllModels()) {
    std::vector<int> weights;
    for (std::size_t i = 0; i < m.params.size(); ++i) {
      if (m.params[i].role != ParamRole::kShape) weights.push_back(static_cast<int>(i));
    }
    if (weights.empty()) continue;  // e.g. ue4: base colour also sets F0, not a linear weight
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<double> p = RandomParams(m, rng);
      const Geometry geo = MakeGeometry(g.CellCentre(g.Index(3 + trial % 10, 5 + trial, 7)), 0.0);
      double f[3];
      m.eval(p.data(), geo, f);
      double sum[3] = {0, 0, 0};
      for (int i : weights) {
        std::vector<double> unit = p;
        for (int j : weights) unit[j] = 0.0;
        unit[i] = p[i];
        double part[3];
        m.eval(unit.data(), geo, part);
        const int ch = static_cast<int>(m.params[i].role) - static_cast<int>(ParamRole::kWeightR);
        for (int c = 0; c < 3; ++c) {
          if (c != ch) {
            EXPECT_EQ(part[c], 0.0) << m.name << " weight " << m.param_names[i];
          }
        }
        sum[ch] += part[ch];
      }
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sum[c], f[c], 1e-12 * (1 + std::abs(f[c]))) << m.name << " channel " << c;
      }
    }
  }
}

// samples.h evaluates a cell and its phi_d mirror once: every catalog model must be isotropic
// and reciprocal.
TEST(Catalog, ModelsAgreeAtMirrorCells) {
  std::mt19937 rng(8);
  const Grid g = SmallGrid();
  for (const ModelInfo& m : AllModels()) {
    for (int trial = 0; trial < 50; ++trial) {
      const std::vector<double> p = RandomParams(m, rng);
      const int ih = 1 + trial % 20, id = 2 + (trial * 7) % 20, ip = (trial * 13) % 60;
      Vec3 a_i, a_o, b_i, b_o;
      FromHalfDiff(g.CellCentre(ih, id, ip), 0.0, &a_i, &a_o);
      FromHalfDiff(g.CellCentre(ih, id, g.n_phi_d - 1 - ip), 0.0, &b_i, &b_o);
      if (a_i.z <= 0.01 || a_o.z <= 0.01) continue;
      double fa[3], fb[3];
      m.eval(p.data(), MakeGeometry(a_i, a_o), fa);
      m.eval(p.data(), MakeGeometry(b_i, b_o), fb);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(fa[c], fb[c], 1e-9 * (std::abs(fa[c]) + 1e-300)) << m.name;
      }
    }
  }
}

// Every catalog model fits a noise-free table of itself (random parameters inside the bounds,
// shape parameters in the middle half) to a tiny error. Multi-lobe models are not identifiable
// parameter by parameter (lobes can trade), so the check is on the metric. One case per model.
class OwnTable : public ::testing::TestWithParam<std::string> {};

TEST_P(OwnTable, ModelFitsItsOwnTable) {
  const ModelInfo& m = *FindModel(GetParam());
  std::mt19937 rng(12 + static_cast<unsigned>(m.name.size()));
  const std::vector<double> truth = RandomParams(m, rng);
  const Table t = SynthModel(m.name, truth, Grid{24, 24, 48, ThetaHMapping::kSqrt});
  const FitResult r = FitTable(m.name, t, SampleOptions{}, LogLossUnpolished());
  EXPECT_FALSE(r.Failed()) << m.name << ": " << r.message;
  EXPECT_LT(r.metrics.log_rmse, 1e-4) << m.name << " " << ::testing::PrintToString(truth)
                                      << " fitted " << ::testing::PrintToString(r.params);
  for (double v : r.params) EXPECT_TRUE(std::isfinite(v)) << m.name;
}

std::vector<std::string> CatalogNames() {
  std::vector<std::string> names;
  for (const ModelInfo& m : AllModels()) names.push_back(m.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Catalog, OwnTable, ::testing::ValuesIn(CatalogNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string s = info.param;
                           for (char& c : s) {
                             if (c == '-' || c == '+') c = '_';
                           }
                           return s;
                         });

TEST(Failure, AllInvalidTableGivesFailedStatusAndFiniteFields) {
  const Table t = Table::Empty(SmallGrid());
  const FitResult r = FitTable("lambert+ggx", t, SampleOptions{}, LogLossUnpolished());
  EXPECT_EQ(r.status, FitStatus::kFailed);
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(r.params.size(), 7u);
  for (double v : r.params) EXPECT_TRUE(std::isfinite(v));
  EXPECT_TRUE(std::isfinite(r.metrics.log_rmse));
}

TEST(Failure, EverythingBeyondCutoffFails) {
  const Table t = SynthModel("lambert", Params("lambert", {}), SmallGrid());
  SampleOptions so;
  so.cutoff_deg = 0.5;  // no cell centre is that close to the normal on both sides
  const FitResult r = FitTable("lambert", t, so, LogLossUnpolished());
  EXPECT_EQ(r.status, FitStatus::kFailed);
}

TEST(Failure, UnknownModelIsAnInputError) {
  const Table t = SynthModel("lambert", Params("lambert", {}), SmallGrid());
  EXPECT_THROW(FitTable("glossy", t, SampleOptions{}, LogLossUnpolished()), InputError);
}

TEST(Fit, DeterministicAndMultistartNoWorse) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.04"});
  const Table t = SynthModel("lambert+ggx", truth, SmallGrid(), 0.05, 0.3, 4);
  const FitResult a = FitTable("lambert+ggx", t, SampleOptions{}, LogLossUnpolished());
  const FitResult b = FitTable("lambert+ggx", t, SampleOptions{}, LogLossUnpolished());
  EXPECT_EQ(a.params, b.params);
  EXPECT_EQ(a.metrics.log_rmse, b.metrics.log_rmse);
  FitOptions multi = LogLossUnpolished();
  multi.multistart = 4;
  const FitResult c = FitTable("lambert+ggx", t, SampleOptions{}, multi);
  EXPECT_EQ(c.starts, 4);
  EXPECT_LE(c.final_cost, a.final_cost * (1 + 1e-12));
}

TEST(Fit, RobustLossResistsOutliers) {
  // 2 % of the cells multiplied by 20 (specks): Huber keeps alpha within 1 %; the plain log
  // loss is pulled further.
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.1"});
  Table t = SynthModel("lambert+ggx", truth, Grid{40, 40, 80, ThetaHMapping::kSqrt});
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t i = 0; i < t.grid.NumCells(); ++i) {
    if (t.valid[i] && u(rng) < 0.02) {
      for (int c = 0; c < 3; ++c) t.Value(i)[c] *= 20;
    }
  }
  FitOptions plain, huber;
  huber.robust = RobustKind::kHuber;
  huber.robust_scale = 0.05;
  const FitResult rp = FitTable("lambert+ggx", t, SampleOptions{}, plain);
  const FitResult rh = FitTable("lambert+ggx", t, SampleOptions{}, huber);
  ASSERT_FALSE(rh.Failed()) << rh.message;
  const double err_plain = std::abs(rp.params[6] / truth[6] - 1);
  const double err_huber = std::abs(rh.params[6] / truth[6] - 1);
  EXPECT_LT(err_huber, 0.01);
  EXPECT_LT(err_huber, err_plain);
}

}  // namespace
}  // namespace brdfit
