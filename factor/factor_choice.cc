#include "factor/factor_choice.h"

#include <fmt/core.h>

#include <cmath>
#include <tuple>

#include "core/model_choice.h"

namespace brdfit {

FactorOptions CandidateOptions(const FactorOptions& base, const FactorCandidate& c) {
  FactorOptions o = base;
  o.param = c.param;
  o.diffuse = c.diffuse;
  o.refine = c.refine;
  o.rank = c.rank;
  o.refine_loss = c.loss;
  return o;
}

std::optional<FactorChoice> ChooseFactorization(const std::vector<FactorScore>& scores,
                                                double tolerance_db) {
  std::optional<std::size_t> best;
  std::vector<double> s(scores.size(), NAN);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    if (!scores[i].rendered.ok) continue;
    s[i] = RenderedScoreDb(scores[i].rendered);
    if (!std::isfinite(s[i])) continue;
    if (!best || s[i] > s[*best]) best = i;
  }
  if (!best) return std::nullopt;
  std::size_t pick = *best;
  auto key = [&](std::size_t i) {
    return std::make_tuple(scores[i].cost.texture_bytes, scores[i].cost.fetches_per_light, -s[i]);
  };
  for (std::size_t i = 0; i < scores.size(); ++i) {
    if (std::isfinite(s[i]) && s[i] >= s[*best] - tolerance_db && key(i) < key(pick)) pick = i;
  }
  FactorChoice c;
  c.index = pick;
  c.score_db = s[pick];
  c.reason = pick == *best
                 ? fmt::format("highest rendered score S = {:.2f} dB", s[pick])
                 : fmt::format(
                       "S = {:.2f} dB, within {:.1f} dB of the best ({:.2f} dB) with less "
                       "texture memory",
                       s[pick], tolerance_db, s[*best]);
  return c;
}

}  // namespace brdfit
