// The Ceres residual block of a fit: many samples in one block, compressed to P + 1 residuals.
//
// Levenberg-Marquardt only needs, per block, the cost sum r^2, the gradient J^T r and the
// Gauss-Newton matrix J^T J (and diag(J^T J) for Jacobi scaling). A block of n residuals r(x)
// with Jacobian J (n x P) is therefore handed to Ceres as the P + 1 residuals
//     r~ = (z, rho),  J~ = (R; 0)   with  R^T R = J^T J,  R^T z = J^T r,  |z|^2 + rho^2 = r^T r,
// which gives Ceres exactly the same normal equations, gradient and cost: the same iterates as
// the n-row problem, without storing an n x P Jacobian (2.7 M x 7 for a full MERL table).
// R comes from the eigen-decomposition J^T J = V L V^T (R = L^1/2 V^T, z = L^-1/2 V^T J^T r,
// eigenvalues below 1e-14 max dropped: J^T r has no component there). The cost is summed
// directly, in the same order with and without Jacobians, so LM's accept/reject ratio stays
// exact near zero residual (noise-free recovery reaches costs ~1e-30).
//
// Robust losses are applied per residual, as ceres::Corrector does (fit/residual.h: the row is
// scaled by jac_scale, the residual by res_scale, the cost adds rho(e^2)). For concave rho
// (Huber, Cauchy) rho(s) >= s rho'(s) keeps rho^2 >= 0 above.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/jet.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "fit/block_compress.h"
#include "fit/lafortune_gradient.h"
#include "fit/loss.h"
#include "fit/param_layout.h"
#include "fit/residual.h"
#include "fit/samples.h"
#include "models/param.h"

namespace brdfit::internal {

template <class M>
class BlockCost final : public ceres::CostFunction {
 public:
  static constexpr int P = static_cast<int>(kNumParams<M>);
  // Derivative lanes padded to a multiple of 4: Eigen then vectorizes and inlines the Jet
  // arithmetic (an odd size such as 7 falls back to out-of-line scalar loops; bench_fit).
  static constexpr int kLanes = (P + 3) / 4 * 4;
  using Jet = ceres::Jet<double, kLanes>;

  BlockCost(const Samples& samples, const LossData& loss, const ParamLayout& layout,
            const ceres::LossFunction* robust, std::size_t begin, std::size_t end)
      : s_(samples), l_(loss), layout_(layout), robust_(robust), begin_(begin), end_(end) {
    set_num_residuals(P + 1);
    mutable_parameter_block_sizes()->push_back(P);
  }

  // Repeated Jacobians at an accepted step come from cache_ (fit/block_compress.h): the cost of
  // WithJacobian is CostOnly's (same sums, same order).
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
    if (cache_.Answer(x, residuals, jacobian)) return true;
    if (jacobian == nullptr) return CostOnlyResiduals(P, CostOnly(x), residuals);
    double cost = 0;
    if (!WithJacobian(x, residuals, jacobian, &cost)) return false;
    cache_.Store(x, residuals, jacobian, cost);
    return true;
  }

 private:
  // Cost and Jacobian are summed in the same order (sample, channel, observation) so that both
  // paths give bit-identical costs.
  // The model's parameters at optimization point x.
  void Params(const double* x, double* p) const {
    for (int i = 0; i < P; ++i) p[i] = layout_.FromOpt(i, x[i]);
  }

