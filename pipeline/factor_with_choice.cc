#include "pipeline/factor_with_choice.h"

#include "core/model_choice.h"
#include "factor/factor_form.h"
#include "factor/factor_metrics.h"

namespace brdfit::pipeline {

FactorWithChoice FactorChoosingForm(const Table& table, const FactorOptions& base,
                                    FactorSystemCache* cache, bool drop_systems) {
  FactorWithChoice out;
  std::vector<Factorization> tried;
  for (const FactorCandidate& c : kAutoFactorCandidates) {
    if (drop_systems && !tried.empty() && tried.back().options.param != c.param) cache->Clear();
    tried.push_back(Factor(table, CandidateOptions(base, c), cache));
    out.seconds.push_back(tried.back().stats.seconds);
    out.scores.push_back(
        {ScoreFactorizationRendered(table, tried.back().brdf), CostOf(tried.back().brdf)});
  }
  const auto pick = ChooseFactorization(out.scores);
  out.chosen = pick ? pick->index : 0;
  out.reason = pick ? pick->reason : "no candidate has a rendered error: the first";
  out.rendered = out.scores[out.chosen].rendered;
  out.kept = std::move(tried[out.chosen]);
  return out;
}

nlohmann::json ScoreJson(const RenderedError& e) {
  const auto number = [&](double v) { return e.ok ? nlohmann::json(v) : nlohmann::json(); };
  return {{"score_db", number(RenderedScoreDb(e))},
          {"psnr_db", number(e.psnr_db)},
          {"median_rel_error", number(e.median_rel_error)}};
}

nlohmann::json ChoiceJson(const FactorWithChoice& c, bool include_timings) {
  nlohmann::json j = {{"rule",
                       "S = psnr_db - 20 median_rel_error; least texture memory within "
                       "0.5 dB of the best (factor/factor_choice.h)"},
                      {"chosen", kAutoFactorCandidates[c.chosen].name},
                      {"reason", c.reason}};
  for (std::size_t k = 0; k < c.scores.size(); ++k) {
    nlohmann::json e = ScoreJson(c.scores[k].rendered);
    e["form"] = kAutoFactorCandidates[k].name;
    e["texture_bytes"] = c.scores[k].cost.texture_bytes;
    e["fetches_per_light"] = c.scores[k].cost.fetches_per_light;
    if (include_timings) e["seconds"] = c.seconds[k];
    j["candidates"].push_back(std::move(e));
  }
  return j;
}

}  // namespace brdfit::pipeline
