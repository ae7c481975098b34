// Run time against error: the one sweep behind `brdfit bench` and bench/bench_fit. Every
// (loss, budget, model) fit of a table, repeated; stage times are medians over the repeats,
// metrics those of the first run (fits are deterministic). One row per fit, in the schema of
// the bench CSV (report/bench_csv.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/table.h"
#include "fit/options.h"
#include "fit/samples.h"
#include "report/report_model.h"

namespace brdfit::pipeline {

struct BenchTable {
  std::string material;  // name in the CSV
  std::string source;    // the input it came from (file, nbrdf:NAME, or a description)
  Table table;
};

struct BenchConfig {
  std::vector<std::string> models = {"lambert+ggx"};
  std::vector<Budget> budgets = {Budget{}};
  std::vector<LossKind> losses = {LossKind::kLog};
  SampleOptions samples;  // cut-off, weighting; the budget is set per row
  FitOptions fit;         // the loss is set per row
  int repeats = 1;        // runs per fit; times are medians
};

struct BenchCallbacks {
  std::function<void(const std::string& label)> on_start;         // before each fit
  std::function<void(const report::BenchPoint& point)> on_point;  // after each fit
};

// Rows in the order losses x budgets x models. Throws InputError for an unknown model.
std::vector<report::BenchPoint> RunBenchSweep(const BenchTable& table, const BenchConfig& config,
                                              const BenchCallbacks& callbacks = {});

}  // namespace brdfit::pipeline
