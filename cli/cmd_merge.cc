// `brdfit merge OUT.h5 PARTS.h5...`: fit reports (the shards of `brdfit fit --shard I/N`,
// docs/scale.md) into one report, equal to the report of one process doing the same work
// (pipeline/merge_reports.h). The parts are only read.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/error.h"
#include "io/file_lock.h"
#include "io/fit_report.h"
#include "io/output_policy.h"
#include "pipeline/merge_reports.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct MergeCliOptions {
  std::string out;
  std::vector<std::string> parts;
  bool no_timings = false;
  bool quiet = false;
};

int RunMerge(const MergeCliOptions& o) {
  const std::vector<fs::path> parts(o.parts.begin(), o.parts.end());
  for (const fs::path& p : parts) {
    if (!fs::exists(p)) throw InputError(p, "no such fit report");
  }
  CheckOutputs(parts, {{o.out, "OUT"}});
  const OutputLock lock(o.out);  // not while a fit writes it
  const pipeline::MergedReports m = pipeline::MergeFitReports(parts);
  const std::size_t n = m.entries.size();
  std::size_t chosen = 0;
  for (const FitReportEntry& e : m.entries) chosen += e.chosen;
  WriteFitReport(m.entries, o.out, m.timed && !o.no_timings);
  if (!o.quiet) {
    fmt::print(
        "{} fits from {} parts ({} read, {} identical duplicates kept once), {} chosen; "
        "report {}\n",
        n, parts.size(), m.read, m.duplicates, chosen, o.out);
  }
  return kExitOk;
}

Registrar reg{
    "merge", "Merge fit reports (shards of fit --shard) into one report", [](CLI::App& sub) {
      auto o = std::make_shared<MergeCliOptions>();
      sub.add_option("out", o->out, "merged HDF5 fit report (written atomically)")->required();
      sub.add_option("parts", o->parts, "fit reports to merge (only read)")->required();
      sub.add_flag("--no-timings", o->no_timings,
                   "leave timings out (kept by default when the parts have them)");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line");
      sub.footer(
          "Entries are keyed by (source, model, options): identical duplicates are kept once, "
          "different results for one key are refused (exit 2, naming both files). The chosen "
          "fit of each table is marked again over all the merged fits, as one `brdfit fit` "
          "over the same work would have: parts written with --no-timings merge into a "
          "report byte-identical to the single-process --no-timings report.\n"
          "Exit codes: 0 ok, 2 bad input (unreadable part, conflict) or output.\n"
          "Examples:\n"
          "  brdfit merge fits.h5 shard-*.h5\n"
          "  brdfit merge all.h5 day1.h5 day2.h5 --no-timings");
      return [o] { return RunMerge(*o); };
    }};

}  // namespace
}  // namespace brdfit::cli
