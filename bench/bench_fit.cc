// Fitting speed against error.
//
//   bench_fit                 Google Benchmark: Lambert + GGX on full MERL-grid tables (a noisy
//                             synthetic one and, when ../shared/data/merl_nbrdf.zip is present,
//                             five NBRDF materials), initializer + LM, one thread, per budget.
//                             Medians over 5 repetitions; times exclude preparation and metrics.
//   bench_fit --csv FILE [--models a,b] [--budgets full,stride:32,...] [--nbrdf all|m1,m2]
//             [--repeats N]   the sweep of `brdfit bench` (pipeline/bench_sweep.h) on these
//                             tables: every (table, model, budget) fit, median times, as the
//                             bench CSV (report/bench_csv.h), plus a summary on stdout of the
//                             medians and of the metrics relative to the full-budget fit.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_tables.h"
#include "core/model_params.h"
#include "core/synth.h"
#include "fit/fitter.h"
#include "io/nbrdf.h"
#include "models/registry.h"
#include "pipeline/bench_sweep.h"
#include "report/bench_csv.h"

namespace {

using namespace brdfit;
using pipeline::BenchTable;
namespace fs = std::filesystem;

const fs::path kZip = bench::NbrdfZip();
const std::vector<std::string> kBudgets = {"full", "stride:8", "stride:16", "stride:32",
                                           "random:8192"};

BenchTable SyntheticTable() {
  return {"synthetic-lambert-ggx-0.08", "synthetic", bench::SyntheticLambertGgxTable()};
}

std::vector<BenchTable> LoadTables(const std::vector<std::string>& nbrdf) {
  std::vector<BenchTable> tables;
  tables.push_back(SyntheticTable());
  if (!fs::exists(kZip)) {
    fmt::print(stderr, "{} not found: NBRDF tables skipped\n", kZip.string());
    return tables;
  }
  for (const std::string& name : nbrdf) {
    NbrdfTabulation tab = TabulateNbrdf(ReadNbrdf(kZip, name), Grid::Merl(), 1);
    tables.push_back({name, "nbrdf:" + name, std::move(tab.table)});
  }
  return tables;
}

// Google Benchmark: init + LM of a model, metrics excluded (a one-sample metric set, no
// rendered-image metric, so no polish either).
void BM_Fit(benchmark::State& state, const BenchTable* table, std::string model,
            std::string budget) {
  SampleOptions so;
  so.budget = Budget::Parse(budget);
  FitOptions fo = LogLossUnpolished();
  PreparedTable prepared = PrepareTable(table->table, so, fo);
  prepared.metric_own = Subsample(prepared.fit, 1, 1);
  prepared.has_own_metric = true;
  prepared.rendered = RenderedReference{};  // metrics excluded (bench_metrics times them)
  FitResult r;
  for (auto _ : state) {
    r = FitPrepared(model, prepared, fo);
    benchmark::DoNotOptimize(r.params.data());
  }
  state.counters["samples"] = static_cast<double>(r.fit_samples);
  state.counters["iterations"] = r.iterations;
  // The last run's split (thread CPU ms): the initializer against the solve.
  state.counters["init_cpu_ms"] = r.times.init_cpu;
  state.counters["solve_cpu_ms"] = r.times.solve_cpu;
  state.SetLabel(std::string(ToString(r.status)));
}

int Sweep(const std::string& csv, const std::vector<std::string>& models,
          const std::vector<std::string>& budgets, const std::vector<std::string>& nbrdf,
          int repeats) {
  const std::vector<BenchTable> tables = LoadTables(nbrdf);
  pipeline::BenchConfig config;
  config.models = models;
  config.budgets.clear();
  for (const std::string& b : budgets) config.budgets.push_back(Budget::Parse(b));
  config.repeats = repeats;
  std::vector<report::BenchPoint> rows;
  std::size_t done = 0;
  const std::size_t total = tables.size() * budgets.size() * models.size();
  pipeline::BenchCallbacks callbacks;
  callbacks.on_start = [&](const std::string& l) {
    fmt::print(stderr, "[{}/{}] {}\n", ++done, total, l);
  };
  for (const BenchTable& t : tables) {
    const auto points = pipeline::RunBenchSweep(t, config, callbacks);
    rows.insert(rows.end(), points.begin(), points.end());
  }
  report::WriteBenchCsv(csv, rows);
  // Summary per (model, budget): medians over the tables, and the metrics relative to the same
  // table and model's full-budget fit (1 = as good; > 1 worse; 0 without a full budget).
  auto full_of = [&](const report::BenchPoint& p) -> const report::BenchPoint* {
    for (const auto& q : rows) {
      if (q.material == p.material && q.model == p.model && q.budget == "full") return &q;
    }
    return nullptr;
  };
  auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  fmt::print("{:<24} {:<12} {:>8} {:>11} {:>11} {:>11} {:>11}\n", "model", "budget", "cells",
             "solve_ms", "log_ratio", "cbrt_ratio", "max_log_r");
  for (const std::string& model : models) {
    for (const std::string& budget : budgets) {
      std::vector<double> ms, lr, cr, n;
      for (const report::BenchPoint& r : rows) {
        if (r.model != model || r.budget != Budget::Parse(budget).ToString()) continue;
        const report::BenchPoint* full = full_of(r);
        ms.push_back(r.init_ms + r.solve_ms);
        lr.push_back(full ? ratio(r.metrics.log_rmse, full->metrics.log_rmse) : 0.0);
        cr.push_back(full ? ratio(r.metrics.cbrt_rmse, full->metrics.cbrt_rmse) : 0.0);
        n.push_back(static_cast<double>(r.fit_cells));
      }
      auto median = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::sort(v.begin(), v.end());
        return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
      };
      const double worst = lr.empty() ? 0.0 : *std::max_element(lr.begin(), lr.end());
      fmt::print("{:<24} {:<12} {:>8.0f} {:>11.1f} {:>11.4f} {:>11.4f} {:>11.4f}\n", model, budget,
                 median(n), median(ms), median(lr), median(cr), worst);
    }
  }
  fmt::print("wrote {} ({} rows)\n", csv, rows.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv;
  std::vector<std::string> models = {"lambert+ggx"};
  std::vector<std::string> budgets = kBudgets;
  std::vector<std::string> nbrdf = bench::kBenchNbrdf;
  int repeats = 3;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--csv" && has_value) {
      csv = argv[++i];
    } else if (a == "--models" && has_value) {
      models = bench::SplitList(argv[++i]);
    } else if (a == "--budgets" && has_value) {
      budgets = bench::SplitList(argv[++i]);
    } else if (a == "--nbrdf" && has_value) {
      const std::string v = argv[++i];
      nbrdf = v == "all"
                  ? (fs::exists(kZip) ? ListNbrdfMaterials(kZip) : std::vector<std::string>{})
                  : bench::SplitList(v);
    } else if (a == "--repeats" && has_value) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      rest.push_back(argv[i]);
    }
  }
  if (!csv.empty()) return Sweep(csv, models, budgets, nbrdf, repeats);

  static const std::vector<BenchTable> tables = LoadTables(bench::kBenchNbrdf);
  for (const BenchTable& t : tables) {
    for (const std::string& b : kBudgets) {
      benchmark::RegisterBenchmark(("lambert+ggx/" + t.material + "/" + b).c_str(), BM_Fit, &t,
                                   std::string("lambert+ggx"), b)
          ->Unit(benchmark::kMillisecond)
          ->Repetitions(5)
          ->ReportAggregatesOnly(true)
          ->Iterations(b == "full" ? 1 : 3);
    }
  }
  // Multi-lobe fits against their single lobe at the default budget (docs/fitting.md, "Speed
  // against error": two- and three-lobe fits are to cost within 3x one lobe).
  for (const BenchTable& t : tables) {
    for (const char* m : {"lambert+lafortune", "lambert+lafortune+lafortune+lafortune",
                          "lambert+ggx+ggx"}) {
      benchmark::RegisterBenchmark((std::string(m) + "/" + t.material + "/stride:32").c_str(),
                                   BM_Fit, &t, std::string(m), std::string("stride:32"))
          ->Unit(benchmark::kMillisecond)
          ->Repetitions(5)
          ->ReportAggregatesOnly(true)
          ->Iterations(1);
    }
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
