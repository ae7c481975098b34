// Synthetic tables (core/synth.h): what the model sees, exact hole counts, the statistics of the
// noise, determinism, and every registered model at its defaults and bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/synth.h"
#include "models/registry.h"

namespace brdfit {
namespace {

const Grid kSmall{18, 16, 32, ThetaHMapping::kSqrt};

BrdfEvalFn ModelEval(const ModelInfo& m, std::vector<double> p) {
  return [&m, p = std::move(p)](const Geometry& g, double rgb[3]) { m.eval(p.data(), g, rgb); };
}

std::size_t CountAboveHorizon(const Grid& g) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < g.NumCells(); ++i) n += g.CellAboveHorizon(i);
  return n;
}

TEST(Synth, ModelSeesTheCellCentreAboveTheHorizonOnly) {
  std::size_t calls = 0;
  auto eval = [&](const Geometry& g, double rgb[3]) {
    ++calls;
    EXPECT_GT(g.cos_i, 0);
    EXPECT_GT(g.cos_o, 0);
    const HalfDiffAngles a = ToHalfDiff(g.wi, g.wo);
    const std::size_t idx = kSmall.CellOf(a);
    const HalfDiffAngles c = kSmall.CellCentre(idx);
    // Round trip through directions: atan2/acos cost ~1e-12 rad, far inside the bin.
    EXPECT_NEAR(a.theta_h, c.theta_h, 1e-9);
    EXPECT_NEAR(a.theta_d, c.theta_d, 1e-9);
    EXPECT_NEAR(a.phi_d, c.phi_d, 1e-9);
    rgb[0] = rgb[1] = rgb[2] = static_cast<double>(idx);  // tag the value with its cell
  };
  const Table t = SynthesizeTable(kSmall, eval, {});
  EXPECT_EQ(calls, CountAboveHorizon(kSmall));
  for (std::size_t i = 0; i < kSmall.NumCells(); ++i) {
    ASSERT_EQ(t.valid[i], kSmall.CellAboveHorizon(i)) << i;
    if (t.valid[i]) {
      ASSERT_EQ(t.Value(i)[0], static_cast<double>(i));
    }
  }
}

TEST(Synth, NoiselessTableIsTheModelAtCellCentres) {
  const ModelInfo* m = FindModel("lambert+ggx");
  ASSERT_NE(m, nullptr);
  const std::vector<double> p = m->DefaultParams();
  const Table t = SynthesizeTable(kSmall, ModelEval(*m, p), {});
  for (std::size_t i = 0; i < kSmall.NumCells(); ++i) {
    if (!t.valid[i]) continue;
    double want[3];
    m->eval(p.data(), MakeGeometry(kSmall.CellCentre(i), 0.0), want);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(t.Value(i)[c], want[c]);
  }
  EXPECT_EQ(t.provenance.generator, "brdfit synth");
  EXPECT_EQ(t.provenance.source, "synthetic");
}

TEST(Synth, SameSeedSameTableOtherSeedOtherTable) {
  const SynthOptions a{0.1, 0.3, 7}, b{0.1, 0.3, 8};
  auto constant = [](const Geometry&, double rgb[3]) { rgb[0] = rgb[1] = rgb[2] = 0.25; };
  const Table t1 = SynthesizeTable(kSmall, constant, a), t2 = SynthesizeTable(kSmall, constant, a);
  const Table t3 = SynthesizeTable(kSmall, constant, b);
  EXPECT_EQ(t1, t2);
  EXPECT_NE(t1.valid, t3.valid);
  EXPECT_NE(t1.rgb, t3.rgb);
  EXPECT_EQ(t1.provenance.seed, 7u);
  EXPECT_EQ(t1.provenance.noise, 0.1);
  EXPECT_EQ(t1.provenance.missing_fraction, 0.3);
}

