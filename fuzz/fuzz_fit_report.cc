// Fuzz harness: HDF5 fit reports (io/fit_report.h, ReadFitReport), as `brdfit fit` reads them
// to resume and `brdfit report`/`compare`/`render` read them. The input is the whole file.
// After a successful read: FitResult's contract (no NaN or Inf anywhere, names match values),
// FitParamsJson works on the entries (what `brdfit fit --json` does with kept entries), and
// write -> read -> write gives the same bytes.
#include <hdf5.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "fuzz/harness_util.h"
#include "core/error.h"
#include "io/fit_report.h"

namespace brdfit::fuzz {

namespace {

void CheckEntry(const FitReportEntry& e) {
  const FitResult& r = e.result;
  CheckInvariant(r.params.size() == r.param_names.size(), "names and values differ in number");
  CheckInvariant(r.at_bound.size() == r.params.size(), "at_bound size");
  for (double p : r.params) CheckInvariant(std::isfinite(p), "non-finite parameter");
  const FitMetrics& m = r.metrics;
  for (double v : {r.init_cost, r.final_cost, m.log_rmse, m.cbrt_rmse, m.rel_l2, m.total_weight,
                   m.cutoff_deg, m.worst.theta_i_deg, m.worst.theta_o_deg, m.worst.log_error,
                   r.times.load, r.times.solve}) {
    CheckInvariant(std::isfinite(v), "non-finite value in an entry");
  }
  for (int c = 0; c < 3; ++c) {
    CheckInvariant(std::isfinite(m.worst.measured[c]) && std::isfinite(m.worst.predicted[c]),
                   "non-finite worst cell");
  }
}

void CheckNothingOpen() {
  const ssize_t objects = H5Fget_obj_count(
      H5F_OBJ_ALL, H5F_OBJ_FILE | H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_ATTR);
  if (objects != 0) Violation("HDF5 objects left open: " + std::to_string(objects));
  if (OpenFdCount() != 0) Violation("file descriptors left open on the input");
}

}  // namespace

int FuzzFitReport(const std::uint8_t* data, std::size_t size) {
  const auto path = WriteScratch("report-in.h5", data, size);
  std::vector<FitReportEntry> entries;
  try {
    entries = ReadFitReport(path);
  } catch (const InputError&) {
    CheckNothingOpen();
    return 0;
  }
  CheckNothingOpen();
  for (const auto& e : entries) CheckEntry(e);
  (void)FitParamsJson(entries);  // must not throw on anything the reader accepted

  const auto out1 = ScratchDir() / "report-1.h5", out2 = ScratchDir() / "report-2.h5";
  // The two writes may fall in different seconds: a fixed date (core/provenance.h) keeps the
  // round trip byte-comparable with the run details written.
  setenv("SOURCE_DATE_EPOCH", "1764633600", 1);
  WriteFitReport(entries, out1);
  WriteFitReport(ReadFitReport(out1), out2);
  if (ReadAllBytes(out1) != ReadAllBytes(out2)) Violation("write -> read -> write changed bytes");
  return 0;
}

}  // namespace brdfit::fuzz

BRDFIT_FUZZ_ENTRY(brdfit::fuzz::FuzzFitReport)
