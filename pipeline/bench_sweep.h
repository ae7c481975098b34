// Run time against error: every (table, model, budget) fit repeated a few times, with the
// median times and the metrics relative to the same model's full-budget fit. Library code so
// that bench/bench_fit and the CLI can share it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/table.h"
#include "fit/options.h"
#include "fit/samples.h"

namespace brdfit {

struct BenchTable {
  std::string material;  // name in the CSV
  std::string kind;      // "synthetic", "nbrdf", "file"
  Table table;
};

struct BenchConfig {
  std::vector<std::string> models = {"lambert+ggx"};
  std::vector<std::string> budgets = {"full", "stride:8", "stride:16", "stride:32", "random:8192"};
  SampleOptions samples;  // cut-off, weighting; the budget is set per row
  FitOptions fit;
  int repeats = 3;  // medians over this many runs
};

struct BenchRow {
  std::string material, kind, model, budget, status;
  std::size_t fit_samples = 0;
  int iterations = 0;
  double prepare_ms = 0;    // fit and metric samples of the table (median, wall)
  double solve_ms = 0;      // init + LM (median, wall)
  double solve_cpu_ms = 0;  // init + LM (median, thread CPU)
  double log_rmse = 0, cbrt_rmse = 0, rel_l2 = 0;
  // Metrics relative to the full-budget fit of the same table and model (1 = as good; > 1
  // worse). 0 when the sweep has no full budget.
  double log_rmse_ratio = 0, cbrt_rmse_ratio = 0, rel_l2_ratio = 0;
};

// progress(done, total, label) is called before each (table, model, budget) cell.
std::vector<BenchRow> RunBenchSweep(
    const std::vector<BenchTable>& tables, const BenchConfig& config,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& progress = {});

// CSV (RFC 4180), one header row; columns as BenchRow, in that order.
std::string BenchRowsCsv(const std::vector<BenchRow>& rows);

}  // namespace brdfit
