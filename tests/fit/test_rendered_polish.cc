// The rendered polish (fit/rendered_polish.h): its residual block against an independent
// evaluation of the residuals, and what the polish promises — never a lower rendered score,
// the truth kept on a table of the model itself, the same bits for any thread count.
#include <gtest/gtest.h>

#include <cmath>

#include "core/model_choice.h"
#include "fit/fitter.h"
#include "fit/pixel_cost.h"
#include "fit/rendered_polish.h"
#include "models/catalog.h"
#include "tests/fit/fit_test_util.h"

namespace brdfit {
namespace {

using testing::Params;
using testing::SynthModel;

const Grid kGrid{32, 32, 64, ThetaHMapping::kSqrt};

// Pixels of a reference with arbitrary positive weights, for the block test.
internal::PolishPixels PixelsOf(const RenderedReference& ref) {
  internal::PolishPixels px;
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
    const auto& q = ref.pixels[i];
    px.geometry.push_back(MakeGeometry(q.wi, q.wo));
    px.cos_l.push_back(q.cos_l);
    px.measured.push_back(q.measured);
    px.rel_w.push_back(i % 7 == 3 ? 0.0 : 0.01 * (1 + static_cast<double>(i % 5)));
    px.delta.push_back(1e-3);
    px.lin_w.push_back(2.5 + 0.1 * static_cast<double>(i % 3));
  }
  return px;
}

// The residuals of the header's formulas, written out from ModelInfo's evaluator.
std::vector<double> OracleResiduals(const ModelInfo& m, const internal::PolishPixels& px,
                                    const std::vector<double>& x) {
  std::vector<double> p(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) p[i] = m.params[i].log_scale ? std::exp(x[i]) : x[i];
  std::vector<double> r;
  for (std::size_t i = 0; i < px.size(); ++i) {
    double f[3];
    m.eval(p.data(), px.geometry[i], f);
    double L[3];
    for (int c = 0; c < 3; ++c) {
      L[c] = f[c] * px.cos_l[i];
      r.push_back(px.lin_w[i] * (L[c] - px.measured[i][c]));
    }
    const double y = 0.2126 * L[0] + 0.7152 * L[1] + 0.0722 * L[2];
    const double ym =
        0.2126 * px.measured[i][0] + 0.7152 * px.measured[i][1] + 0.0722 * px.measured[i][2];
    r.push_back(px.rel_w[i] > 0 ? px.rel_w[i] * std::log((y + px.delta[i]) / (ym + px.delta[i]))
                                : 0.0);
  }
  return r;
}

TEST(RenderedPolish, PixelBlockMatchesIndependentResiduals) {
  using M = Sum<Lambert, Ggx>;
  const ModelInfo& m = *FindModel("lambert+ggx");
  const Table t = SynthModel("lambert+ggx+ggx",
                             Params("lambert+ggx+ggx", {"ggx1.alpha=0.08", "ggx2.alpha=0.3"}), kGrid);
  RenderedErrorOptions ro;
  ro.resolution = 24;
  const RenderedReference ref = PrepareRenderedReference(t, ro);
  const internal::PolishPixels px = PixelsOf(ref);
  const ParamLayout layout = ParamLayout::Of(M::kParams);
  const std::vector<double> p = Params("lambert+ggx", {"ggx.alpha=0.12", "lambert.kd_g=0.3"});
  std::vector<double> x(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[i] = layout.ToOpt(i, p[i]);

  const std::vector<double> r = OracleResiduals(m, px, x);
  double cost = 0;
  for (double e : r) cost += e * e;
  const int P = static_cast<int>(x.size());
  // J^T r by central differences of the oracle.
  std::vector<double> jtr(P, 0.0);
  for (int k = 0; k < P; ++k) {
    std::vector<double> xp = x, xm = x;
    const double h = 1e-6 * std::max(1.0, std::abs(x[k]));
    xp[k] += h;
    xm[k] -= h;
    const auto rp = OracleResiduals(m, px, xp), rm = OracleResiduals(m, px, xm);
    for (std::size_t j = 0; j < r.size(); ++j) jtr[k] += r[j] * (rp[j] - rm[j]) / (2 * h);
  }

  internal::PixelCost<M> block(px, layout, 0, px.size());
  std::vector<double> res(P + 1), jac((P + 1) * P);
  const double* params[] = {x.data()};
  double* jacs[] = {jac.data()};
  ASSERT_TRUE(block.Evaluate(params, res.data(), jacs));
  double block_cost = 0;
  for (double e : res) block_cost += e * e;
  EXPECT_NEAR(block_cost, cost, 1e-12 * cost);
  for (int k = 0; k < P; ++k) {
    double g = 0;  // (J~^T r~)_k = (J^T r)_k
    for (int j = 0; j <= P; ++j) g += jac[j * P + k] * res[j];
    EXPECT_NEAR(g, jtr[k], 1e-6 * (std::abs(jtr[k]) + 1e-3 * std::sqrt(cost))) << m.param_names[k];
  }
  // The cost-only path of a fresh block (nothing cached) gives the same cost; the block's own
  // repeats at the same x come from its cache (fit/block_compress.h JacobianCache), bit for bit.
  internal::PixelCost<M> fresh(px, layout, 0, px.size());
  std::vector<double> res2(P + 1);
  ASSERT_TRUE(fresh.Evaluate(params, res2.data(), nullptr));
  EXPECT_DOUBLE_EQ(res2[P] * res2[P], block_cost);
  std::vector<double> res3(P + 1), jac3((P + 1) * P);
  double* jacs3[] = {jac3.data()};
  ASSERT_TRUE(block.Evaluate(params, res3.data(), jacs3));
  EXPECT_EQ(res3, res);
  EXPECT_EQ(jac3, jac);
  ASSERT_TRUE(block.Evaluate(params, res2.data(), nullptr));
  EXPECT_DOUBLE_EQ(res2[P] * res2[P], block_cost);
  // Another x is evaluated, not answered from the cache.
  std::vector<double> x2 = x;
  x2[P - 1] += 0.1;
  const double* params2[] = {x2.data()};
  ASSERT_TRUE(block.Evaluate(params2, res3.data(), jacs3));
  EXPECT_NE(jac3, jac);
}

// The fit of `model` without and with the polish, on one prepared table (loss rel).
struct PlainAndPolished {
  PreparedTable prepared;
  FitResult plain, polished;
};
PlainAndPolished FitBoth(const std::string& model, const Table& t) {
  FitOptions o = LogLossUnpolished();
  o.loss = LossKind::kRel;
  PlainAndPolished r{PrepareTable(t, SampleOptions{}, o), {}, {}};
  r.plain = FitPrepared(model, r.prepared, o);
  o.polish = PolishKind::kRendered;
  r.polished = FitPrepared(model, r.prepared, o);
  return r;
}

// A table lambert+ggx cannot express: two GGX lobes (α 0.05 and 0.35) over a dark diffuse.
Table TwoLobeTable() {
  return SynthModel("lambert+ggx+ggx",
                    Params("lambert+ggx+ggx", {"ggx1.alpha=0.05", "ggx2.alpha=0.35",
                                               "lambert.kd_r=0.02", "lambert.kd_g=0.02",
                                               "lambert.kd_b=0.02"}),
                    kGrid);
}

// A model that cannot express the table (one lobe for two): the polish raises S, and the
// outcome it reports is the metric of the fit it returns.
TEST(RenderedPolish, RaisesTheRenderedScoreOfAMismatchedFit) {
  const Table t = TwoLobeTable();
  const auto [prepared, plain, polished] = FitBoth("lambert+ggx", t);
  ASSERT_FALSE(plain.Failed());
  ASSERT_FALSE(polished.Failed());
  const double s0 = RenderedScoreDb(plain.metrics.rendered);
  const double s1 = RenderedScoreDb(polished.metrics.rendered);
  EXPECT_GT(s1, s0) << "plain " << s0 << " dB, polished " << s1 << " dB";
  EXPECT_GT(polished.iterations, plain.iterations);
  // Its metric is the one of its parameters.
  const RenderedError again =
      ScoreRendered(prepared.rendered, ModelBrdf(*FindModel("lambert+ggx"), polished.params));
  EXPECT_DOUBLE_EQ(RenderedScoreDb(again), s1);
  // And the options say so (reports key fits by them).
  FitOptions o = LogLossUnpolished();
  o.polish = PolishKind::kRendered;
  EXPECT_NE(OptionsJson(SampleOptions{}, o).find("\"polish\":\"rendered\""), std::string::npos);
  EXPECT_EQ(OptionsJson(SampleOptions{}, LogLossUnpolished()).find("polish"), std::string::npos);
}

// On a table of the model itself the fit is the truth: it is not polished (fit/fit_engine.cc),
// since all the polish could fit there is the rendered images' interpolation of the table.
TEST(RenderedPolish, LeavesAnExactFitAlone) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Table t = SynthModel("lambert+ggx", truth, kGrid);
  const auto [prepared, plain, polished] = FitBoth("lambert+ggx", t);
  ASSERT_FALSE(polished.Failed());
  EXPECT_EQ(polished.params, plain.params);
  EXPECT_EQ(polished.iterations, plain.iterations);
}

// With 5 % noise the polish runs, and the parameters stay near the truth: the noise, not the
// polish, sets how far.
TEST(RenderedPolish, KeepsANoisyFitNearTheTruth) {
  const std::vector<double> truth = Params("lambert+ggx", {"ggx.alpha=0.2"});
  const Table t = SynthModel("lambert+ggx", truth, Grid{45, 45, 90, ThetaHMapping::kSqrt}, 0.05);
  const auto [prepared, plain, polished] = FitBoth("lambert+ggx", t);
  ASSERT_FALSE(polished.Failed());
  EXPECT_GT(polished.iterations, plain.iterations);  // it ran
  EXPECT_GE(RenderedScoreDb(polished.metrics.rendered), RenderedScoreDb(plain.metrics.rendered));
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_NEAR(polished.params[i], truth[i], 0.02 * std::abs(truth[i]) + 1e-3)
        << polished.param_names[i] << " (unpolished " << plain.params[i] << ")";
  }
}

