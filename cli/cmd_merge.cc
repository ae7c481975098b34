// `brdfit merge OUT PARTS...`: the outputs of shards (docs/scale.md) into the output one
// process doing the same work would have written. The parts' kind decides: fit reports of
// `fit --shard` (pipeline/merge_reports.h), bench CSVs of `bench --shard` (*.csv,
// pipeline/merge_bench.h), output folders of `factor --shard` (folders,
// pipeline/merge_factors.h). The parts are only read.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/error.h"
#include "io/file_lock.h"
#include "io/fit_report.h"
#include "io/output_policy.h"
#include "pipeline/merge_bench.h"
#include "pipeline/merge_factors.h"
#include "pipeline/merge_reports.h"
#include "report/bench_csv.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct MergeCliOptions {
  std::string out;
  std::vector<std::string> parts;
  bool no_timings = false;
  bool quiet = false;
};

enum class PartKind { kFitReports, kBenchCsvs, kFactorFolders };

// All parts folders: factor outputs; all *.csv: bench CSVs; else fit reports. A mix is refused.
PartKind KindOf(const std::vector<fs::path>& parts) {
  std::size_t folders = 0, csvs = 0;
  for (const fs::path& p : parts) {
    if (!fs::exists(p)) throw InputError(p, "no such fit report, bench CSV or folder");
    folders += fs::is_directory(p);
    csvs += p.extension() == ".csv";
  }
  if (folders == parts.size()) return PartKind::kFactorFolders;
  if (csvs == parts.size()) return PartKind::kBenchCsvs;
  if (folders + csvs > 0) {
    const auto kind = [](const fs::path& p) -> std::string {
      return fs::is_directory(p)       ? "a factor folder"
             : p.extension() == ".csv" ? "a bench CSV"
                                       : "a fit report";
    };
    const auto other = std::find_if(parts.begin(), parts.end(),
                                    [&](const fs::path& p) { return kind(p) != kind(parts[0]); });
    throw InputError(fmt::format(
        "merge: the parts mix kinds: {} is {} but {} is {}; give one kind (factor folders, bench "
        "CSVs or fit reports)",
        parts[0].string(), kind(parts[0]), other->string(), kind(*other)));
  }
  return PartKind::kFitReports;
}

int MergeFactors(const MergeCliOptions& o, const std::vector<fs::path>& parts) {
  for (const fs::path& p : parts) {
    std::error_code ec;
    if (fs::equivalent(p, o.out, ec)) throw InputError(p, "is also OUT: merge into a new folder");
  }
  const pipeline::MergedFactors m = pipeline::MergeFactorFolders(o.out, parts);
  if (!o.quiet) {
    fmt::print(
        "{} factorizations ({} files) from {} folders ({} identical files kept once); "
        "folder {}\n",
        m.sidecars, m.files, parts.size(), m.duplicates, o.out);
  }
  return kExitOk;
}

int MergeBench(const MergeCliOptions& o, const std::vector<fs::path>& parts) {
  CheckOutputs(parts, {{o.out, "OUT"}});
  pipeline::MergedBench m = pipeline::MergeBenchCsvs(parts);
  if (o.no_timings) {
    for (auto& b : m.points) b.time_ms = b.prepare_ms = b.init_ms = b.solve_ms = 0;
  }
  report::WriteBenchCsv(o.out, m.points);
  if (!o.quiet) {
    fmt::print("{} bench rows from {} parts ({} read, {} identical duplicates kept once); CSV {}\n",
               m.points.size(), parts.size(), m.read, m.duplicates, o.out);
  }
  return kExitOk;
}

int RunMerge(const MergeCliOptions& o) {
  const std::vector<fs::path> parts(o.parts.begin(), o.parts.end());
  const PartKind kind = KindOf(parts);
  if (kind == PartKind::kFactorFolders) return MergeFactors(o, parts);
  if (kind == PartKind::kBenchCsvs) return MergeBench(o, parts);
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
    "merge", "Merge the outputs of shards (fit reports, bench CSVs, factor folders) into one",
    [](CLI::App& sub) {
      auto o = std::make_shared<MergeCliOptions>();
      sub.add_option("out", o->out,
                     "merged HDF5 fit report, bench CSV, or factor folder (written atomically)")
          ->required();
      sub.add_option("parts", o->parts,
                     "fit reports, bench CSVs (*.csv) or factor output folders (only read)")
          ->required();
      sub.add_flag("--no-timings", o->no_timings,
                   "leave timings out (kept by default when the parts have them)");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line");
      sub.footer(
          "Fit report entries are keyed by (material, model, options), the material being its "
          "key (docs/scale.md, \"Material identity\"): identical duplicates are kept once, "
          "different results for one key are refused (exit 2, naming both files). The chosen "
          "fit of each table is marked again over all the merged fits, as one `brdfit fit` "
          "over the same work would have: parts written with --no-timings merge into a "
          "report byte-identical to the single-process --no-timings report. Bench CSVs: rows "
          "keyed by (material, model, loss, budget), kept once when all but the times agree. "
          "Factor folders: each sidecar and its textures, a file kept once when the bytes "
          "agree. Both byte-identical to one process's output with --no-timings.\n"
          "Exit codes: 0 ok, 2 bad input (unreadable part, conflict) or output.\n"
          "Examples:\n"
          "  brdfit merge fits.h5 shard-*.h5\n"
          "  brdfit merge all.h5 day1.h5 day2.h5 --no-timings\n"
          "  brdfit merge bench.csv bench-*.csv\n"
          "  brdfit merge factors factors-0 factors-1 factors-2");
      return [o] { return RunMerge(*o); };
    }};

}  // namespace
}  // namespace brdfit::cli
