// Computing the fit metrics of core/metrics.h (definitions there) from predictions on a sample
// set: every valid cell inside the cut-off, whatever the fit's loss or budget, so that fits are
// comparable. Also used by the factorization: any predictor that yields RGB per observation can
// be scored.
#pragma once

#include <span>

#include "core/metrics.h"
#include "fit/samples.h"

namespace brdfit {

// predicted_rgb: 3 values per observation of `samples` (see ExpandToObservations).
// Throws std::invalid_argument if the size does not match. `threads` share the pass; the result
// is the same bits for any number of threads (fixed chunks, summed in order).
FitMetrics ComputeMetrics(const Samples& samples, std::span<const double> predicted_rgb,
                          int threads = 1);

// The same metrics (bit-identical) from 3 predictions per *sample*: an observation takes its
// sample's prediction (a cell and its phi_d mirror share one model evaluation), so no
// per-observation copy is made (22 MB on a full MERL table). Throws std::invalid_argument if
// the size does not match.
FitMetrics ComputeMetricsPerSample(const Samples& samples, std::span<const double> per_sample_rgb,
                                   int threads = 1);

}  // namespace brdfit
