// Fitting more models to the table a report's fit came from, without touching the report:
// what `brdfit export` does when a material's fits hold none of the target's own models
// (docs/exports.md, "Which fits export").
#pragma once

#include <string>
#include <vector>

#include "io/fit_report.h"

namespace brdfit::pipeline {

struct SourceRefit {
  // One entry per model (failed fits included), named as the report's material.
  std::vector<FitReportEntry> entries;
  // Whether `of` was fitted with the options these fits used (brdfit fit's defaults).
  bool same_options = false;
};

// Fits `models` (registry names) to the table `of` was fitted to (its source: a file or
// nbrdf:NAME) with `brdfit fit`'s default options, in a scratch report that is removed
// afterwards. Throws InputError naming the source when it cannot be read, or when its contents
// are not the ones `of` was fitted to (its source_hash).
SourceRefit RefitSource(const FitReportEntry& of, const std::vector<std::string>& models);

}  // namespace brdfit::pipeline
