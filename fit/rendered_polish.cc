#include "fit/rendered_polish.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/luminance.h"
#include "core/model_choice.h"
#include "core/rendered_regions.h"
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

// The pixels of the reference with this round's weights at parameters x (header comment): each
// region's terms weighted by weight[r], d S / d S_r of the score the stage climbs.
bool Reweight(const ModelOps& ops, const RenderedReference& ref,
              const std::vector<std::size_t>& begin, const RenderedPolishOptions& o,
              const std::vector<double>& x, const std::array<double, kRenderedRegions>& weight,
              PolishPixels& px) {
  const std::vector<double> p = FromOpt(ops.layout, x);
  std::vector<double> err(px.size(), -1.0);
  std::array<double, kRenderedRegions> sse{};
  std::array<std::size_t, kRenderedRegions> compared{};
  std::vector<std::size_t> region_of(static_cast<std::size_t>(ref.counts.num_lights));
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    const auto g = static_cast<std::size_t>(RegionOfLight(ref.counts.lights[k].light_deg));
    region_of[static_cast<std::size_t>(k)] = g;
    // The light's peak over all its pixels, as the metric's floor.
    const double peak_y = ref.peak_y[static_cast<std::size_t>(k)];
    for (std::size_t i = begin[k]; i < begin[k + 1]; ++i) {
      double f[3], L[3];
      ops.eval(p.data(), px.geometry[i], f);
      for (int c = 0; c < 3; ++c) {
        L[c] = f[c] * px.cos_l[i];
        sse[g] += (L[c] - px.measured[i][c]) * (L[c] - px.measured[i][c]);
      }
      px.delta[i] = o.delta_fraction * peak_y;
      if (!(px.delta[i] > 0)) return false;
      const double ym = Rec709Luminance(px.measured[i].data());
      // The metric's compared pixels (fit/rendered_error.h, luminance_floor).
      if (ym > ref.luminance_floor * peak_y) {
        err[i] = std::abs(Rec709Luminance(L) - ym) / ym;
        ++compared[g];
      }
    }
  }
  bool any = false;
  for (int k = 0; k < ref.counts.num_lights; ++k) {
    const std::size_t g = region_of[static_cast<std::size_t>(k)];
    const double w = weight[g];
    if (!std::isfinite(sse[g])) return false;
    const double lin_w = sse[g] > 0 && w > 0 ? std::sqrt(w * 10.0 / std::log(10.0) / sse[g]) : 0.0;
    for (std::size_t i = begin[k]; i < begin[k + 1]; ++i) {
      px.lin_w[i] = lin_w;
      px.rel_w[i] =
          err[i] < 0 || !(w > 0)
              ? 0.0
              : std::sqrt(w * o.median_weight /
                          (static_cast<double>(compared[g]) * std::max(err[i], o.min_error)));
      any = any || lin_w > 0 || px.rel_w[i] > 0;
    }
  }
  return any;
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
  px.lin_w.assign(n, 0.0);
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

  // Two stages when the metric has lights beyond the front: the front region's S alone (the
  // highlight seen head-on, where a fit's parameters are best determined), then the whole S
  // from there. IRLS on the whole S from the table fit's parameters stalls where one region's
  // surrogate forbids what another needs; from the front's optimum it trades only what S
  // gains. The parameters returned are the best by the whole S of all visited.
  bool beyond_front = false;
  for (int r = 1; r < kRenderedRegions; ++r) beyond_front |= out.rendered.regions[r].lights > 0;
  std::vector<double> stage_start = x;
  RenderedError stage_start_rendered = out.rendered;  // the metric at stage_start
  for (int stage = beyond_front ? 0 : 1; stage < 2; ++stage) {
    const bool front_only = stage == 0;
    const auto stage_score = [&](const RenderedError& e) {
      if (!e.ok) return std::nan("");
      return front_only ? RenderedRegions(e)[0].score_db : RenderedScoreDb(e);
    };
    std::vector<double> cur = stage_start;
    RenderedError cur_rendered = stage_start_rendered;
    double stage_best = stage_score(cur_rendered);
    if (!std::isfinite(stage_best)) break;
    // The rounds are shared between the stages: the polish costs what one stage did.
    const int rounds = beyond_front ? (o.rounds + 1) / 2 : o.rounds;
    for (int round = 0; round < rounds; ++round) {
      std::array<double, kRenderedRegions> weight{};
      if (front_only) {
        weight[0] = 1;
      } else {
        weight = RegionScoreWeights(cur_rendered);
      }
      if (!cur_rendered.ok || !Reweight(ops, ref, begin, o, cur, weight, px)) break;
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
      cur_rendered = e;
      const double s = ScoreOf(e);
      out.round_scores.push_back(s);
      if (std::isfinite(s) && s > out.score_after) {
        out.score_after = s;
        out.rendered = e;
        out.improved = true;
        x = cur;
      }
      const double ss = stage_score(e);
      const double gain = std::isfinite(ss) ? ss - stage_best : 0.0;
      if (std::isfinite(ss) && ss > stage_best) {
        stage_best = ss;
        stage_start = cur;
        stage_start_rendered = e;
      }
      // IRLS until the stage's score stops rising (options' comment): two rounds at least.
      if (round >= 1 && !(gain >= o.min_round_gain_db)) break;
    }
  }
  return out;
}

}  // namespace brdfit::internal
