// Derivative checks shared by test_gradients_single.cc and test_gradients_sums.cc (the Ceres
// autodiff instantiations of the model tests, split in two TUs to compile in parallel):
// ceres::GradientChecker (autodiff Jacobian against Ridders numeric differentiation) at random
// valid points, and finite values and derivatives at the singular corners (theta_h = 0,
// alpha = 1e-4, 89.9 degree incidence, retro-reflection, every bound).
#pragma once

#include <ceres/ceres.h>
#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "models/catalog.h"

namespace brdfit::test {

constexpr double kGrazing = 89.9 * kPi / 180.0;

// f(p) / f(p0) per channel, with every parameter in its own block. Both matter for the
// numeric side of the check: Ridders' steps are relative to each block's magnitude (one block
// would step alpha = 1e-3 by 1e-3 x ks = 0.5), and its convergence test is absolute (values
// of 1e-114 in a lobe's tail would pass after the first, crude step).
template <class M>
struct ScaledResidual {
  Geometry g;
  std::array<double, 3> scale;
  template <class T>
  bool operator()(T const* const* blocks, T* rgb) const {
    T p[kNumParams<M>];
    for (std::size_t i = 0; i < kNumParams<M>; ++i) p[i] = blocks[i][0];
    M::Eval(p, g, rgb);
    for (int c = 0; c < 3; ++c) rgb[c] = rgb[c] / scale[c];
    return true;
  }
};

template <class M>
std::unique_ptr<ceres::CostFunction> MakeCost(const Geometry& g, const std::vector<double>& p) {
  double f[3];
  M::Eval(p.data(), g, f);
  auto* functor = new ScaledResidual<M>{g, {}};
  for (int c = 0; c < 3; ++c) functor->scale[c] = f[c] > 1e-300 ? f[c] : 1.0;
  auto cost = std::make_unique<ceres::DynamicAutoDiffCostFunction<ScaledResidual<M>, 4>>(functor);
  for (std::size_t i = 0; i < kNumParams<M>; ++i) cost->AddParameterBlock(1);
  cost->SetNumResiduals(3);
  return cost;
}

// A point strictly inside the bounds (log-uniform for log-scale parameters), at least 1 % of
// the range (or of the decades) away from each bound so that numeric steps stay inside.
template <class M>
std::vector<double> RandomParams(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.01, 0.99);
  std::vector<double> p;
  for (const ParamSpec& s : M::kParams) {
    const double t = u(rng);
    p.push_back(s.log_scale ? s.lower * std::pow(s.upper / s.lower, t)
                            : s.lower + t * (s.upper - s.lower));
  }
  return p;
}

inline Geometry RandomGeometry(std::mt19937& rng) {
  std::uniform_real_distribution<double> t(0.05, 1.45), p(0.0, 2 * kPi);
  return MakeGeometry(FromSpherical(t(rng), p(rng)), FromSpherical(t(rng), p(rng)));
}

// True when the point is within a numeric-difference step of a kink of the model in its
// parameters (Lafortune's max(0, x)^n at x = 0): central differences straddle the kink there.
template <class M>
bool NearParameterKink(const std::vector<double>& p, const Geometry& g) {
  if constexpr (requires { M::kParams[3].name; }) {
    if (ModelName<M>().find("lafortune") != std::string::npos) {
      for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        if (M::kParams[i].name == "cxy") {
          const double base = p[i] * (g.wi.x * g.wo.x + g.wi.y * g.wo.y) + g.wi.z * g.wo.z;
          if (std::abs(base) < 1e-3) return true;
        }
      }
    }
  }
  return false;
}

template <class M>
void CheckGradients(int points) {
  std::mt19937 rng(1234);
  // GradientChecker differentiates numerically with Ridders' method. From its default first
  // step (1e-2 |p|) Ceres 2.1's extrapolation diverges on sharp lobes, whose log changes by
  // O(100) over that step: exp(-tan^2 / alpha^2) at alpha = 0.14 gives -1e43 instead of 1819,
  // Cook-Torrance at alpha = 0.002 -6e257 instead of 5.6e5 (plain central differences agree
  // with the Jets there to 1e-6); it also stops at a 3.5e-4 error on Oren-Nayar's A(sigma).
  // Starting from 1e-8 |p| it converges for every model.
  ceres::NumericDiffOptions options;
  options.ridders_relative_initial_step_size = 1e-8;
  int checked = 0, floored = 0;
  for (int k = 0; k < points; ++k) {
    const std::vector<double> p = RandomParams<M>(rng);
    const Geometry g = RandomGeometry(rng);
    if (NearParameterKink<M>(p, g)) continue;
    auto cost = MakeCost<M>(g, p);
    ceres::GradientChecker checker(
        cost.get(), static_cast<const std::vector<const ceres::Manifold*>*>(nullptr), options);
    ceres::GradientChecker::ProbeResults results;
    std::vector<const double*> blocks;
    for (const double& v : p) blocks.push_back(&v);
    if (!checker.Probe(blocks.data(), 1e-6, &results)) {
      ++floored;
      // Probe compares every entry relatively. An entry that is tiny next to the (scaled to 1)
      // residual — a lobe's derivative inside a sum dominated by another lobe — cannot be
      // resolved numerically to 1e-6 relative; accept it when the difference, expressed as the
      // change of the residual for a 100 % change of the parameter, is below 1e-7.
      bool ok = results.return_value;
      for (std::size_t b = 0; b < p.size(); ++b)
        for (int c = 0; c < 3; ++c) {
          const double a = results.jacobians[b](c, 0), n = results.numeric_jacobians[b](c, 0);
          const double diff = std::abs(a - n);
          if (diff > 1e-6 * std::max(std::abs(a), std::abs(n)) && diff * std::abs(p[b]) > 1e-7) {
            ok = false;
          }
        }
      EXPECT_TRUE(ok) << ModelName<M>() << " at wi (" << g.wi.x << ", " << g.wi.y << ", " << g.wi.z
                      << ") wo (" << g.wo.x << ", " << g.wo.y << ", " << g.wo.z
                      << "): " << results.error_log;
    }
    ++checked;
  }
  EXPECT_GE(checked, points * 9 / 10) << ModelName<M>();
  if (floored > 0) {
    std::printf("  %-38s %d of %d points needed the absolute floor\n", ModelName<M>().c_str(),
                floored, checked);
  }
}