  double CostOnly(const double* x) const {
    double p[P];
    Params(x, p);
    double cost = 0;
    [[maybe_unused]] typename AnalyticGradient<M>::Prepared prepared{};
    if constexpr (AnalyticGradient<M>::kAvailable) prepared = AnalyticGradient<M>::Prepare(p, layout_);
    for (std::size_t s = begin_; s < end_; ++s) {
      double rgb[3];
      // The same values either way (fit/lafortune_gradient.h: bit for bit, tested).
      if constexpr (AnalyticGradient<M>::kAvailable) {
        AnalyticGradient<M>::Eval(prepared, s_.geometry[s], rgb, nullptr);
      } else {
        M::Eval(p, s_.geometry[s], rgb);
      }
      for (int ch = 0; ch < 3; ++ch) {
        for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
          const double w = l_.sqrt_w[o];
          const RobustTerm r = Robustify(robust_, LossResidual(l_, o, ch, rgb[ch]));
          cost += w * w * r.cost;
        }
      }
    }
    return cost;
  }

  // The model is differentiated once per sample (Jets); each of its observations' residuals
  // e_j = inv_j (T(f c_j) - t_j) then has the gradient a_j grad f with the scalar
  // a_j = sqrt(omega_j) js_j inv_j T'(f c_j) c_j. Per sample and channel, J^T J gains
  // (sum a_j^2) grad f grad f^T and J^T r gains (sum a_j b_j) grad f (b_j the weighted,
  // robustified residual): one rank-1 row [sqrt(sum a^2) grad f, sum a b / sqrt(sum a^2)].
  bool WithJacobian(const double* x, double* residuals, double* jacobian, double* cost_out) const {
    GramRows<P + 1> gram;
    double& cost = *cost_out;
    // One sample's channel at value f: adds its cost; the row's scale sqrt(sum a^2) and its
    // right-hand side sum a b / sqrt(sum a^2), or false when no observation has a slope.
    auto reduce = [&](std::size_t s, int ch, double f, double* sq, double* rhs) {
      double saa = 0, sab = 0;
      for (std::uint32_t o = s_.obs_begin[s]; o < s_.obs_begin[s + 1]; ++o) {
        const double w = l_.sqrt_w[o];
        const SlopedResidual e = LossResidualWithSlope(l_, o, ch, f);
        const RobustTerm r = Robustify(robust_, e.e);
        cost += w * w * r.cost;
        const double a = e.Slope(w * r.jac_scale);
        saa += a * a;
        sab += a * (w * r.res_scale * e.e);
      }
      if (!(saa > 0)) return false;
      *sq = std::sqrt(saa);
      *rhs = sab / *sq;
      return true;
    };
    // One sample's channel: value f and gradient grad (optimization space).
    auto add = [&](std::size_t s, int ch, double f, const double* grad) {
      double sq, rhs;
      if (!reduce(s, ch, f, &sq, &rhs)) return;
      double* row = gram.Next();
      for (int i = 0; i < P; ++i) row[i] = sq * grad[i];
      row[P] = rhs;
      gram.Commit();
    };
    if constexpr (AnalyticGradient<M>::kAvailable) {
      // Closed-form derivatives (fit/lafortune_gradient.h): the values are CostOnly's. Channel
      // ch's gradient is zero outside the channel's weights and the shared shapes (kC - 1 of P
      // columns: 10 of 18 for three lobes), so each channel's rows go to a Gram matrix of those
      // columns alone, added into the whole one at the end (a third of the products for three
      // lobes; the same matrix up to the order of its sums).
      using AG = AnalyticGradient<M>;
      constexpr std::array<std::array<int, AG::kC>, 3> cols = AG::ChannelColumns();
      std::array<GramRows<AG::kC>, 3> grams;
      auto add_sparse = [&](std::size_t s, int ch, double f, const double* grad) {
        double sq, rhs;
        if (!reduce(s, ch, f, &sq, &rhs)) return;
        double* row = grams[ch].Next();
        for (int j = 0; j + 1 < AG::kC; ++j) row[j] = sq * grad[cols[ch][j]];
        row[AG::kC - 1] = rhs;
        grams[ch].Commit();
      };
      double p[P];
      Params(x, p);
      const auto prepared = AG::Prepare(p, layout_);
      for (std::size_t s = begin_; s < end_; ++s) {
        double rgb[3], grad[3 * P];
        AG::Eval(prepared, s_.geometry[s], rgb, grad);
        for (int ch = 0; ch < 3; ++ch) add_sparse(s, ch, rgb[ch], grad + ch * P);
      }
      // Each channel's lower triangle into the whole one's (its columns ascend: lower stays
      // lower); the shared shapes' entries are the sum of the three channels'.
      std::array<double, (P + 1) * (P + 1)> full{};
      for (int ch = 0; ch < 3; ++ch) {
        const double* g = grams[ch].Finish();
        for (int c = 0; c < AG::kC; ++c) {
          for (int r = c; r < AG::kC; ++r) {
            full[cols[ch][c] * (P + 1) + cols[ch][r]] += g[c * AG::kC + r];
          }
        }
      }
      return CompressGram(full.data(), P, cost, residuals, jacobian);
    } else {
      Jet p[P];
      SeedParams<Jet, P>(layout_, x, p);
      for (std::size_t s = begin_; s < end_; ++s) {
        Jet rgb[3];
        M::Eval(p, s_.geometry[s], rgb);
        for (int ch = 0; ch < 3; ++ch) add(s, ch, rgb[ch].a, rgb[ch].v.data());
      }
    }
    return CompressGram(gram.Finish(), P, cost, residuals, jacobian);
  }

  const Samples& s_;
  const LossData& l_;
  const ParamLayout& layout_;
  const ceres::LossFunction* robust_;
  std::size_t begin_, end_;
  mutable JacobianCache<P> cache_;
};

}  // namespace brdfit::internal
