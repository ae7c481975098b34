// Analytic Jacobian of Lambert + N Lafortune lobes: the 3 + 5 N parameter
// autodiff (Jets of 20 lanes for three lobes) dominated those fits' solves. BlockCost uses this
// where it exists (AnalyticGradient<M>::kAvailable); every other model keeps its Jets.
//
// The value is models/lafortune.h's and models/lambert.h's Eval in double, the same operations
// in the same order as Sum::Eval<double> (bit for bit, tested), with what depends on the
// parameters alone (the softplus bound, (n + 2) / (2 pi)) computed once per parameter vector:
// two transcendental calls per lobe and sample instead of five, for the cost as well. The derivatives, per lobe
// L = k exp(s) with k = (n + 2) / (2 pi), s = n ln b - softplus(t) / 2, t = n ln(cxy^2),
// b = cxy sxy + c (Lafortune et al. 1997 with the bound of models/lafortune.h):
//   dL/dcxy = L (n sxy / b - sigma(t) n / cxy),   sigma = softplus' = 1 / (1 + e^-t),
//   dL/dn   = exp(s) / (2 pi) + L (ln b - sigma(t) ln(cxy^2) / 2),
// and L = 0 with zero derivatives where b <= 1e-300 (the lobe's clip); the softplus term is
// absent where cxy^2 <= 1e-200, as in Eval. Against the Jets: 1e-10 relative (tested).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "fit/param_layout.h"
#include "models/geometry.h"
#include "models/lafortune.h"
#include "models/lambert.h"
#include "models/math.h"
#include "models/sum.h"

namespace brdfit::internal {

// One Lafortune lobe (models/lafortune.h) at n geometries, rgb[s * stride + c]: Lafortune::Eval
// in double, the same operations in the same order (bit for bit, tested), with the softplus
// bound and (n + 2) / (2 pi) computed once: two transcendental calls per sample instead of five
// (the initializer's basis columns, fit/grid_init.cc).
inline void LafortuneColumn(const double* p, const Geometry* g, std::size_t count, double* rgb,
                            std::size_t stride) {
  const double cxy = p[3], n = p[4];
  const bool bounded = cxy * cxy > 1e-200;
  double half_softplus = 0;
  if (bounded) {
    const double t = n * std::log(cxy * cxy);
    const double softplus = t > 0.0 ? t + std::log1p(std::exp(-t)) : std::log1p(std::exp(t));
    half_softplus = 0.5 * softplus;
  }
  const double k = (n + 2.0) / (2.0 * kPi);
  for (std::size_t s = 0; s < count; ++s) {
    const Geometry& gs = g[s];
    const double sxy = gs.wi.x * gs.wo.x + gs.wi.y * gs.wo.y;
    const double base = cxy * sxy + gs.wi.z * gs.wo.z;
    double lobe = 0.0;
    if (base > 1e-300) {
      double log_shape = n * std::log(base);
      if (bounded) log_shape = log_shape - half_softplus;
      lobe = k * std::exp(log_shape);
    }
    double* out = rgb + s * stride;
    for (int c = 0; c < 3; ++c) out[c] = p[c] * lobe;
  }
}

template <class M>
struct AnalyticGradient {
  static constexpr bool kAvailable = false;
  struct Prepared {};
};

template <class... Lobes>
  requires(std::is_same_v<Lobes, Lafortune> && ...)
struct AnalyticGradient<Sum<Lambert, Lobes...>> {
  static constexpr bool kAvailable = true;
  static constexpr int kLobes = static_cast<int>(sizeof...(Lobes));
  static constexpr int P = 3 + 5 * kLobes;

  // Channel ch's columns where its gradient can be non-zero, ascending: Lambert's weight of
  // ch, then per lobe its weight of ch, cxy and n; last the residual's column P of the Gram
  // matrix [J r]^T [J r] (fit/block_cost.h).
  static constexpr int kC = 2 + 3 * kLobes;
  static constexpr std::array<std::array<int, kC>, 3> ChannelColumns() {
    std::array<std::array<int, kC>, 3> out{};
    for (int ch = 0; ch < 3; ++ch) {
      out[ch][0] = ch;
      for (int k = 0; k < kLobes; ++k) {
        const int o = 3 + 5 * k;
        out[ch][1 + 3 * k] = o + ch;
        out[ch][2 + 3 * k] = o + 3;
        out[ch][3 + 3 * k] = o + 4;
      }
      out[ch][kC - 1] = P;
    }
    return out;
  }

