#include "core/model_choice.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "core/rendered_regions.h"

namespace brdfit {

namespace {

struct Combination {
  std::array<double, kLightRegions> region_weight{};  // d S / d S_r
  double score = 0;
  bool any = false;
};

Combination Combine(const std::array<RegionError, kLightRegions>& regions) {
  Combination c;
  double total = 0;
  int worst = -1;
  for (int r = 0; r < kLightRegions; ++r) {
    if (regions[r].lights == 0) continue;
    total += kRegionWeights[r];
    if (worst < 0 || regions[r].score_db < regions[worst].score_db) worst = r;
  }
  if (worst < 0 || !(total > 0)) return c;
  c.any = true;
  for (int r = 0; r < kLightRegions; ++r) {
    if (regions[r].lights == 0) continue;
    c.region_weight[r] = (1 - kWorstRegionWeight) * kRegionWeights[r] / total +
                         (r == worst ? kWorstRegionWeight : 0.0);
    c.score += c.region_weight[r] * regions[r].score_db;
  }
  return c;
}

}  // namespace

double RenderedScoreDb(const RenderedError& rendered) {
  const Combination c = Combine(RegionsOfNumbers(rendered));
  if (c.any) return c.score;
  // Neither regions nor lights: the pooled numbers alone (a bench CSV's without regions).
  return std::min(rendered.psnr_db, kScorePsnrCapDb) - 20.0 * rendered.median_rel_error;
}

std::array<double, kRenderedRegions> RegionScoreWeights(const RenderedError& rendered) {
  return Combine(RegionsOfNumbers(rendered)).region_weight;
}

bool BodyColorHolds(const RenderedError& rendered) {
  // NaN (not computed: a report written before it) holds.
  return !(rendered.body_color_error > kBodyColorTolerance);
}

std::optional<double> RenderedScoreDb(const FitResult& fit) {
  const RenderedError& re = fit.metrics.rendered;
  if (fit.Failed() || !re.ok) return std::nullopt;
  const double s = RenderedScoreDb(re);
  if (!std::isfinite(s)) return std::nullopt;
  return s;
}

std::optional<ModelChoice> ChooseCandidate(const std::vector<ChoiceCandidate>& candidates,
                                           const ModelChoiceOptions& options) {
  std::optional<std::size_t> best;
  std::vector<std::optional<double>> score(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    score[i] = RenderedScoreDb(*candidates[i].fit);
  }
  // Fits whose body colour is off take part only when every fit's is.
  auto holds = [&](std::size_t i) { return BodyColorHolds(candidates[i].fit->metrics.rendered); };
  bool any_holds = false;
  for (std::size_t i = 0; i < candidates.size(); ++i) any_holds |= score[i] && holds(i);
  std::size_t set_aside = 0;
  if (any_holds) {
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (score[i] && !holds(i)) {
        score[i].reset();
        ++set_aside;
      }
    }
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (score[i] && (!best || *score[i] > *score[*best])) best = i;
  }
  if (!best) return std::nullopt;
  std::optional<std::size_t> chosen;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!score[i] || *score[i] < *score[*best] - options.tolerance_db) continue;
    if (!chosen) {
      chosen = i;
      continue;
    }
    const ChoiceCandidate &a = candidates[i], &c = candidates[*chosen];
    const bool fewer = a.parameters < c.parameters;
    const bool same = a.parameters == c.parameters;
    if (fewer || (same && (*score[i] > *score[*chosen] ||
                           (*score[i] == *score[*chosen] && a.name < c.name)))) {
      chosen = i;
    }
  }
  ModelChoice out;
  out.index = *chosen;
  out.score_db = *score[*chosen];
  const ChoiceCandidate &c = candidates[*chosen], &b = candidates[*best];
  const RenderedError& rc = c.fit->metrics.rendered;
  if (*chosen == *best) {
    out.reason = fmt::format(
        "best rendered score of {} fit(s): {:.2f} dB (PSNR {:.2f} dB, median luminance error "
        "{:.1f} %)",
        candidates.size(), out.score_db, rc.psnr_db, 100 * rc.median_rel_error);
  } else {
    out.reason = fmt::format(
        "{} parameters against {} for the best-scoring {} ({:.2f} dB), within {:.2f} dB of it: "
        "{:.2f} dB (PSNR {:.2f} dB, median luminance error {:.1f} %)",
        c.parameters, b.parameters, b.name, *score[*best], options.tolerance_db, out.score_db,
        rc.psnr_db, 100 * rc.median_rel_error);
  }
  if (set_aside > 0) {
    out.reason += fmt::format(
        "; {} fit(s) set aside: the body's colour off by more than {:.0f} % in a channel",
        set_aside, 100 * kBodyColorTolerance);
  }
  return out;
}

std::optional<ModelChoice> ChooseFit(const std::vector<const FitResult*>& fits,
                                     const ModelChoiceOptions& options) {
  std::vector<ChoiceCandidate> candidates;
  for (const FitResult* f : fits) candidates.push_back({f, f->params.size(), f->model});
  return ChooseCandidate(candidates, options);
}

}  // namespace brdfit
