#include "pipeline/fit_settings.h"

#include "core/error.h"

namespace brdfit::pipeline {

void ApplyFitSettings(const FitSettings& s, SampleOptions* samples, FitOptions* fit) {
  if (s.threads < 1 || s.threads > 256) throw InputError("--threads must be in [1, 256]");
  if (s.multistart < 1 || s.multistart > 1000)
    throw InputError("--multistart must be in [1, 1000]");
  if (s.max_iterations < 1) throw InputError("--max-iterations must be >= 1");
  SampleOptions& so = *samples;
  so.cutoff_deg = s.cutoff;
  so.weighting = WeightingFromString(s.weighting);
  so.budget = Budget::Parse(s.budget);
  so.seed = s.seed;
  FitOptions& fo = *fit;
  fo.loss = s.loss.empty() ? kDefaultLoss : LossKindFromString(s.loss);
  fo.cosine = !s.no_cosine;
  fo.robust = RobustKindFromString(s.robust);
  fo.robust_scale = s.robust_scale;
  if (!(fo.robust_scale > 0)) throw InputError("--robust-scale must be positive");
  fo.multistart = s.multistart;
  fo.max_iterations = s.max_iterations;
  fo.threads = s.threads;
  fo.seed = s.seed;
  fo.polish = FromString<PolishKind>(s.polish);
  if (!(so.cutoff_deg > 0 && so.cutoff_deg <= 90)) throw InputError("--cutoff must be in (0, 90]");
}

}  // namespace brdfit::pipeline
