#include "pipeline/factor_table.h"

#include "factor/factor_choice.h"
#include "factor/factor_form.h"
#include "factor/factor_metrics.h"
#include "pipeline/factor_export.h"
#include "pipeline/factor_sidecar.h"

namespace brdfit::pipeline {

namespace fs = std::filesystem;

FactorPaths WriteFactorFiles(const Factorization& r, const Table& table, const fs::path& folder,
                             const std::string& stem, const std::string& material,
                             const std::string& file, const FitMetrics& metrics,
                             const RenderedError& rendered, double ln_rmse,
                             const nlohmann::json& choice, const nlohmann::json& ranks,
                             bool timings) {
  nlohmann::json extra = {{"material", material},
                          {"source", SourceJson(file, table)},
                          {"metrics", MetricsJson(metrics, rendered, ln_rmse)},
                          {"provenance", ProvenanceJson(timings)}};
  if (!choice.is_null()) extra["choice"] = choice;
  if (!ranks.is_null()) extra["ranks"] = ranks;
  return SaveFactorization(r, folder, stem, extra, timings);
}

FactoredTable FactorTable(const Table& table, const FactorTableRequest& q) {
  FactoredTable out;
  nlohmann::json choice;
  try {
    if (!q.auto_form) {
      out.result = Factor(table, q.options, q.cache);
      // What the preview draws from the textures written below (docs/accuracy.md).
      out.rendered = ScoreFactorizationRendered(table, out.result.brdf);
    } else {
      // On the last table, a parameterization's system goes once its candidates are done.
      FactorWithChoice c = FactorChoosingForm(table, q.options, q.cache, q.last);
      choice = ChoiceJson(c, q.timings);
      for (std::size_t k = 0; k < c.scores.size(); ++k) {
        out.forms.push_back({kAutoFactorCandidates[k].name, c.scores[k].rendered, k == c.chosen});
      }
      out.result = std::move(c.kept);
      out.rendered = c.rendered;
    }
  } catch (const InputError& e) {
    throw InputError(q.file, e.what());
  }
  // The factored systems (~100 MB each on the MERL grid) serve the next tables; after the last
  // one they are dropped before the metrics' own per-cell arrays are made.
  if (q.last && q.cache) q.cache->Clear();
  const Factorization& r = out.result;
  out.ln_rmse = FactorLnRatioRmse(table, r.brdf, q.options.max_theta);
  // What each product bought: the lower ranks met on the way, scored like the result.
  nlohmann::json ranks;
  if (!r.lower_ranks.empty()) {
    std::vector<const FactoredBrdf*> all;
    for (const FactoredBrdf& b : r.lower_ranks) all.push_back(&b);
    all.push_back(&r.brdf);
    for (const FactoredBrdf* b : all) {
      const RenderedError e = b == &r.brdf ? out.rendered : ScoreFactorizationRendered(table, *b);
      const FactorCost c = CostOf(*b);
      nlohmann::json line = ScoreJson(e);
      line["rank"] = b->rank();
      line["texture_bytes"] = c.texture_bytes;
      line["fetches_per_light"] = c.fetches_per_light;
      line["fetches_per_fragment"] = c.fetches_per_fragment;
      ranks.push_back(std::move(line));
      out.ranks.push_back({b->rank(), e, c});
    }
  }
  out.metrics = ScoreFactorization(table, r.brdf, q.metric_samples);
  out.paths = WriteFactorFiles(r, table, q.out_dir, q.stem, q.material, q.file, out.metrics,
                               out.rendered, out.ln_rmse, choice, ranks, q.timings);
  return out;
}

}  // namespace brdfit::pipeline
