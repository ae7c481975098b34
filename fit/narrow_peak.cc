#include "fit/narrow_peak.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "core/luminance.h"
#include "core/model_choice.h"

namespace brdfit {

namespace {

double LuminanceAt(const ModelInfo& model, const std::vector<double>& params, double theta_h) {
  double rgb[3] = {0, 0, 0};
  model.eval(params.data(), MakeGeometry(HalfDiffAngles{theta_h, 0.0, 0.0}), rgb);
  return Rec709Luminance(rgb);
}

}  // namespace

double PeakSharpness(const ModelInfo& model, const std::vector<double>& params, int resolution) {
  const double pixel = 2.0 / resolution;
  const double peak = LuminanceAt(model, params, 0.0);  // wi = wo = n
  const double off = LuminanceAt(model, params, pixel);
  if (!std::isfinite(peak) || !std::isfinite(off)) return std::numeric_limits<double>::infinity();
  if (off <= 0) return peak > 0 ? std::numeric_limits<double>::infinity() : 1.0;
  return peak / off;
}

NarrowPeak CheckNarrowPeak(const ModelInfo& model, const RenderedReference& check, FitResult* fit) {
  if (fit->Failed() || !fit->metrics.rendered.ok || check.Empty()) return NarrowPeak::kNone;
  const RenderedError& first = fit->metrics.rendered;
  const double sharpness = PeakSharpness(model, fit->params, first.resolution);
  if (!(sharpness > kNarrowPeakRatio)) return NarrowPeak::kNone;
  RenderedError second = ScoreRendered(check, ModelBrdf(model, fit->params));
  const double s1 = RenderedScoreDb(first);
  const double s2 = second.ok ? RenderedScoreDb(second) : -std::numeric_limits<double>::infinity();
  if (!(s2 < s1)) return NarrowPeak::kKept;
  const std::string note =
      second.ok ? fmt::format(
                      "a peak narrower than a pixel of the judge's images (f(0) / f(1 px) "
                      "= {:.3g}): scored at the worse of {} px (S {:.2f} dB) and {} px "
                      "(S {:.2f} dB)",
                      sharpness, first.resolution, s1, second.resolution, s2)
                : fmt::format(
                      "a peak narrower than a pixel of the judge's images (f(0) / f(1 px) "
                      "= {:.3g}) fails the judge at {} px: {}",
                      sharpness, check.counts.resolution, second.problem);
  fit->message += (fit->message.empty() ? "" : "; ") + note;
  fit->metrics.rendered = std::move(second);
  return NarrowPeak::kLowered;
}

}  // namespace brdfit
