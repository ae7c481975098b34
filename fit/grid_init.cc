#include "fit/grid_init.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fit/box_lsq.h"
#include "fit/residual.h"

namespace brdfit::internal {

namespace {
// NaN costs sort last.
bool Less(double a, double b) {
  if (std::isnan(b)) return !std::isnan(a);
  return a < b;
}
}  // namespace

ShapeStarts MakeShapeStarts(const ParamLayout& layout, const std::vector<int>& dims_idx,
                            bool coarse) {
  const std::size_t dims = dims_idx.size();
  ShapeStarts out;
  auto at = [&](std::size_t d, double t) {  // t in [0, 1] -> parameter value
    const int idx = dims_idx[d];
    return layout.FromOpt(
        idx, layout.lower_opt[idx] + t * (layout.upper_opt[idx] - layout.lower_opt[idx]));
  };
  if (dims == 0) {
    out.points.assign(1, {});
  } else if (dims <= 2) {
    const int n = dims == 1 ? (coarse ? 24 : 48) : (coarse ? 8 : 14);
    std::vector<int> odo(dims, 0);
    while (true) {
      std::vector<double> point(dims);
      for (std::size_t d = 0; d < dims; ++d) {
        point[d] = at(d, static_cast<double>(odo[d]) / (n - 1));
      }
      out.points.push_back(point);
      std::size_t d = 0;
      while (d < dims && ++odo[d] == n) odo[d++] = 0;
      if (d == dims) break;
    }
    out.spacing.assign(dims, 1.0 / (n - 1));
  } else {
    // Halton 1960 points: every coordinate takes as many distinct values as there are points
    // (a product grid of the same size would give each only n^(1/d)).
    const int n = coarse ? 64 : 343;
    constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
    for (int i = 1; i <= n; ++i) {
      std::vector<double> point(dims);
      for (std::size_t d = 0; d < dims; ++d) {
        const int base = kPrimes[d % 16] + (d >= 16 ? 58 : 0);
        double f = 1.0, t = 0.0;
        for (int k = i; k > 0; k /= base) {
          f /= base;
          t += f * (k % base);
        }
        point[d] = at(d, t);
      }
      out.points.push_back(point);
    }
    out.spacing.assign(dims, std::pow(static_cast<double>(n), -1.0 / dims));
  }
  return out;
}

GridInitializer::GridInitializer(const Samples& s, const LossData& l, const ParamLayout& layout,
                                 const std::vector<ComponentOps>& components,
                                 const ceres::LossFunction* robust)
    : s_(s), l_(l), layout_(layout), components_(components), robust_(robust) {
  // A sum's lobes are independent (models/sum.h): a lobe's column depends on the shape
  // parameters of its own component only, the offset on those of the weightless components.
  const auto component_of = [&](int i) {
    for (std::size_t c = 0; c < components.size(); ++c) {
      const std::size_t u = static_cast<std::size_t>(i);
      if (u >= components[c].offset && u < components[c].offset + components[c].count) return c;
    }
    throw std::logic_error("grid initializer: parameter outside every component");
  };
  std::vector<bool> has_lobe(components.size(), false);
  for (const auto& lobe : layout.lobes) {
    lobe_component_.push_back(component_of(lobe[0]));
    has_lobe[lobe_component_.back()] = true;
  }
  for (std::size_t c = 0; c < components.size(); ++c) {
    if (!has_lobe[c]) offset_components_.push_back(c);
  }
  lobe_shape_.resize(layout.lobes.size());
  for (int i : layout.shape) {
    const std::size_t c = component_of(i);
    if (!has_lobe[c]) offset_shape_.push_back(i);
    for (std::size_t k = 0; k < layout.lobes.size(); ++k) {
      if (lobe_component_[k] == c) lobe_shape_[k].push_back(i);
    }
  }
  const std::size_t n = s.NumObservations();
  // Linearization at the data.
  w_data_.resize(3 * n);
  y_data_.resize(3 * n);
  for (std::size_t o = 0; o < n; ++o) {
    for (int ch = 0; ch < 3; ++ch) {
      const double m = s.Value(o)[ch];
      const double d = LossResidualWithSlope(l, o, ch, m).Slope();
      w_data_[3 * o + ch] = l.sqrt_w[o] * l.sqrt_w[o] * d * d;
      y_data_[3 * o + ch] = m;
    }
  }
}

std::vector<InitCandidate> GridInitializer::Run(int keep) {
  // Outer search: the log-scale shape parameters (alpha, exponents: where the loss is
  // multimodal). Inner: colour weights solved linearly and, if the model has linear-scale shape
  // parameters (cxy, f0, metallic, ...), a short compass search over them from their defaults.
  std::vector<int> outer, inner;
  for (int idx : layout_.shape) (layout_.specs[idx].log_scale ? outer : inner).push_back(idx);
  const ShapeStarts starts = MakeShapeStarts(layout_, outer, !inner.empty());
  const std::vector<double> inner_step =
      Spacing(inner, std::vector<double>(inner.size(), 1.0 / 64));
  std::vector<double> p(layout_.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = layout_.specs[i].init;
  std::vector<InitCandidate> all;
  for (const auto& point : starts.points) {
    for (std::size_t d = 0; d < outer.size(); ++d) p[outer[d]] = point[d];
    all.push_back(EvaluatePoint(p));
  }
  if (!inner.empty()) {
    // The inner search at every point, except on the Halton sets (three or more outer
    // dimensions: several lobes), where it runs on the kScreened best points by their cost at
    // the inner defaults — the rest rank as screened (docs/fitting.md, "Multi-lobe fits"; 8 of
    // 64, where 16 cost a third of a three-lobe fit's initializer and found no better fits
    // over 25 MERL proxies).
    std::vector<std::size_t> order(all.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    constexpr std::size_t kScreened = 8;
    if (outer.size() >= 3 && all.size() > kScreened) {
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return Less(all[a].cost, all[b].cost);
      });
      order.resize(kScreened);
      std::sort(order.begin(), order.end());  // grid order again
    }
    for (std::size_t i : order) PatternSearch(&all[i], inner, inner_step, 1.0 / 16, 40);
  }
  // Stable order: ties keep grid order, so results do not depend on the sort algorithm.
  std::stable_sort(all.begin(), all.end(), [](const InitCandidate& a, const InitCandidate& b) {
    return Less(a.cost, b.cost);
  });
  // Refine the best few: compass search over every shape parameter, then Gauss-Newton on the
  // weights, then rescore. One spare candidate, except on the Halton sets with an inner
  // search (several Lafortune lobes), whose screened, searched points are already ranked
  // among many: there the spare's 200-evaluation search was a quarter of the initializer.
  const bool halton_inner = outer.size() >= 3 && !inner.empty();
  const std::size_t refine =
      std::min<std::size_t>(all.size(), std::max(keep, 1) + (halton_inner ? 0 : 1));
  all.resize(refine);
  std::vector<double> fractions(starts.spacing);
  fractions.resize(layout_.shape.size(), 1.0 / 64);  // inner dims after the outer ones
  std::vector<int> dims = outer;
  dims.insert(dims.end(), inner.begin(), inner.end());
  const std::vector<double> step = Spacing(dims, fractions);
  for (auto& c : all) {
    PatternSearch(&c, dims, step, 1.0 / 64, 200);
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

std::vector<double> GridInitializer::Spacing(const std::vector<int>& dims,
                                             const std::vector<double>& fractions) const {
  std::vector<double> out;
  for (std::size_t d = 0; d < dims.size(); ++d) {
    out.push_back(fractions[d] * (layout_.upper_opt[dims[d]] - layout_.lower_opt[dims[d]]));
  }
  return out;
}

InitCandidate GridInitializer::EvaluatePoint(std::vector<double> p) {
  ComputeBasis(p);
  SolveWeights(w_data_, y_data_, &p);
  const double cost = Score(p);
  return {std::move(p), cost};
}

// Compass search (Kolda, Lewis, Torczon 2003, "Optimization by Direct Search", SIAM Review
// 45(3), §3) with a step per coordinate (log for log_scale parameters): +-step, accept an
// improvement and double the step, halve it when neither direction improves; a coordinate is
// done when its step falls below shrink_to times its initial step.
void GridInitializer::PatternSearch(InitCandidate* c, const std::vector<int>& dims,
                                    const std::vector<double>& initial_step, double shrink_to,
                                    int max_evaluations) {
  std::vector<double> step = initial_step;
  int evaluations = 0;
  bool any = true;
  while (any && evaluations < max_evaluations) {
    any = false;
    for (std::size_t d = 0; d < dims.size() && evaluations < max_evaluations; ++d) {
      const int idx = dims[d];
      const double range = layout_.upper_opt[idx] - layout_.lower_opt[idx];
      if (step[d] < shrink_to * initial_step[d]) continue;
      any = true;
      bool improved = false;
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
          break;
        }
      }
      // Expand after a success (the local scale may be larger than the first guess), shrink
      // after a failure in both directions.
      step[d] = improved ? std::min(2.0 * step[d], 0.25 * range) : 0.5 * step[d];
    }
  }
}

// basis_[(s * K + k) * 3 + ch]: lobe k's value in channel ch with unit weights. Only the
// columns whose shape parameters changed since the last call are evaluated again (a compass
// step moves one parameter: one lobe's column, not every lobe's).
void GridInitializer::ComputeBasis(const std::vector<double>& p_in) {
  const std::size_t K = layout_.lobes.size(), ns = s_.NumSamples();
  const bool first = basis_at_.empty();
  const auto changed = [&](const std::vector<int>& dims) {
    if (first) return true;
    for (int i : dims) {
      if (!(p_in[i] == basis_at_[i])) return true;  // (NaN: changed)
    }
    return false;
  };
  if (first) {
    basis_.assign(ns * K * 3, 0.0);
    offset_.assign(ns * 3, 0.0);
  }
  std::vector<double> p = p_in;
  for (const auto& lobe : layout_.lobes) {
    for (int idx : lobe) p[idx] = 0.0;
  }
  // The part that no colour weight scales: the weightless components (all of ue4, whose base
  // colour is a shape parameter); a weighted lobe is zero at zero weights.
  if (changed(offset_shape_)) {
    std::fill(offset_.begin(), offset_.end(), 0.0);
    for (std::size_t c : offset_components_) {
      const ComponentOps& op = components_[c];
      for (std::size_t s = 0; s < ns; ++s) {
        double rgb[3];
        op.eval(p.data() + op.offset, s_.geometry[s], rgb);
        for (int ch = 0; ch < 3; ++ch) offset_[3 * s + ch] += rgb[ch];
      }
    }
  }
  for (std::size_t k = 0; k < K; ++k) {
    if (!changed(lobe_shape_[k])) continue;
    const ComponentOps& op = components_[lobe_component_[k]];
    for (int idx : layout_.lobes[k]) p[idx] = 1.0;
    if (op.column != nullptr) {
      op.column(p.data() + op.offset, s_.geometry.data(), ns, &basis_[k * 3], K * 3);
    } else {
      for (std::size_t s = 0; s < ns; ++s) {
        double rgb[3];
        op.eval(p.data() + op.offset, s_.geometry[s], rgb);
        for (int ch = 0; ch < 3; ++ch) basis_[(s * K + k) * 3 + ch] = rgb[ch];
      }
    }
    for (int idx : layout_.lobes[k]) p[idx] = 0.0;
  }
  basis_at_ = p_in;
}

double GridInitializer::Predict(const std::vector<double>& p, std::size_t s, int ch) const {
  const std::size_t K = layout_.lobes.size();
  double f = offset_[3 * s + ch];
  for (std::size_t k = 0; k < K; ++k) f += p[layout_.lobes[k][ch]] * basis_[(s * K + k) * 3 + ch];
  return f;
}

namespace {
// The normal equations of one channel's weights: n (K x K, column-major) += (ws B) B^T and
// b += wy B per sample, each entry summed in sample order. With the lobe count a constant
// (KT > 0) the sums stay in registers: the same operations in the same order, so the same bits
// as the loop over a run-time K (KT = 0), ~4x faster for four lobes.
template <int KT>
void AccumulateNormal(const Samples& s, const std::vector<double>& basis_all,
                      const std::vector<double>& offset, const std::vector<double>& w,
                      const std::vector<double>& y, int K_run, int ch, double* n, double* b) {
  const int K = KT > 0 ? KT : K_run;
  constexpr int kMax = KT > 0 ? KT : 1;
  double nl[kMax * kMax] = {}, bl[kMax] = {};
  double* na = KT > 0 ? nl : n;
  double* ba = KT > 0 ? bl : b;
  for (std::size_t i = 0; i < s.NumSamples(); ++i) {
    const double* basis = &basis_all[i * K * 3 + ch];  // lobe k at basis[3 k]
    double ws = 0, wy = 0;
    for (std::uint32_t o = s.obs_begin[i]; o < s.obs_begin[i + 1]; ++o) {
      ws += w[3 * o + ch];
      wy += w[3 * o + ch] * (y[3 * o + ch] - offset[3 * i + ch]);
    }
    for (int j = 0; j < K; ++j) {
      const double bj = basis[3 * j];
      for (int k = 0; k < K; ++k) na[j * K + k] += (ws * basis[3 * k]) * bj;
      ba[j] += wy * bj;
    }
  }
  if constexpr (KT > 0) {
    for (int j = 0; j < K * K; ++j) n[j] = nl[j];
    for (int j = 0; j < K; ++j) b[j] = bl[j];
  }
}
}  // namespace

// Per channel: min sum W (sum_k a_k B_k - y)^2 within the weights' bounds.
void GridInitializer::SolveWeights(const std::vector<double>& w, const std::vector<double>& y,
                                   std::vector<double>* p) const {
  const int K = static_cast<int>(layout_.lobes.size());
  if (K == 0) return;
  for (int ch = 0; ch < 3; ++ch) {
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(K, K);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(K), lo(K), hi(K);
    // Accumulated in plain loops (the same products as N += (ws B) B^T, b += wy B): Eigen's
    // dynamic-size outer product allocated a temporary per sample.
    double* n = N.data();
    switch (K) {
      case 1:
        AccumulateNormal<1>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
      case 2:
        AccumulateNormal<2>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
      case 3:
        AccumulateNormal<3>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
      case 4:
        AccumulateNormal<4>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
      case 5:
        AccumulateNormal<5>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
      default:
        AccumulateNormal<0>(s_, basis_, offset_, w, y, K, ch, n, b.data());
        break;
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
        const SlopedResidual r = LossResidualWithSlope(l_, o, ch, f0);
        const double e0 = r.e, d = r.Slope();
        if (!(std::abs(d) > 0) || !std::isfinite(e0)) continue;
        const double irls = Robustify(robust_, e0).weight;
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
  // Without a robust function its term is e^2 (Robustify), computed here without the call.
  const bool plain = robust_ == nullptr;
  // Predict's weights gathered once: the same products summed in the same order.
  const std::size_t K = layout_.lobes.size();
  std::vector<double> a(3 * K);
  for (std::size_t k = 0; k < K; ++k) {
    for (int ch = 0; ch < 3; ++ch) a[ch * K + k] = p[layout_.lobes[k][ch]];
  }
  for (std::size_t s = 0; s < s_.NumSamples(); ++s) {
    for (int ch = 0; ch < 3; ++ch) {
      double f = offset_[3 * s + ch];
      for (std::size_t k = 0; k < K; ++k) f += a[ch * K + k] * basis_[(s * K + k) * 3 + ch];
      for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
        const double e = LossResidual(l_, o, ch, f);
        const double term = plain ? e * e : Robustify(robust_, e).cost;
        cost += l_.sqrt_w[o] * l_.sqrt_w[o] * term;
      }
    }
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace brdfit::internal
