// The catalog and the name registry: names, parameter tables and the weight-role contract the
// fitter relies on (value linear in each kWeight parameter, without a constant term).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "models/registry.h"

namespace brdfit {
namespace {

TEST(Registry, NamesAreUniqueAndFindable) {
  std::set<std::string> names;
  for (const ModelInfo& m : AllModels()) {
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate " << m.name;
    EXPECT_EQ(FindModel(m.name), &m);
    EXPECT_FALSE(m.doc.empty()) << m.name;
    EXPECT_NE(ModelNames().find(m.name), std::string::npos);
  }
  EXPECT_EQ(FindModel("no-such-model"), nullptr);
  // The catalog the issue asks for.
  for (const char* n : {"lambert",
                        "oren-nayar",
                        "burley",
                        "oren-nayar-fujii",
                        "burley-2012",
                        "oren-nayar-fujii+ggx",
                        "burley-2012+ggx",
                        "phong",
                        "blinn-phong",
                        "ward",
                        "ward-duer",
                        "beckmann",
                        "ggx",
                        "ggx-hc",
                        "cook-torrance",
                        "lafortune",
                        "ue4",
                        "lambert+ggx",
                        "lambert+beckmann",
                        "lambert+ward",
                        "lambert+blinn-phong",
                        "lambert+cook-torrance",
                        "lambert+phong",
                        "lambert+lafortune",
                        "lambert+ggx+ggx",
                        "lambert+lafortune+lafortune",
                        "lambert+lafortune+lafortune+lafortune"}) {
    EXPECT_NE(FindModel(n), nullptr) << n;
  }
}

TEST(Registry, ParameterTablesAreConsistent) {
  for (const ModelInfo& m : AllModels()) {
    ASSERT_EQ(m.params.size(), m.param_names.size()) << m.name;
    std::set<std::string> qualified(m.param_names.begin(), m.param_names.end());
    EXPECT_EQ(qualified.size(), m.param_names.size()) << m.name << ": parameter names repeat";
    for (std::size_t i = 0; i < m.params.size(); ++i) {
      const ParamSpec& s = m.params[i];
      SCOPED_TRACE(m.name + "." + m.param_names[i]);
      EXPECT_FALSE(s.name.empty());
      EXPECT_FALSE(s.unit.empty());
      EXPECT_FALSE(s.doc.empty());
      EXPECT_LT(s.lower, s.upper);
      EXPECT_GE(s.init, s.lower);
      EXPECT_LE(s.init, s.upper);
      if (s.log_scale) {
        EXPECT_GT(s.lower, 0.0) << "log-scale parameters must be positive";
      }
    }
  }
}

// Roughness parameters named alpha reach 1e-4 (MERL lobes reach alpha ~ 0.005). The sheen's
// alpha is not a highlight's width but the fibres' spread (models/sheen.h), peaking at
// theta_h = 90 deg: at alpha = 0.01 its value at 80 deg (where the 80 deg cut-off leaves the
// last fitted cells) is 22 % of the peak, and narrower lobes would lie where no fitted cell
// is, so it stops at 0.01 (three.js clamps sheenRoughness at 0.07, alpha 0.0049).
TEST(Registry, AlphaBoundsCoverSharpLobes) {
  for (const ModelInfo& m : AllModels()) {
    for (const ParamSpec& s : m.params) {
      if (s.name == "alpha" && s.doc.starts_with("sheen alpha")) {
        EXPECT_EQ(s.lower, 0.01) << m.name;
        EXPECT_EQ(s.upper, 1.0) << m.name;
      } else if (s.name == "alpha") {
        EXPECT_LE(s.lower, 1e-4) << m.name;
        EXPECT_GE(s.upper, 1.0) << m.name;
      }
    }
  }
}

// Colour weights come as consecutive R, G, B triples; the value in channel c is linear in its
// weight, with no constant term, and does not depend on the other channels' weights.
TEST(Registry, WeightRolesAreLinearWithoutConstantTerm) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (const ModelInfo& m : AllModels()) {
    for (std::size_t i = 0; i < m.params.size(); ++i) {
      if (m.params[i].role == ParamRole::kWeightR) {
        ASSERT_LT(i + 2, m.params.size()) << m.name;
        EXPECT_EQ(m.params[i + 1].role, ParamRole::kWeightG) << m.name;
        EXPECT_EQ(m.params[i + 2].role, ParamRole::kWeightB) << m.name;
      }
    }
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> p;
      for (const auto& s : m.params) {
        const double t = u(rng);
        p.push_back(s.log_scale ? s.lower * std::pow(s.upper / s.lower, t)
                                : s.lower + t * (s.upper - s.lower));
      }
      const Geometry g =
          MakeGeometry(FromSpherical(0.2 + u(rng), 0.0), FromSpherical(0.2 + u(rng), 3.0 * u(rng)));
      double base[3];
      m.eval(p.data(), g, base);
      for (std::size_t i = 0; i < m.params.size(); ++i) {
        const ParamRole role = m.params[i].role;
        if (role == ParamRole::kShape) continue;
        const int ch = role == ParamRole::kWeightR ? 0 : role == ParamRole::kWeightG ? 1 : 2;
        std::vector<double> q = p;
        q[i] = 0.0;
        double zero[3];
        m.eval(q.data(), g, zero);
        q[i] = 2.0 * p[i];
        double twice[3];
        m.eval(q.data(), g, twice);
        // f = w * a + rest: rest = f(0), and f(2w) - f(0) = 2 (f(w) - f(0)).
        const double scale = std::max(std::abs(base[ch]), 1e-300);
        EXPECT_NEAR(twice[ch] - zero[ch], 2.0 * (base[ch] - zero[ch]), 1e-12 * scale)
            << m.name << "." << m.param_names[i];
        for (int c = 0; c < 3; ++c) {
          if (c != ch) {
            EXPECT_EQ(zero[c], base[c]) << m.name << "." << m.param_names[i];
          }
        }
      }
      // All weights zero: the model is zero (no constant term), unless it has no weights.
      std::vector<double> q = p;
      bool has_weights = false;
      for (std::size_t i = 0; i < m.params.size(); ++i) {
        if (m.params[i].role != ParamRole::kShape) {
          q[i] = 0.0;
          has_weights = true;
        }
      }
      if (has_weights) {
        double f[3];
        m.eval(q.data(), g, f);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(f[c], 0.0) << m.name;
      }
    }
  }
}

// Models the fitter can solve linearly must declare their weights (the ones that are linear).
TEST(Registry, EveryModelButUe4AndGgxF0HasWeights) {
  for (const ModelInfo& m : AllModels()) {
    int weights = 0;
    for (const auto& s : m.params) weights += s.role != ParamRole::kShape;
    if (m.name == "ue4") {
      EXPECT_EQ(weights, 0) << "ue4's base colour also sets F0: not a linear weight";
    } else if (m.name == "ggx-f0" || m.name == "lambert+ggx-f0") {
      EXPECT_EQ(weights, 0) << m.name << ": ggx-f0 has no weight, a constant term of the sum";
    } else {
      EXPECT_GE(weights, 3) << m.name;
    }
  }
}

TEST(Registry, GgxInterfaceIsStable) {
  const ModelInfo* m = FindModel("ggx");
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->params.size(), 4u);
  EXPECT_EQ(m->params[0].name, "ks_r");
  EXPECT_EQ(m->params[3].name, "alpha");
  const ModelInfo* s = FindModel("lambert+ggx+ggx");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->param_names[6], "ggx1.alpha");
  EXPECT_EQ(s->param_names[10], "ggx2.alpha");
}

}  // namespace
}  // namespace brdfit