// The polish's own ops for a model (the engine's registry, fit/model_ops.h).
internal::ModelOps OpsOf(const std::string& model) {
  for (auto& ops : testing::AllModelOps()) {
    if (ops.name == model) return ops;
  }
  ADD_FAILURE() << model << " not registered";
  return {};
}

// The reweighting rounds (fit/rendered_polish.h): two always, then on while a round raises S
// by at least min_round_gain_db, at most `rounds`; the x returned is the best by S.
// Where the polish tests start: a lambert+ggx fit of the two-lobe table under the rel loss, its
// parameters in optimization space, and the metric's reference with its front lights alone.
struct PolishStart {
  PreparedTable prepared;  // its rendered reference has every light of the metric
  internal::ModelOps ops;
  std::vector<double> x0;
  RenderedReference front;
  bool ok = false;  // the fit converged
};

PolishStart TwoLobeTableFit() {
  const Table t = TwoLobeTable();
  FitOptions fo = LogLossUnpolished();
  fo.loss = LossKind::kRel;
  PolishStart s;
  s.prepared = PrepareTable(t, SampleOptions{}, fo);
  const FitResult plain = FitPrepared("lambert+ggx", s.prepared, fo);
  s.ok = !plain.Failed();
  s.ops = OpsOf("lambert+ggx");
  s.x0.resize(plain.params.size());
  for (std::size_t i = 0; i < s.x0.size(); ++i) s.x0[i] = s.ops.layout.ToOpt(i, plain.params[i]);
  RenderedErrorOptions front_lights;
  front_lights.light_angles_deg = {0, 30, 45, 60, 70, 80};
  front_lights.environment.samples = 0;  // the front region alone
  s.front = PrepareRenderedReference(t, front_lights);
  return s;
}

