#include "pipeline/factor_sidecar.h"

#include "core/enum_names.h"
#include "core/metrics.h"
#include "core/provenance.h"
#include "io/metrics_json.h"

namespace brdfit::pipeline {

namespace fs = std::filesystem;

nlohmann::json MetricsJson(const FitMetrics& m, const RenderedError& rendered, double ln_rmse) {
  nlohmann::json j = {{"ln_ratio_rmse", ln_rmse},
                      {"ln_ratio_rmse_definition",
                       "sqrt(mean over valid cells above the horizon with all channels > 0 of "
                       "(ln f_factored - ln f_table)^2), unweighted, cell centres"}};
  nlohmann::json& fm = j["fit_metrics"];
  fm = {{"ok", m.ok},
        {"cells", m.cells},
        {"weighting", m.weighting},
        {"cutoff_deg", m.cutoff_deg},
        {"definition", MetricsDefinition()}};
  for (const ErrorMetricField& f : kErrorMetrics) fm[f.name] = m.*f.value;
  if (!m.ok) j["fit_metrics"]["problem"] = m.problem;
  // The rendered-image metric, written as brdfit fit writes it (io/metrics_json.h).
  j["rendered"] = nlohmann::json(RenderedErrorJson(rendered));
  return j;
}

nlohmann::json SourceJson(const fs::path& file, const Table& t) {
  const Provenance& p = t.provenance;
  const std::string name = file.string();
  // As given, as fit reports record their sources: relative to the working directory of the
  // run, never made absolute (an output names no path the user did not give).
  return {{"file", name},
          {"hash", TableContentHash(t)},
          {"grid",
           {{"n_theta_h", t.grid.n_theta_h},
            {"n_theta_d", t.grid.n_theta_d},
            {"n_phi_d", t.grid.n_phi_d},
            {"theta_h_mapping", ToString(t.grid.theta_h_mapping)}}},
          {"provenance",
           {{"source", p.source},
            {"generator", p.generator},
            {"model", p.model},
            {"seed", p.seed},
            {"noise", p.noise},
            {"missing_fraction", p.missing_fraction}}}};
}

nlohmann::json ProvenanceJson(bool run_details) {
  const RunProvenance run = CurrentRunProvenance(run_details);
  nlohmann::json provenance = {{"brdfit_version", run.version}};
  if (run_details) {
    provenance["command_line"] = run.command_line;
    provenance["created"] = run.created;
  }
  return provenance;
}

}  // namespace brdfit::pipeline
