// The residual block of the rendered polish (fit/rendered_polish.h): the pixels of the
// rendered-image metric's scene (fit/rendered_error.h), compressed to P + 1 residuals as the
// table's blocks are (fit/block_cost.h: same normal equations, gradient and cost).
//
// Per lit pixel i, with L = f(wi, wo) n.l the approximation's radiance and L_m the measured one:
//   linear, per channel c:  r = lin_w_i (L_c - L_m,c)                     (the PSNR's error)
//   luminance:              r = rel_w_i ln((Y + delta_i) / (Y_m + delta_i))   (the relative error)
// Y: Rec. 709 luminance (ITU-R BT.709-6), as the metric. The weights are set per round by the
// polish, which makes sum r^2 a local model of the rendered score (fit/rendered_polish.cc).
#pragma once

#include <ceres/cost_function.h>
#include <ceres/jet.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/luminance.h"
#include "fit/block_compress.h"
#include "fit/param_layout.h"
#include "models/geometry.h"
#include "models/param.h"

namespace brdfit::internal {

// The pixels and the current round's weights; read by every block of a polish problem.
struct PolishPixels {
  std::vector<Geometry> geometry;              // of (wi, wo) in the pixel's local frame
  std::vector<double> cos_l;                   // n.l
  std::vector<std::array<double, 3>> measured; // L_m
  std::vector<double> lin_w;                   // per pixel: the weight of its light's PSNR term
  std::vector<double> rel_w;  // 0: below the metric's luminance floor (no relative term)
  std::vector<double> delta;  // the luminance offset of the log ratio (> 0)
  std::size_t size() const { return geometry.size(); }
};

// The four residuals of pixel i from the model's f (T: double or a Jet).
template <class T>
void PixelResiduals(const PolishPixels& px, std::size_t i, const T* f, T r[4]) {
  using std::log;
  using std::max;
  T L[3];
  for (int c = 0; c < 3; ++c) {
    L[c] = f[c] * px.cos_l[i];
    r[c] = px.lin_w[i] * (L[c] - px.measured[i][c]);
  }
  const double ym = Rec709Luminance(px.measured[i].data());
  if (px.rel_w[i] > 0) {
    // Catalog models are non-negative (models/param.h); the max only guards rounding.
    T y = Rec709Luminance(L);
    if (y < T(0)) y = T(0);
    r[3] = px.rel_w[i] * log((y + px.delta[i]) / (ym + px.delta[i]));
  } else {
    r[3] = T(0);
  }
}

template <class M>
class PixelCost final : public ceres::CostFunction {
 public:
  static constexpr int P = static_cast<int>(kNumParams<M>);
  static constexpr int kLanes = (P + 3) / 4 * 4;  // as fit/block_cost.h
  using Jet = ceres::Jet<double, kLanes>;

  PixelCost(const PolishPixels& pixels, const ParamLayout& layout, std::size_t begin,
            std::size_t end)
      : px_(pixels), layout_(layout), begin_(begin), end_(end) {
    set_num_residuals(P + 1);
    mutable_parameter_block_sizes()->push_back(P);
  }

  // Repeated Jacobians at an accepted step come from cache_ (fit/block_compress.h): the cost of
  // the Jacobian evaluation sums the same residuals in the same order as the cost-only one.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
    if (cache_.Answer(x, residuals, jacobian)) return true;
    if (jacobian == nullptr) {
      double p[P];
      for (int i = 0; i < P; ++i) p[i] = layout_.FromOpt(i, x[i]);
      double cost = 0;
      for (std::size_t s = begin_; s < end_; ++s) {
        double f[3], r[4];
        M::Eval(p, px_.geometry[s], f);
        PixelResiduals(px_, s, f, r);
        for (double e : r) cost += e * e;
      }
      return CostOnlyResiduals(P, cost, residuals);
    }
    GramRows<P + 1> gram;
    Jet p[P];
    SeedParams<Jet, P>(layout_, x, p);
    double cost = 0;
    for (std::size_t s = begin_; s < end_; ++s) {
      Jet f[3], r[4];
      M::Eval(p, px_.geometry[s], f);
      PixelResiduals(px_, s, f, r);
      for (const Jet& e : r) {
        cost += e.a * e.a;
        double* row = gram.Next();
        for (int i = 0; i < P; ++i) row[i] = e.v[i];
        row[P] = e.a;
        gram.Commit();
      }
    }
    if (!CompressGram(gram.Finish(), P, cost, residuals, jacobian)) return false;
    cache_.Store(x, residuals, jacobian, cost);
    return true;
  }

 private:
  const PolishPixels& px_;
  const ParamLayout& layout_;
  std::size_t begin_, end_;
  mutable JacobianCache<P> cache_;
};

}  // namespace brdfit::internal