TEST(RenderedPolish, RoundsGoOnWhileTheScoreRises) {
  // Front lights only: one stage (the stages: TwoStagesNeverScoreBelowTheFrontAlone).
  const PolishStart start = TwoLobeTableFit();
  ASSERT_TRUE(start.ok);
  const internal::ModelOps& ops = start.ops;
  const std::vector<double>& x0 = start.x0;
  const RenderedReference& front = start.front;
  const auto polish = [&](int rounds, double min_gain, std::vector<double>& x) {
    internal::RenderedPolishOptions o;
    o.rounds = rounds;
    o.min_round_gain_db = min_gain;
    x = x0;
    return internal::PolishOnRendered(ops, front, o, x);
  };
  // An unreachable gain: exactly two rounds, the same bits as a cap of two.
  std::vector<double> x_two, x_inf, x_rule;
  const auto two = polish(2, 0.0, x_two);
  const auto inf = polish(6, INFINITY, x_inf);
  ASSERT_TRUE(two.ran);
  EXPECT_EQ(two.round_scores.size(), 2u);
  EXPECT_EQ(inf.round_scores.size(), 2u);
  EXPECT_EQ(x_inf, x_two);
  // The default rule: each round after the second that ran was earned by the one before it.
  const internal::RenderedPolishOptions defaults;
  const auto rule = polish(defaults.rounds, defaults.min_round_gain_db, x_rule);
  const std::vector<double>& s = rule.round_scores;
  ASSERT_GE(s.size(), 2u);
  ASSERT_LE(s.size(), static_cast<std::size_t>(defaults.rounds));
  double best = rule.score_before;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double gain = s[k] - best;
    if (k >= 1 && k + 1 < s.size()) {
      EXPECT_GE(gain, defaults.min_round_gain_db) << "round " << k;
    }
    if (k >= 1 && k + 1 == s.size() && s.size() < static_cast<std::size_t>(defaults.rounds)) {
      EXPECT_LT(gain, defaults.min_round_gain_db) << "the last round";
    }
    best = std::max(best, s[k]);
  }
  // The best round's x is returned and scored; more rounds never score lower than two.
  EXPECT_DOUBLE_EQ(rule.score_after, best);
  EXPECT_GE(rule.score_after, two.score_after);
  std::vector<double> p(x_rule.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = ops.layout.FromOpt(i, x_rule[i]);
  const RenderedError again = ScoreRendered(front, ModelBrdf(*FindModel("lambert+ggx"), p));
  EXPECT_DOUBLE_EQ(RenderedScoreDb(again), rule.score_after);
}

