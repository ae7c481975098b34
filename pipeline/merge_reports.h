// `brdfit merge OUT.h5 PARTS.h5...`: fit reports (of shards, docs/scale.md) into one, so that
// the merged report is the report one process would have written for the same work: the
// union of the entries, the `chosen` marks made again over all of them (MarkChosenFits), in
// the report's order (io/fit_report.h SortEntries). With parts written without timings, the
// merged file is byte-identical to the single-process `--no-timings` report.
//
//  * One source per material key (pipeline/material_keys.h): a key with two sources is a
//    conflict (InputError naming both files).
//  * Duplicates (same material key, model and options in two parts, or twice in one): kept once when
//    their results are identical (everything the report stores but timings and choice marks,
//    compared as the bytes of the entry written alone); a conflict otherwise (InputError
//    naming both files).
//  * Of identical duplicates, the first part's entry (with its timings) is kept. When some
//    kept entry has timings the merged report has timings (zeros for entries without).
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "io/fit_report.h"

namespace brdfit::pipeline {

struct MergedReports {
  std::vector<FitReportEntry> entries;  // sorted, marked
  std::size_t read = 0;                 // entries read over all parts
  std::size_t duplicates = 0;           // identical duplicates dropped
  bool timed = false;                   // some kept entry has timings
};

// Throws InputError for an unreadable part (naming it) or conflicting duplicates.
MergedReports MergeFitReports(const std::vector<std::filesystem::path>& parts);

}  // namespace brdfit::pipeline
