// JSON of the metric structs of core/metrics.h, shared by every writer of JSON results (fit
// parameters, io/fit_report.h; factorization sidecars, cli/cmd_factor.cc), so that a fit and a
// factorization name and lay out the same numbers alike (docs/formats.md).
#pragma once

#include <nlohmann/json.hpp>

#include "core/metrics.h"

namespace brdfit {

// The rendered-image metric (docs/accuracy.md) as written under "metrics"/"rendered":
//   {"psnr_db", "psnr_srgb_db", "median_rel_error", "p95_rel_error" (fractions), "ok"}
// plus "problem" when ok is false (the numbers are then zeros, as RenderedError holds them).
nlohmann::ordered_json RenderedErrorJson(const RenderedError& e);

// Whether a RenderedError was computed at all (a failed fit is not scored): the writers leave
// "rendered" out when it was not.
inline bool RenderedErrorComputed(const RenderedError& e) { return e.num_lights > 0; }

}  // namespace brdfit
