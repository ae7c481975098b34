// `brdfit merge OUT.csv PARTS.csv...`: bench CSVs (of `brdfit bench --shard I/N`, docs/scale.md)
// into the CSV one process would have written for the same tables: every part's rows, by
// material key (pipeline/material_keys.h), each material's rows in its part's order (loss x
// budget x model as bench sweeps them). With parts written with --no-timings the merged CSV is
// byte-identical to the single-process --no-timings CSV.
//
//  * Rows are keyed by (material, model, loss, budget). Rows of one key in two parts are kept
//    once (the first part's) when everything but the times agrees (a shard run twice, a
//    timed and an untimed run); a conflict otherwise (InputError naming both files).
//  * One table per material key: a key with two tables is a conflict.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "report/report_model.h"

namespace brdfit::pipeline {

struct MergedBench {
  std::vector<report::BenchPoint> points;  // by material, then each part's order
  std::size_t read = 0;                    // rows read over all parts
  std::size_t duplicates = 0;              // identical duplicates dropped
};

// Rows by material key (a stable sort): the order of `brdfit bench`'s CSV.
void SortBenchPoints(std::vector<report::BenchPoint>& points);

// Throws InputError for an unreadable part (naming it) or conflicting rows.
MergedBench MergeBenchCsvs(const std::vector<std::filesystem::path>& parts);

}  // namespace brdfit::pipeline
