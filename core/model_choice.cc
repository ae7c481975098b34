#include "core/model_choice.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace brdfit {

double RenderedScoreDb(const RenderedError& rendered) {
  return std::min(rendered.psnr_db, kScorePsnrCapDb) - 20.0 * rendered.median_rel_error;
}

std::optional<double> RenderedScoreDb(const FitResult& fit) {
  const RenderedError& re = fit.metrics.rendered;
  if (fit.Failed() || !re.ok) return std::nullopt;
  const double s = RenderedScoreDb(re);
  if (!std::isfinite(s)) return std::nullopt;
  return s;
}

std::optional<ModelChoice> ChooseFit(const std::vector<const FitResult*>& fits,
                                     const ModelChoiceOptions& options) {
  std::optional<std::size_t> best;
  std::vector<std::optional<double>> score(fits.size());
  for (std::size_t i = 0; i < fits.size(); ++i) {
    score[i] = RenderedScoreDb(*fits[i]);
    if (score[i] && (!best || *score[i] > *score[*best])) best = i;
  }
  if (!best) return std::nullopt;
  std::optional<std::size_t> chosen;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    if (!score[i] || *score[i] < *score[*best] - options.tolerance_db) continue;
    if (!chosen) {
      chosen = i;
      continue;
    }
    const FitResult &a = *fits[i], &c = *fits[*chosen];
    const bool fewer = a.params.size() < c.params.size();
    const bool same = a.params.size() == c.params.size();
    if (fewer || (same && (*score[i] > *score[*chosen] ||
                           (*score[i] == *score[*chosen] && a.model < c.model)))) {
      chosen = i;
    }
  }
  ModelChoice out;
  out.index = *chosen;
  out.score_db = *score[*chosen];
  const FitResult &c = *fits[*chosen], &b = *fits[*best];
  const RenderedError& rc = c.metrics.rendered;
  if (*chosen == *best) {
    out.reason = fmt::format(
        "best rendered score of {} fit(s): {:.2f} dB (PSNR {:.2f} dB, median luminance error "
        "{:.1f} %)",
        fits.size(), out.score_db, rc.psnr_db, 100 * rc.median_rel_error);
  } else {
    out.reason = fmt::format(
        "{} parameters against {} for the best-scoring {} ({:.2f} dB), within {:.2f} dB of it: "
        "{:.2f} dB (PSNR {:.2f} dB, median luminance error {:.1f} %)",
        c.params.size(), b.params.size(), b.model, *score[*best], options.tolerance_db,
        out.score_db, rc.psnr_db, 100 * rc.median_rel_error);
  }
  return out;
}

}  // namespace brdfit