// With lights beyond the front, the polish climbs the front region's S first and the whole S
// from there, the rounds shared: it never ends below what the front stage alone reached, scored
// by the whole S, nor below its start.
TEST(RenderedPolish, TwoStagesNeverScoreBelowTheFrontAlone) {
  const PolishStart start = TwoLobeTableFit();
  ASSERT_TRUE(start.ok);
  const PreparedTable& prepared = start.prepared;
  const internal::ModelOps& ops = start.ops;
  const std::vector<double>& x0 = start.x0;
  const internal::RenderedPolishOptions o;
  std::vector<double> x_front = x0, x_whole = x0;
  internal::RenderedPolishOptions half = o;
  half.rounds = (o.rounds + 1) / 2;
  ASSERT_TRUE(internal::PolishOnRendered(ops, start.front, half, x_front).ran);
  const auto whole = internal::PolishOnRendered(ops, prepared.rendered, o, x_whole);
  ASSERT_TRUE(whole.ran);
  EXPECT_LE(whole.round_scores.size(), static_cast<std::size_t>(2 * half.rounds));
  EXPECT_GE(whole.score_after, whole.score_before);
  const auto score = [&](const std::vector<double>& x) {
    std::vector<double> p(x.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = ops.layout.FromOpt(i, x[i]);
    return RenderedScoreDb(
        ScoreRendered(prepared.rendered, ModelBrdf(*FindModel("lambert+ggx"), p)));
  };
  // The front stage polishes the same pixels with other block boundaries: equal to rounding
  // (LM trajectories that differ in the last bits; 1e-3 dB is below what S is reported to).
  EXPECT_GE(whole.score_after, score(x_front) - 1e-3);
  EXPECT_DOUBLE_EQ(score(x_whole), whole.score_after);
}

TEST(RenderedPolish, SameBitsForAnyThreadCount) {
  const Table t = SynthModel("lambert+ggx+ggx",
                             Params("lambert+ggx+ggx", {"ggx1.alpha=0.06", "ggx2.alpha=0.3"}), kGrid);
  FitOptions o = LogLossUnpolished();
  o.loss = LossKind::kRel;
  o.polish = PolishKind::kRendered;
  const PreparedTable prepared = PrepareTable(t, SampleOptions{}, o);
  const FitResult one = FitPrepared("lambert+ggx", prepared, o);
  o.threads = 2;
  const FitResult two = FitPrepared("lambert+ggx", prepared, o);
  ASSERT_EQ(one.params.size(), two.params.size());
  for (std::size_t i = 0; i < one.params.size(); ++i) EXPECT_EQ(one.params[i], two.params[i]);
}

}  // namespace
}  // namespace brdfit
