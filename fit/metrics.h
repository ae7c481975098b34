// Computing the fit metrics of core/metrics.h (definitions there) from predictions on a sample
// set: every valid cell inside the cut-off, whatever the fit's loss or budget, so that fits are
// comparable. Also used by the factorization: any predictor that yields RGB per observation can
// be scored.
#pragma once

#include <cstddef>
#include <functional>
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

// Writes the 3 predictions of samples [begin, end) to out (3 (end - begin) values).
using SampleEvaluator = std::function<void(std::size_t begin, std::size_t end, double* out)>;

// The same metrics (bit-identical to ComputeMetricsPerSample) with the predictions made chunk by
// chunk, on the thread that scores the chunk, and never stored whole (3 doubles per sample: 11 MB
// and its page faults on a MERL table). eval must give any sample the same values whatever range
// it is asked for (ModelOps::eval_samples does: tests/fit/test_sample_eval.cc).
FitMetrics ComputeMetricsStreamed(const Samples& samples, const SampleEvaluator& eval,
                                  int threads = 1);

}  // namespace brdfit
