#include "fit/grid_init.h"

#include <ceres/jet.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/box_lsq.h"

namespace brdfit::internal {

namespace {
// NaN costs sort last.
bool Less(double a, double b) {
  if (std::isnan(b)) return !std::isnan(a);
  return a < b;
}
}  // namespace

// Grid values of one shape parameter: geometric for log_scale parameters, else uniform,
// endpoints included.
std::vector<double> ShapeGridValues(const ParamSpec& s, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.5 : static_cast<double>(i) / (n - 1);
    v[i] = s.log_scale ? std::exp(std::log(s.lower) + t * (std::log(s.upper) - std::log(s.lower)))
                       : s.lower + t * (s.upper - s.lower);
  }
  return v;
}

// Points per shape dimension: 48 in 1-D (ratio 1.22 between alphas over [1e-4, 1]), 14 in
// 2-D, 7 in 3-D, then about 1000^(1/d) with at least 3.
int ShapeGridSize(std::size_t dims) {
  if (dims <= 1) return 48;
  if (dims == 2) return 14;
  if (dims == 3) return 7;
  return std::max(3, static_cast<int>(std::floor(std::pow(1000.0, 1.0 / dims))));
}

GridInitializer::GridInitializer(const Samples& s, const LossData& l, const ParamLayout& layout,
                                 EvalFn eval, const ceres::LossFunction* robust)
    : s_(s), l_(l), layout_(layout), eval_(eval), robust_(robust) {
  const std::size_t n = s.NumObservations();
  // Linearization at the data.
  w_data_.resize(3 * n);
  y_data_.resize(3 * n);
  for (std::size_t o = 0; o < n; ++o) {
    for (int ch = 0; ch < 3; ++ch) {
      const double m = s.value[3 * o + ch];
      const double d = l.inv[3 * o + ch] * Slope(m * l.mult[o]) * l.mult[o];
      w_data_[3 * o + ch] = l.sqrt_w[o] * l.sqrt_w[o] * d * d;
      y_data_[3 * o + ch] = m;
    }
  }
}