TEST(Synth, MissingFractionRemovesExactlyThatShareUniformly) {
  const Grid g{40, 40, 80, ThetaHMapping::kLinear};
  auto constant = [](const Geometry&, double rgb[3]) { rgb[0] = rgb[1] = rgb[2] = 1.0; };
  const std::size_t above = CountAboveHorizon(g);
  for (const double f : {0.0, 0.001, 0.3, 1.0}) {
    SynthReport r;
    const Table t = SynthesizeTable(g, constant, {0.0, f, 3}, &r);
    const auto k = static_cast<std::size_t>(std::llround(f * above));
    EXPECT_EQ(r.removed, k) << f;
    EXPECT_EQ(t.CountValid(), above - k) << f;
    EXPECT_EQ(r.below_horizon, g.NumCells() - above);
  }
  // Uniform choice: the holes' share in each theta_h slice is near 0.3 (binomial sd ~1.4 %).
  SynthReport r;
  const Table t = SynthesizeTable(g, constant, {0.0, 0.3, 4}, &r);
  for (int ih = 0; ih < g.n_theta_h; ih += 5) {
    std::size_t above_slice = 0, holes = 0;
    for (int id = 0; id < g.n_theta_d; ++id) {
      for (int ip = 0; ip < g.n_phi_d; ++ip) {
        const std::size_t i = g.Index(ih, id, ip);
        if (!g.CellAboveHorizon(i)) continue;
        ++above_slice;
        holes += !t.valid[i];
      }
    }
    EXPECT_NEAR(static_cast<double>(holes) / above_slice, 0.3, 0.06) << ih;
  }
}

// Log-normal noise: log(noisy / clean) ~ N(0, sigma^2), independent across channels.
TEST(Synth, NoiseIsLogNormalWithTheRequestedSigma) {
  const Grid g{30, 30, 60, ThetaHMapping::kSqrt};
  auto eval = [](const Geometry& geo, double rgb[3]) {
    rgb[0] = 1 + geo.cos_i, rgb[1] = 2.0, rgb[2] = 0.5 * geo.cos_o;
  };
  const double sigma = 0.05;
  const Table clean = SynthesizeTable(g, eval, {});
  const Table noisy = SynthesizeTable(g, eval, {sigma, 0.0, 99});
  std::array<double, 3> s1{}, s2{}, within{};
  double cross = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < g.NumCells(); ++i) {
    if (!clean.valid[i]) continue;
    ASSERT_TRUE(noisy.valid[i]);
    double z[3];
    for (int c = 0; c < 3; ++c) {
      z[c] = std::log(noisy.Value(i)[c] / clean.Value(i)[c]) / sigma;
      s1[c] += z[c];
      s2[c] += z[c] * z[c];
      within[c] += std::fabs(z[c]) < 1;
    }
    cross += z[0] * z[1];
    ++n;
  }
  const double tol = 5.0 / std::sqrt(static_cast<double>(n));  // 5 standard errors
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s1[c] / n, 0.0, tol);
    EXPECT_NEAR(s2[c] / n, 1.0, 5.0 * std::sqrt(2.0 / n));
    EXPECT_NEAR(within[c] / n, 0.682689, tol);  // P(|z| < 1) of a standard normal
  }
  EXPECT_NEAR(cross / n, 0.0, tol);
}

