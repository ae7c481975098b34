#include "fit/rendered_polish.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <cmath>

#include "core/model_choice.h"
#include "fit/bounded_lm.h"
#include "fit/pixel_cost.h"

namespace brdfit::internal {

namespace {

std::vector<double> FromOpt(const ParamLayout& layout, const std::vector<double>& x) {
  std::vector<double> p(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    p[i] = std::clamp(layout.FromOpt(i, x[i]), layout.specs[i].lower, layout.specs[i].upper);
  }
  return p;
}

// The rendered metric at x (the parameters clamped into their bounds, as the fit reports them).
RenderedError RenderedAt(const ModelOps& ops, const RenderedReference& ref,
                         const std::vector<double>& x) {
  const std::vector<double> p = FromOpt(ops.layout, x);
  return ScoreRendered(ref, [&](const Vec3& wi, const Vec3& wo) {
    std::array<double, 3> rgb{};
    ops.eval(p.data(), MakeGeometry(wi, wo), rgb.data());
    return rgb;
  });
}

// S of a rendered metric, or NaN when the metric failed.
double ScoreOf(const RenderedError& e) {
  return e.ok ? RenderedScoreDb(e) : std::nan("");
}

// The pixels of the reference with this round's weights, at parameters x (header comment).
bool Reweight(const ModelOps& ops, const RenderedReference& ref,
              const std::vector<std::size_t>& begin, const RenderedPolishOptions& o,
              const std::vector<double>& x, PolishPixels& px) {
  const std::vector<double> p = FromOpt(ops.layout, x);
  const std::size_t n = px.size();
  std::vector<double> err(n, -1.0);
  double sse = 0;
  std::size_t compared = 0;
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    double peak_y = 0;
    // The light's peak over all its pixels, as the metric's floor.
    for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; ++i) {
      peak_y = std::max(peak_y, PolishLuminance(ref.pixels[i].measured.data()));
    }
    for (std::size_t i = begin[k]; i < begin[k + 1]; ++i) {
      double f[3], L[3];
      ops.eval(p.data(), px.geometry[i], f);
      for (int c = 0; c < 3; ++c) {
        L[c] = f[c] * px.cos_l[i];
        sse += (L[c] - px.measured[i][c]) * (L[c] - px.measured[i][c]);
      }
      px.delta[i] = o.delta_fraction * peak_y;
      const double ym = PolishLuminance(px.measured[i].data());
      // The metric's compared pixels (fit/rendered_error.h, luminance_floor).
      if (ym > ref.luminance_floor * peak_y) {
        err[i] = std::abs(PolishLuminance(L) - ym) / ym;
        ++compared;
      }
    }
  }
  if (!(sse > 0) || !std::isfinite(sse) || !(px.delta.front() > 0)) return false;
  px.lin_w = std::sqrt(10.0 / std::log(10.0) / sse);
  for (std::size_t i = 0; i < n; ++i) {
    px.rel_w[i] = err[i] < 0 ? 0.0
                             : std::sqrt(o.median_weight / (static_cast<double>(compared) *
                                                            std::max(err[i], o.min_error)));
  }
  return true;
}

}  // namespace

RenderedPolishOutcome PolishOnRendered(const ModelOps& ops, const RenderedReference& ref,
                                       const RenderedPolishOptions& o, std::vector<double>& x) {
  RenderedPolishOutcome out;
  const ParamLayout& layout = ops.layout;
  if (ref.pixels.empty() || ops.make_pixel_block == nullptr) return out;
  out.rendered = RenderedAt(ops, ref, x);
  out.score_before = out.score_after = ScoreOf(out.rendered);
  if (!std::isfinite(out.score_before)) return out;
  out.ran = true;

  // The polished pixels: every pixel_stride-th of each light's (the weights need the light).
  PolishPixels px;
  std::vector<std::size_t> begin = {0};
  const std::size_t stride = static_cast<std::size_t>(std::max(o.pixel_stride, 1));
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    for (std::size_t i = ref.begin[k]; i < ref.begin[k + 1]; i += stride) {
      const RenderedReference::Pixel& q = ref.pixels[i];
      px.geometry.push_back(MakeGeometry(q.wi, q.wo));
      px.cos_l.push_back(q.cos_l);
      px.measured.push_back(q.measured);
    }
    begin.push_back(px.size());
  }
  const std::size_t n = px.size();
  px.rel_w.assign(n, 0.0);
  px.delta.assign(n, 0.0);

  ceres::Solver::Options so = LmSolverOptions(o.threads);
  // S to ~0.0004 dB is enough (it is reported to 0.01 dB): a relative cost change of 1e-4 ends a
  // round. Where a step leaves the box, Ceres' projected Armijo search interpolates quadratically,
  // from the costs alone: cubic interpolation asks the Jacobian at every trial point (65 pixel
  // Jacobians for 20 iterations on chrome, 13 with both settings). Over the 100 MERL proxies both
  // cost 0.05 dB of held-out S and save 10 % of the candidates' solve time (docs/accuracy.md).
  so.function_tolerance = o.function_tolerance;
  so.line_search_interpolation_type = ceres::QUADRATIC;

  std::vector<double> cur = x;
  for (int round = 0; round < o.rounds; ++round) {
    if (!Reweight(ops, ref, begin, o, cur, px)) break;
    // Blocks of 2048 pixels: Ceres' threads share them; accumulation stays short. LM with an
    // active set (fit/bounded_lm.h), as the table fit: a parameter the fit left on a bound (a
    // metal's zero diffuse) is held there instead of projected after every step.
    const std::size_t nb = std::max<std::size_t>(n / 2048, 1);
    const BoundedLmRun run = RunBoundedLm(
        layout,
        [&](double* xb, ceres::Problem* problem) {
          for (std::size_t b = 0; b < nb; ++b) {
            problem->AddResidualBlock(
                ops.make_pixel_block(px, layout, n * b / nb, n * (b + 1) / nb), nullptr, xb);
          }
        },
        so, o.max_iterations, cur.data());
    out.iterations += run.iterations;
    if (!run.finite) break;
    const RenderedError e = RenderedAt(ops, ref, cur);
    const double s = ScoreOf(e);
    out.round_scores.push_back(s);
    const double gain = std::isfinite(s) ? s - out.score_after : 0.0;
    if (std::isfinite(s) && s > out.score_after) {
      out.score_after = s;
      out.rendered = e;
      out.improved = true;
      x = cur;
    }
    // IRLS until S stops rising (options' comment): the second round always runs.
    if (round >= 1 && !(gain >= o.min_round_gain_db)) break;
  }
  return out;
}

}  // namespace brdfit::internal