std::vector<InitCandidate> GridInitializer::Run(int keep) {
  const std::size_t dims = layout_.shape.size();
  const int per_dim = ShapeGridSize(dims);
  std::vector<std::vector<double>> values;
  for (int idx : layout_.shape) values.push_back(ShapeGridValues(layout_.specs[idx], per_dim));

  std::vector<double> p(layout_.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = layout_.specs[i].init;
  std::vector<InitCandidate> all;
  std::vector<int> odo(dims, 0);
  while (true) {
    for (std::size_t d = 0; d < dims; ++d) p[layout_.shape[d]] = values[d][odo[d]];
    all.push_back(EvaluatePoint(p));
    std::size_t d = 0;
    while (d < dims && ++odo[d] == per_dim) odo[d++] = 0;
    if (d == dims) break;
  }
  // Stable order: ties keep grid order, so results do not depend on the sort algorithm.
  std::stable_sort(all.begin(), all.end(), [](const InitCandidate& a, const InitCandidate& b) {
    return Less(a.cost, b.cost);
  });
  // Refine the best few: pattern search over the shape parameters, then Gauss-Newton on the
  // weights, then rescore.
  const std::size_t refine = std::min<std::size_t>(all.size(), std::max(keep, 1) + 1);
  all.resize(refine);
  std::vector<double> spacing;
  for (int idx : layout_.shape) {
    spacing.push_back((layout_.upper_opt[idx] - layout_.lower_opt[idx]) / std::max(per_dim - 1, 1));
  }
  for (auto& c : all) {
    PatternSearch(&c, spacing);
    ComputeBasis(c.params);
    for (int it = 0; it < 2; ++it) Relinearize(&c.params);
    c.cost = Score(c.params);
  }
  std::stable_sort(all.begin(), all.end(), [](const InitCandidate& a, const InitCandidate& b) {
    return Less(a.cost, b.cost);
  });
  all.resize(std::min<std::size_t>(all.size(), std::max(keep, 1)));
  return all;
}

// d T(x) / dx of the loss transform, through a Jet (same guards as the loss).
InitCandidate GridInitializer::EvaluatePoint(std::vector<double> p) {
  ComputeBasis(p);
  SolveWeights(w_data_, y_data_, &p);
  const double cost = Score(p);
  return {std::move(p), cost};
}

// Compass search (Kolda, Lewis, Torczon 2003, "Optimization by Direct Search", SIAM Review
// 45(3), §3): +-step along each shape coordinate (log for log_scale parameters), accept any
// improvement, halve the steps when none; six halvings from the grid spacing.
void GridInitializer::PatternSearch(InitCandidate* c, const std::vector<double>& spacing) {
  constexpr int kLevels = 6;
  constexpr int kMaxEvaluations = 200;
  std::vector<double> step = spacing;
  int evaluations = 0;
  for (int level = 0; level < kLevels && evaluations < kMaxEvaluations; ++level) {
    bool improved = true;
    while (improved && evaluations < kMaxEvaluations) {
      improved = false;
      for (std::size_t d = 0; d < layout_.shape.size(); ++d) {
        const int idx = layout_.shape[d];
        for (const double sign : {-1.0, 1.0}) {
          const double x0 = layout_.ToOpt(idx, c->params[idx]);
          const double x =
              std::clamp(x0 + sign * step[d], layout_.lower_opt[idx], layout_.upper_opt[idx]);
          if (x == x0) continue;
          std::vector<double> trial = c->params;
          trial[idx] = layout_.FromOpt(idx, x);
          InitCandidate t = EvaluatePoint(std::move(trial));
          ++evaluations;
          if (Less(t.cost, c->cost)) {
            *c = std::move(t);
            improved = true;
          }
        }
      }
    }
    for (double& s : step) s *= 0.5;
  }
}

double GridInitializer::Slope(double x) const {
  const ceres::Jet<double, 1> j(x, 0);
  return LossTransform(l_.kind, j).v[0];
}

// basis_[(s * K + k) * 3 + ch]: lobe k's value in channel ch with unit weights.
void GridInitializer::ComputeBasis(const std::vector<double>& p_in) {
  const std::size_t K = layout_.lobes.size(), ns = s_.NumSamples();
  basis_.assign(ns * K * 3, 0.0);
  std::vector<double> p = p_in;
  for (const auto& lobe : layout_.lobes) {
    for (int idx : lobe) p[idx] = 0.0;
  }
  for (std::size_t k = 0; k < K; ++k) {
    for (int idx : layout_.lobes[k]) p[idx] = 1.0;
    for (std::size_t s = 0; s < ns; ++s) {
      double rgb[3];
      eval_(p.data(), s_.geometry[s], rgb);
      for (int ch = 0; ch < 3; ++ch) basis_[(s * K + k) * 3 + ch] = rgb[ch];
    }
    for (int idx : layout_.lobes[k]) p[idx] = 0.0;
  }
}

double GridInitializer::Predict(const std::vector<double>& p, std::size_t s, int ch) const {
  const std::size_t K = layout_.lobes.size();
  double f = 0;
  for (std::size_t k = 0; k < K; ++k) f += p[layout_.lobes[k][ch]] * basis_[(s * K + k) * 3 + ch];
  return f;
}

// Per channel: min sum W (sum_k a_k B_k - y)^2 within the weights' bounds.
void GridInitializer::SolveWeights(const std::vector<double>& w, const std::vector<double>& y,
                                   std::vector<double>* p) const {
  const int K = static_cast<int>(layout_.lobes.size());
  if (K == 0) return;
  for (int ch = 0; ch < 3; ++ch) {
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(K, K);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(K), lo(K), hi(K);
    Eigen::VectorXd basis(K);
    for (std::size_t s = 0; s < s_.NumSamples(); ++s) {
      for (int k = 0; k < K; ++k) basis[k] = basis_[(s * K + k) * 3 + ch];
      double ws = 0, wy = 0;
      for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
        ws += w[3 * o + ch];
        wy += w[3 * o + ch] * y[3 * o + ch];
      }
      N.noalias() += ws * basis * basis.transpose();
      b.noalias() += wy * basis;
    }
    for (int k = 0; k < K; ++k) {
      const ParamSpec& spec = layout_.specs[layout_.lobes[k][ch]];
      lo[k] = spec.lower;
      hi[k] = spec.upper;
    }
    const Eigen::VectorXd a = BoxLeastSquares(N, b, lo, hi);
    for (int k = 0; k < K; ++k) (*p)[layout_.lobes[k][ch]] = a[k];
  }
}

// One Gauss-Newton step on the weights (IRLS weights for robust losses).
void GridInitializer::Relinearize(std::vector<double>* p) {
  const std::size_t n = s_.NumObservations();
  std::vector<double> w(3 * n, 0.0), y(3 * n, 0.0);
  for (std::size_t s = 0; s < s_.NumSamples(); ++s) {
    for (int ch = 0; ch < 3; ++ch) {
      const double f0 = Predict(*p, s, ch);
      for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
        const double c = l_.mult[o], inv = l_.inv[3 * o + ch];
        const double e0 = inv * (LossTransform(l_.kind, f0 * c) - l_.target[3 * o + ch]);
        const double d = inv * Slope(f0 * c) * c;
        if (!(std::abs(d) > 0) || !std::isfinite(e0)) continue;
        double irls = 1.0;
        if (robust_ != nullptr) {
          double rho[3];
          robust_->Evaluate(e0 * e0, rho);
          irls = std::max(rho[1], 0.0);
        }
        w[3 * o + ch] = l_.sqrt_w[o] * l_.sqrt_w[o] * d * d * irls;
        y[3 * o + ch] = f0 - e0 / d;
      }
    }
  }
  SolveWeights(w, y, p);
}

// The loss (robust function included) at p, from the basis.
double GridInitializer::Score(const std::vector<double>& p) const {
  double cost = 0;
  for (std::size_t s = 0; s < s_.NumSamples(); ++s) {
    for (int ch = 0; ch < 3; ++ch) {
      const double f = Predict(p, s, ch);
      for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
        const double e =
            l_.inv[3 * o + ch] * (LossTransform(l_.kind, f * l_.mult[o]) - l_.target[3 * o + ch]);
        double term = e * e;
        if (robust_ != nullptr) {
          double rho[3];
          robust_->Evaluate(term, rho);
          term = rho[0];
        }
        cost += l_.sqrt_w[o] * l_.sqrt_w[o] * term;
      }
    }
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace brdfit::internal
