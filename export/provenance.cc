#include "export/provenance.h"

#include <fmt/core.h>

#include "core/provenance.h"
#include "io/metrics_json.h"

namespace brdfit::exports {

std::string Provenance::FidelityLine() const {
  if (fidelity.Exact()) return "exact: the target evaluates the fitted model's formula";
  std::string s = "approximate (the nearest expressible material): ";
  for (std::size_t i = 0; i < fidelity.approximations.size(); ++i) {
    s += (i ? "; " : "") + fidelity.approximations[i];
  }
  return s;
}

std::vector<std::string> Provenance::Lines() const {
  return {
      fmt::format("Exported by brdfit {} (brdfit export --format ..., docs/exports.md) for {}",
                  version, target),
      "source table: " + source + " (material " + material +
          (source_hash.empty() ? "" : ", content hash " + source_hash) + ")",
      "fit: " + model + " from " + fits,
      "fit metrics (of the fitted model against the table): " + metrics,
      "export: " + FidelityLine(),
  };
}

Provenance ProvenanceOf(const FitReportEntry& e, const std::string& fits_path,
                        const std::string& target, const Fidelity& fidelity) {
  Provenance p;
  p.version = std::string(BrdfitVersion());
  p.source_hash = e.source_hash;
  p.fits = fits_path;
  p.source = e.source;
  p.material = e.material;
  p.model = e.result.model;
  p.target = target;
  p.fidelity = fidelity;
  const FitMetrics& m = e.result.metrics;
  p.metrics =
      fmt::format("log_rmse {:.5g}, rel_l2 {:.5g} ({} weighting, cut-off {:g} deg)", m.log_rmse,
                  m.rel_l2, m.weighting.empty() ? "?" : m.weighting, m.cutoff_deg);
  if (RenderedErrorComputed(m.rendered) && m.rendered.ok) {
    p.metrics += fmt::format(
        "; rendered error psnr {:.2f} dB, median relative {:.2f} %, p95 {:.2f} % "
        "(docs/accuracy.md)",
        m.rendered.psnr_db, 100 * m.rendered.median_rel_error, 100 * m.rendered.p95_rel_error);
  } else {
    p.metrics += "; no rendered error in the fit report";
  }
  return p;
}

}  // namespace brdfit::exports
