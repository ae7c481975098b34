// The batch fit runner behind `brdfit fit`: every (input, model) pair of a request, fitted in
// parallel, resumable and checkpointed into one HDF5 fit report (docs/formats.md).
//
//  * Parallel over (input, model) with `jobs` workers; each input is loaded and prepared once
//    (fit/fitter.h PrepareTable), shared by its models' fits, and freed after its last fit.
//  * Resume: entries already in the report with the same source, model and options are kept
//    and skipped (unless `force`); entries this run redoes replace the old ones.
//  * Checkpoints: the report is rewritten (atomically, io/atomic_file.h) at most every 5 s
//    while fits finish, and once at the end, so a killed run loses at most the fits in flight.
//  * A table that cannot be loaded is an input error of the batch (reported, not thrown); a
//    fit that fails is a failed entry, never an exception.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "fit/options.h"
#include "fit/samples.h"
#include "io/fit_report.h"

namespace brdfit::pipeline {

struct BatchFitRequest {
  std::vector<std::string> inputs;  // expanded inputs (pipeline/inputs.h ExpandInputs)
  std::vector<std::string> models;  // registry names (ResolveModelNames)
  SampleOptions samples;
  FitOptions fit;
  std::filesystem::path report;  // resumed from when it exists, and written
  bool force = false;            // redo fits the report already holds
  bool timings = true;           // false: no timings in the report (byte-identical reruns)
  int jobs = 1;                  // fits in parallel
};

struct BatchFitResult {
  std::vector<FitReportEntry> fresh;      // fits made by this run, sorted (SortEntries)
  std::vector<FitReportEntry> all;        // what the report holds now: kept + fresh
  std::vector<std::string> input_errors;  // one message per unreadable input, sorted
  std::size_t skipped = 0;                // (input, model) pairs already in the report
  std::size_t planned = 0;                // fits this run set out to make
};

// Called (serialized) as each fit starts, with the number of fits this run makes and a label
// "material model".
using BatchProgress = std::function<void(std::size_t planned, const std::string& label)>;

// Throws InputError for an invalid request (no inputs or models, jobs outside [1, 256], an
// existing report that is not readable without `force`); OutputError if the report cannot be
// written.
BatchFitResult RunBatchFit(const BatchFitRequest& request, const BatchProgress& on_start = nullptr);

// Marks, per source, the fit core/model_choice.h recommends among the entries of that source
// (`chosen`, with the reason in `choice`); clears every other mark. RunBatchFit does it before
// every write, over everything the report holds.
void MarkChosenFits(std::vector<FitReportEntry>& entries);

// Model names as `brdfit fit --model` takes them: "NAME:N" is N lobes of NAME
// ("lafortune:2" -> "lafortune+lafortune"); then, with diffuse D other than "none", a name N
// becomes "D+N" when the catalog has it (measured materials have a diffuse part). Names that
// already include a diffuse lobe, diffuse models, and names without a "D+N" entry stay as
// given; duplicates are dropped. Throws InputError for an unknown name or diffuse model.
std::vector<std::string> ResolveModelNames(const std::vector<std::string>& requested,
                                           const std::string& diffuse);

}  // namespace brdfit::pipeline
