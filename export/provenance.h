// What every exported file states about itself: the brdfit version, the source table, the fit
// and its own metrics (docs/exports.md), and what the target could not express.
#pragma once

#include <string>
#include <vector>

#include "export/targets.h"
#include "io/fit_report.h"

namespace brdfit::exports {

struct Provenance {
  std::string version;   // BrdfitVersion() (core/provenance.h)
  std::string fits;      // the report or JSON exported from
  std::string source;    // the measured table the fit was made to
  std::string material;  // its name
  std::string source_hash;  // its content hash (core/provenance.h), when the report has it
  std::string model;     // the fitted model
  std::string metrics;   // one line: the fit's log_rmse, rel_l2 and rendered error
  std::string target;    // "glTF 2.0", "Mitsuba 3", "pbrt-v4"
  Fidelity fidelity;     // exact, or the approximations made

  // "exact" or "approximate: a; b" for one line.
  std::string FidelityLine() const;
  // The lines a file's header comment holds, without comment markers.
  std::vector<std::string> Lines() const;
};

Provenance ProvenanceOf(const FitReportEntry& e, const std::string& fits_path,
                        const std::string& target, const Fidelity& fidelity);

}  // namespace brdfit::exports
