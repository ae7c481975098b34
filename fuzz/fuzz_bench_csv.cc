// Fuzz harness: the bench CSV (report/bench_csv.h, ReadBenchCsv), read by `report` and
// `compare`. The input is the file. After a successful read: every number is finite, times
// and the errors of a usable point are >= 0, and writing the points and reading them back
// gives the same text (the writer's shortest round-trip numbers are read back exactly).
#include <cmath>
#include <string>
#include <vector>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "report/bench_csv.h"

namespace brdfit::fuzz {

namespace {

void CheckPoint(const report::BenchPoint& b) {
  const FitMetrics& m = b.metrics;
  const RenderedError& r = m.rendered;
  for (const double v : {b.time_ms, b.prepare_ms, b.init_ms, b.solve_ms, m.log_rmse, m.cbrt_rmse,
                         m.rel_l2, m.cutoff_deg, r.psnr_db, r.psnr_srgb_db, r.median_rel_error,
                         r.p95_rel_error}) {
    CheckInvariant(std::isfinite(v), "a number that is not finite");
  }
  CheckInvariant(b.time_ms >= 0 && b.prepare_ms >= 0 && b.init_ms >= 0 && b.solve_ms >= 0,
                 "a negative time");
  CheckInvariant(!m.ok || (m.log_rmse >= 0 && m.cbrt_rmse >= 0 && m.rel_l2 >= 0),
                 "a negative error of a usable point");
  CheckInvariant(b.iterations >= 0, "negative iterations");
}

}  // namespace

int FuzzBenchCsv(const std::uint8_t* data, std::size_t size) {
  const auto path = WriteScratch("b.csv", data, size);
  std::vector<report::BenchPoint> points;
  try {
    points = report::ReadBenchCsv(path);
  } catch (const InputError&) {
    return 0;
  }
  for (const auto& b : points) CheckPoint(b);
  const std::string text = report::BenchCsvText(points);
  const auto again = WriteScratch("b2.csv", text.data(), text.size());
  const std::vector<report::BenchPoint> back = report::ReadBenchCsv(again);
  CheckInvariant(back.size() == points.size(), "round trip: number of points");
  CheckInvariant(report::BenchCsvText(back) == text, "round trip: text");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzBenchCsv)
