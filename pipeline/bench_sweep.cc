#include "pipeline/bench_sweep.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <map>

#include "fit/fitter.h"

namespace brdfit {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string Quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

double Ratio(double a, double b) {
  return b > 0 ? a / b : 0.0;
}

}  // namespace

std::vector<BenchRow> RunBenchSweep(
    const std::vector<BenchTable>& tables, const BenchConfig& config,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& progress) {
  using Clock = std::chrono::steady_clock;
  std::vector<BenchRow> rows;
  const std::size_t total = tables.size() * config.budgets.size() * config.models.size();
  std::size_t done = 0;
  for (const BenchTable& t : tables) {
    std::map<std::string, const BenchRow*> full;  // model -> its full-budget row
    const std::size_t first_row = rows.size();
    for (const std::string& budget : config.budgets) {
      SampleOptions so = config.samples;
      so.budget = Budget::Parse(budget);
      std::vector<double> prep;
      PreparedTable prepared;
      for (int k = 0; k < std::max(config.repeats, 1); ++k) {
        const auto t0 = Clock::now();
        prepared = PrepareTable(t.table, so, config.fit);
        prep.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
      for (const std::string& model : config.models) {
        if (progress) progress(done++, total, t.material + " " + model + " " + budget);
        std::vector<double> wall, cpu;
        FitResult r;
        for (int k = 0; k < std::max(config.repeats, 1); ++k) {
          r = FitPrepared(model, prepared, config.fit);
          wall.push_back(r.times.init + r.times.solve);
          cpu.push_back(r.times.init_cpu + r.times.solve_cpu);
        }
        BenchRow row;
        row.material = t.material;
        row.kind = t.kind;
        row.model = model;
        row.budget = budget;
        row.status = ToString(r.status);
        row.fit_samples = r.fit_samples;
        row.iterations = r.iterations;
        row.prepare_ms = Median(prep);
        row.solve_ms = Median(wall);
        row.solve_cpu_ms = Median(cpu);
        row.log_rmse = r.metrics.log_rmse;
        row.cbrt_rmse = r.metrics.cbrt_rmse;
        row.rel_l2 = r.metrics.rel_l2;
        rows.push_back(row);
      }
    }
    for (std::size_t i = first_row; i < rows.size(); ++i) {
      if (rows[i].budget == "full") full[rows[i].model] = &rows[i];
    }
    for (std::size_t i = first_row; i < rows.size(); ++i) {
      const auto it = full.find(rows[i].model);
      if (it == full.end()) continue;
      rows[i].log_rmse_ratio = Ratio(rows[i].log_rmse, it->second->log_rmse);
      rows[i].cbrt_rmse_ratio = Ratio(rows[i].cbrt_rmse, it->second->cbrt_rmse);
      rows[i].rel_l2_ratio = Ratio(rows[i].rel_l2, it->second->rel_l2);
    }
  }
  return rows;
}

std::string BenchRowsCsv(const std::vector<BenchRow>& rows) {
  std::string s =
      "material,kind,model,budget,status,fit_samples,iterations,prepare_ms,solve_ms,"
      "solve_cpu_ms,log_rmse,cbrt_rmse,rel_l2,log_rmse_ratio,cbrt_rmse_ratio,rel_l2_ratio\n";
  for (const BenchRow& r : rows) {
    s += fmt::format(
        "{},{},{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.9g},{:.9g},{:.9g},{:.6f},{:.6f},"
        "{:.6f}\n",
        Quote(r.material), Quote(r.kind), Quote(r.model), Quote(r.budget), r.status, r.fit_samples,
        r.iterations, r.prepare_ms, r.solve_ms, r.solve_cpu_ms, r.log_rmse, r.cbrt_rmse, r.rel_l2,
        r.log_rmse_ratio, r.cbrt_rmse_ratio, r.rel_l2_ratio);
  }
  return s;
}

}  // namespace brdfit