  // What does not depend on the directions, per lobe: computed once per parameter vector.
  struct Lobe {
    const double* rho = nullptr;
    double cxy = 0, n = 0;
    double k = 0;             // (n + 2) / (2 pi)
    bool bounded = false;     // cxy^2 > 1e-200: the softplus term is there
    double half_softplus = 0; // softplus(t) / 2
    double ds_dcxy = 0;       // its part of ds/dcxy: -sigma(t) n / cxy
    double ds_dn = 0;         // and of ds/dn: -sigma(t) ln(cxy^2) / 2
  };
  struct Prepared {
    const double* p = nullptr;
    const ParamLayout* layout = nullptr;
    std::array<Lobe, kLobes> lobes;
  };

  static Prepared Prepare(const double* p, const ParamLayout& layout) {
    Prepared out;
    out.p = p;
    out.layout = &layout;
    for (int k = 0; k < kLobes; ++k) {
      Lobe& l = out.lobes[static_cast<std::size_t>(k)];
      const int o = 3 + 5 * k;
      l.rho = p + o;
      l.cxy = p[o + 3];
      l.n = p[o + 4];
      l.k = (l.n + 2.0) / (2.0 * kPi);
      l.bounded = l.cxy * l.cxy > 1e-200;
      if (l.bounded) {
        const double ln_c2 = std::log(l.cxy * l.cxy);
        const double t = l.n * ln_c2;
        const double e = std::exp(t > 0.0 ? -t : t);
        const double softplus = t > 0.0 ? t + std::log1p(e) : std::log1p(e);
        const double sigma = t > 0.0 ? 1.0 / (1.0 + e) : e / (1.0 + e);
        l.half_softplus = 0.5 * softplus;
        l.ds_dcxy = -(sigma * l.n / l.cxy);
        l.ds_dn = -(0.5 * sigma * ln_c2);
      }
    }
    return out;
  }

  // rgb: the model at p (grad null: the value only); grad[c * P + i]: d rgb[c] / d x_i with x
  // the optimization variables (x = ln p for the layout's log_scale parameters).
  static void Eval(const Prepared& pr, const Geometry& g, double rgb[3], double* grad) {
    const double* p = pr.p;
    if (grad) {
      for (int i = 0; i < 3 * P; ++i) grad[i] = 0;
    }
    // Sum::Eval: 0, then each lobe added in order.
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (int c = 0; c < 3; ++c) {
      rgb[c] += p[c] * kInvPi;
      if (grad) grad[c * P + c] = kInvPi;
    }
    const double sxy = g.wi.x * g.wo.x + g.wi.y * g.wo.y;
    const double cz = g.wi.z * g.wo.z;
    for (int k = 0; k < kLobes; ++k) {
      const Lobe& l = pr.lobes[static_cast<std::size_t>(k)];
      const double base = l.cxy * sxy + cz;
      double lobe = 0.0, d_cxy = 0.0, d_n = 0.0;
      if (base > 1e-300) {
        const double ln_b = std::log(base);
        double log_shape = l.n * ln_b;
        if (l.bounded) log_shape = log_shape - l.half_softplus;
        const double shape = std::exp(log_shape);
        lobe = l.k * shape;
        if (grad) {
          d_cxy = lobe * (l.n * sxy / base + l.ds_dcxy);
          d_n = shape / (2.0 * kPi) + lobe * (ln_b + l.ds_dn);
        }
      }
      const int o = 3 + 5 * k;
      for (int c = 0; c < 3; ++c) {
        rgb[c] += l.rho[c] * lobe;
        if (!grad) continue;
        grad[c * P + o + c] = lobe;
        grad[c * P + o + 3] = l.rho[c] * d_cxy;
        grad[c * P + o + 4] = l.rho[c] * d_n;
      }
    }
    if (!grad) return;
    // Chain rule into optimization space: d/dx = p d/dp for x = ln p.
    for (int i = 0; i < P; ++i) {
      if (!pr.layout->specs[static_cast<std::size_t>(i)].log_scale) continue;
      for (int c = 0; c < 3; ++c) grad[c * P + i] *= p[i];
    }
  }
};

}  // namespace brdfit::internal
