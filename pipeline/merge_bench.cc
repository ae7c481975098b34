#include "pipeline/merge_bench.h"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "report/bench_csv.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;

using Key = std::tuple<std::string, std::string, std::string, std::string>;

// The row as the CSV writes it, times zeroed: what two runs of one fit must agree on.
std::string Untimed(report::BenchPoint b) {
  b.time_ms = b.prepare_ms = b.init_ms = b.solve_ms = 0;
  return report::BenchCsvText({b});
}

}  // namespace

void SortBenchPoints(std::vector<report::BenchPoint>& points) {
  std::stable_sort(points.begin(), points.end(),
                   [](const auto& a, const auto& b) { return a.material < b.material; });
}

MergedBench MergeBenchCsvs(const std::vector<fs::path>& parts) {
  if (parts.empty()) throw InputError("merge: no bench CSV to merge");
  MergedBench out;
  std::map<Key, std::pair<std::size_t, std::size_t>> seen;              // key -> point, part
  std::map<std::string, std::pair<std::string, std::size_t>> table_of;  // material -> table, part
  for (std::size_t p = 0; p < parts.size(); ++p) {
    std::vector<report::BenchPoint> rows = report::ReadBenchCsv(parts[p]);
    out.read += rows.size();
    for (report::BenchPoint& b : rows) {
      const auto [t, fresh_material] = table_of.emplace(b.material, std::make_pair(b.table, p));
      if (!fresh_material && t->second.first != b.table) {
        throw InputError(fmt::format(
            "material '{}' is {} in {} but {} in {}: two tables under one material key; "
            "refusing to merge",
            b.material, t->second.first, parts[t->second.second].string(), b.table,
            parts[p].string()));
      }
      const Key key{b.material, b.model, b.loss, b.budget};
      const auto it = seen.find(key);
      if (it == seen.end()) {
        seen.emplace(key, std::make_pair(out.points.size(), p));
        out.points.push_back(std::move(b));
        continue;
      }
      const report::BenchPoint& kept = out.points[it->second.first];
      if (Untimed(kept) != Untimed(b)) {
        throw InputError(fmt::format(
            "conflicting bench rows of {} with model {}, loss {}, budget {}: {} and {} hold "
            "different results (log_rmse {} vs {}, status {} vs {}); refusing to merge",
            b.material, b.model, b.loss, b.budget, parts[it->second.second].string(),
            parts[p].string(), kept.metrics.log_rmse, b.metrics.log_rmse, kept.status, b.status));
      }
      ++out.duplicates;
    }
  }
  SortBenchPoints(out.points);
  return out;
}

}  // namespace brdfit::pipeline