TEST(Synth, GeneratorMomentsMatchUniformAndNormal) {
  const int n = 200000;
  double su = 0, sn = 0, sn2 = 0, sn4 = 0, umin = 1, umax = 0;
  for (int i = 0; i < n; ++i) {
    const double u = SynthUniform(12, 3, i), z = SynthNormal(12, 3, i);
    su += u;
    umin = std::min(umin, u);
    umax = std::max(umax, u);
    sn += z;
    sn2 += z * z;
    sn4 += z * z * z * z;
  }
  EXPECT_GT(umin, 0.0);
  EXPECT_LT(umax, 1.0);
  EXPECT_NEAR(su / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(sn / n, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(sn2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sn4 / n, 3.0, 5 * std::sqrt(96.0 / n));  // E z^4 = 3, Var z^4 = 96
  EXPECT_NE(SynthUniform(1, 0, 0), SynthUniform(2, 0, 0));
  EXPECT_NE(SynthUniform(1, 0, 0), SynthUniform(1, 1, 0));
}

TEST(Synth, BadModelValuesAreMaskedAndCountedNotClamped) {
  SynthReport r;
  const Table t = SynthesizeTable(
      kSmall,
      [](const Geometry& g, double rgb[3]) {
        rgb[0] = rgb[1] = rgb[2] = 1.0;
        if (g.cos_i < 0.2) rgb[1] = -0.1;
        if (g.cos_o < 0.1) rgb[2] = std::nan("");
      },
      {}, &r);
  EXPECT_GT(r.negative, 0u);
  EXPECT_GT(r.non_finite, 0u);
  EXPECT_EQ(t.CountValid() + r.negative + r.non_finite + r.below_horizon, kSmall.NumCells());
}

TEST(Synth, RejectsBadOptions) {
  auto one = [](const Geometry&, double rgb[3]) { rgb[0] = rgb[1] = rgb[2] = 1.0; };
  EXPECT_THROW(SynthesizeTable(kSmall, one, {-0.1, 0, 0}), std::invalid_argument);
  EXPECT_THROW(SynthesizeTable(kSmall, one, {0, 1.5, 0}), std::invalid_argument);
  EXPECT_THROW(SynthesizeTable(kSmall, one, {NAN, 0, 0}), std::invalid_argument);
}

// Every model the registry knows (models/catalog.h grows; this test follows it) gives a finite,
// non-negative table at its defaults and at the corners of its bounds.
TEST(Synth, EveryRegisteredModelGivesAFiniteNonNegativeTable) {
  ASSERT_FALSE(AllModels().empty());
  const std::size_t above = CountAboveHorizon(kSmall);
  for (const ModelInfo& m : AllModels()) {
    std::map<std::string, std::vector<double>> settings = {{"defaults", m.DefaultParams()}};
    for (const auto& s : m.params) {
      settings["lower bounds"].push_back(s.lower);
      settings["upper bounds"].push_back(s.upper);
    }
    for (const auto& [what, p] : settings) {
      SynthReport r;
      const Table t = SynthesizeTable(kSmall, ModelEval(m, p), {}, &r);
      EXPECT_EQ(r.non_finite, 0u) << m.name << " at " << what;
      EXPECT_EQ(r.negative, 0u) << m.name << " at " << what;
      EXPECT_EQ(t.CountValid(), above) << m.name << " at " << what;
      for (std::size_t i = 0; i < kSmall.NumCells(); ++i) {
        if (!t.valid[i]) continue;
        for (int c = 0; c < 3; ++c) {
          ASSERT_TRUE(std::isfinite(t.Value(i)[c]) && t.Value(i)[c] >= 0)
              << m.name << " at " << what << ", cell " << i;
        }
      }
    }
    // Defaults are meant to look like a material: something is reflected.
    const Table t = SynthesizeTable(kSmall, ModelEval(m, m.DefaultParams()), {});
    double total = 0;
    for (std::size_t i = 0; i < kSmall.NumCells(); ++i) {
      if (t.valid[i]) total += t.Value(i)[0] + t.Value(i)[1] + t.Value(i)[2];
    }
    EXPECT_GT(total, 0) << m.name;
  }
}

TEST(Synth, NoiseAndHolesOnAnExistingTable) {
  Table t = Table::Empty(kSmall);
  for (std::size_t i = 0; i < kSmall.NumCells(); i += 2) {
    t.valid[i] = 1;
    t.Value(i)[0] = t.Value(i)[1] = t.Value(i)[2] = 2.0;
  }
  const std::size_t valid = t.CountValid();
  SynthReport r;
  ApplyNoiseAndHoles(t, {0.2, 0.5, 1}, &r);
  EXPECT_EQ(r.removed, valid / 2);
  EXPECT_EQ(t.CountValid(), valid - valid / 2);
  for (std::size_t i = 1; i < kSmall.NumCells(); i += 2) ASSERT_FALSE(t.valid[i]);
  EXPECT_EQ(t.provenance.noise, 0.2);
}

}  // namespace
}  // namespace brdfit
