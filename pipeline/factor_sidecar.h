// What `brdfit factor` writes into a factorization's sidecar besides the factorization itself
// (docs/formats.md, "Factorization sidecar"): the source table, the metrics, the provenance.
// Shared by the factor command and the factorization candidates of `brdfit fit`
// (pipeline/factor_candidate.h), so that both write the same sidecar for the same table.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/metrics.h"
#include "core/table.h"

namespace brdfit::pipeline {

// The sidecar's "source" member: the file as given (never made absolute), its content hash,
// grid and provenance.
nlohmann::json SourceJson(const std::filesystem::path& file, const Table& t);

// The sidecar's "metrics" member: the ln-ratio RMS (factor/factor_metrics.h), the fit metrics
// and the rendered-image metric as brdfit fit writes them (io/metrics_json.h).
nlohmann::json MetricsJson(const FitMetrics& m, const RenderedError& rendered, double ln_rmse);

// The sidecar's "provenance" member: the version; the command line and date with run details.
nlohmann::json ProvenanceJson(bool run_details);

}  // namespace brdfit::pipeline
