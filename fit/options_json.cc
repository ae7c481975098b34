#include <nlohmann/json.hpp>

#include "fit/loss.h"
#include "fit/options.h"
#include "fit/samples.h"

namespace brdfit {

std::string OptionsJson(const SampleOptions& s, const FitOptions& f) {
  nlohmann::json j;  // std::map-backed: keys come out sorted
  j["cutoff_deg"] = s.cutoff_deg;
  j["weighting"] = ToString(s.weighting);
  j["budget"] = s.budget.ToString();
  j["sample_seed"] = s.seed;
  j["pair_mirrors"] = s.pair_mirrors;
  j["loss"] = ToString(f.loss);
  j["cosine"] = f.cosine;
  j["robust"] = ToString(f.robust);
  j["robust_scale"] = f.robust_scale;
  j["multistart"] = f.multistart;
  j["max_iterations"] = f.max_iterations;
  j["init_samples"] = f.init_samples;
  j["coarse_samples"] = f.coarse_samples;
  j["seed"] = f.seed;
  j["function_tolerance"] = f.function_tolerance;
  j["parameter_tolerance"] = f.parameter_tolerance;
  j["gradient_tolerance"] = f.gradient_tolerance;
  // Written only when on, so that reports made before the polish existed keep their keys.
  if (f.polish != PolishKind::kNone) j["polish"] = ToString(f.polish);
  // The rendered metric that scores, polishes and chooses every fit: its lights all around
  // (core/rendered_regions.h). Fits scored by the front-light judge before it (no key) are not
  // comparable, so a report of them is refitted on resume and refused by merge.
  j["judge"] = kRenderedJudge;
  return j.dump();
}

}  // namespace brdfit