// The corners where naive forms divide by zero or lose all digits.
inline std::vector<Geometry> SingularGeometries() {
  std::vector<Geometry> out;
  out.push_back(MakeGeometry(FromSpherical(0, 0), FromSpherical(0, 0)));           // all normal
  out.push_back(MakeGeometry(FromSpherical(0.6, 0), FromSpherical(0.6, kPi)));     // th_h = 0
  out.push_back(MakeGeometry(FromSpherical(0.6, 1), FromSpherical(0.6, 1)));       // retro
  out.push_back(MakeGeometry(FromSpherical(kGrazing, 0), FromSpherical(0.3, 2)));  // grazing in
  out.push_back(MakeGeometry(FromSpherical(0.3, 0), FromSpherical(kGrazing, 2)));  // grazing out
  out.push_back(MakeGeometry(FromSpherical(kGrazing, 0), FromSpherical(kGrazing, kPi)));
  out.push_back(MakeGeometry(FromSpherical(kGrazing, 0), FromSpherical(kGrazing, 0)));
  out.push_back(MakeGeometry(FromSpherical(kGrazing, 0), FromSpherical(kGrazing, kPi / 2)));
  out.push_back(MakeGeometry(FromSpherical(1e-7, 0), FromSpherical(1e-7, kPi)));
  return out;
}

// Parameter vectors at the corners: defaults; every shape parameter at its lower bound, at its
// upper bound; "alpha" parameters at 1e-4 with the rest at defaults.
template <class M>
std::vector<std::vector<double>> CornerParams() {
  std::vector<double> defaults, lower, upper, sharp;
  for (const ParamSpec& s : M::kParams) {
    const bool weight = s.role != ParamRole::kShape;
    defaults.push_back(s.init);
    lower.push_back(weight ? s.init : s.lower);
    upper.push_back(s.upper);
    sharp.push_back(s.name == "alpha" ? 1e-4 : s.init);
  }
  return {defaults, lower, upper, sharp};
}

template <class M>
void CheckFiniteAtCorners() {
  constexpr int N = kNumParams<M>;
  using J = ceres::Jet<double, N>;
  for (const auto& p : CornerParams<M>()) {
    for (const Geometry& g : SingularGeometries()) {
      J jp[N];
      for (int i = 0; i < N; ++i) jp[i] = J(p[i], i);
      J rgb[3];
      M::Eval(jp, g, rgb);
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(rgb[c].a)) << ModelName<M>() << " cos_i " << g.cos_i;
        ASSERT_GE(rgb[c].a, 0.0) << ModelName<M>();
        for (int i = 0; i < N; ++i) {
          ASSERT_TRUE(std::isfinite(rgb[c].v[i]))
              << ModelName<M>() << " d/d" << M::kParams[i].name << " at cos_i " << g.cos_i
              << " cos_o " << g.cos_o << " cos_h " << g.cos_h << " p[" << i << "] = " << p[i];
        }
      }
    }
  }
}

// The Jet value equals the double value (the same template serves both).
template <class M>
void CheckJetValueEqualsDouble() {
  std::mt19937 rng(99);
  constexpr int N = kNumParams<M>;
  using J = ceres::Jet<double, N>;
  for (int k = 0; k < 20; ++k) {
    const auto p = RandomParams<M>(rng);
    const Geometry g = RandomGeometry(rng);
    J jp[N];
    for (int i = 0; i < N; ++i) jp[i] = J(p[i], i);
    J jrgb[3];
    double rgb[3];
    M::Eval(jp, g, jrgb);
    M::Eval(p.data(), g, rgb);
    // Jet divides by a double as a multiplication by its inverse: last-bit differences.
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(jrgb[c].a, rgb[c], 1e-14 * std::abs(rgb[c])) << ModelName<M>();
    }
  }
}

// All three checks for every catalog model M with IsSum<M> == kSums.
template <class M>
inline constexpr bool kIsSum = requires {
  M::kNumLobes;
};

template <bool kSums>
void CheckCatalogDerivatives() {
  int checked = 0, expected = 0;
  ForEachModel([&](auto m) {
    using M = typename decltype(m)::type;
    expected += (ModelName<M>().find('+') != std::string::npos) == kSums;
    if constexpr (kIsSum<M> == kSums) {
      SCOPED_TRACE(ModelName<M>());
      CheckGradients<M>(40);
      CheckFiniteAtCorners<M>();
      CheckJetValueEqualsDouble<M>();
      ++checked;
    }
  });
  EXPECT_EQ(checked, expected);
  EXPECT_GT(checked, 0);
}

}  // namespace brdfit::test
