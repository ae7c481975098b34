// The batch fit runner behind `brdfit fit`: every (input, model) pair of a request, fitted in
// parallel, resumable and checkpointed into one HDF5 fit report (docs/formats.md).
//
//  * Parallel over (input, model) with `jobs` workers; each input is loaded and prepared once
//    (fit/fitter.h PrepareTable), shared by its models' fits, and freed after its last fit;
//    what depends only on the grid (fit/prepare_cache.h) is made once for the whole batch.
//  * Fits are identified by (material key, model, options): the key is unique in the batch and
//    the same on every machine (pipeline/material_keys.h); a report holds one source per key.
//  * Resume: entries already in the report with the same key, model and options, fitted to
//    the same table contents (their source_hash), are kept and skipped (unless `force`);
//    entries this run redoes replace the old ones, and a table whose contents changed since is
//    fitted again (docs/scale.md, "Resume"). A kept entry of
//    one of the run's keys but another source is an InputError (the report is not resumed).
//  * Checkpoints: the report is rewritten (atomically, io/atomic_file.h) at most every 5 s
//    while fits finish, and once at the end, so a killed run loses at most the fits in flight.
//  * A table that cannot be loaded is an input error of the batch (reported, not thrown); a
//    fit that fails is a failed entry, never an exception.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fit/options.h"
#include "fit/samples.h"
#include "io/fit_report.h"
#include "pipeline/shard.h"

namespace brdfit::pipeline {

// What a run makes of each input: a fit of an analytic model, or the table's factorization
// (pipeline/factor_candidate.h), a candidate of the model choice like the fits.
enum class TaskKind { kFit, kFactor };

// One model to fit to every input, under the request's loss or its own, or the factorization.
struct ModelRun {
  std::string model;             // registry name (ResolveModelNames), or the entries' model
                                 // name of a factorization (io/fit_report.h)
  std::optional<LossKind> loss;  // nullopt: BatchFitRequest::fit.loss
  TaskKind kind = TaskKind::kFit;
  bool operator==(const ModelRun&) const = default;
};

// The candidates of `brdfit fit --model auto`, each under the loss that served it best in the
// study of docs/accuracy.md ("Choosing the model, with the rendered polish"): over the 100 MERL
// proxies, the first four (model, loss) pairs added greedily, by the mean rendered score of
// each material's choice (core/model_choice.h), from eight models and two losses, every fit
// polished. Against the five of the unpolished study they score the same mean (43.99 against
// 44.00 dB), reach 30 dB on two more materials, and cost two thirds of the time. The fifth,
// a sheen lobe over lambert+ggx ("Cloth: a sheen lobe"), is chosen on cloth only: it raises
// the worst fabric by 1.4 dB for 15 % more time. The rough bodies are the forms Blender Cycles
// evaluates (Burley 2012, Fujii's Oren-Nayar; "The rough bodies Blender evaluates"), which
// render as the Frostbite and qualitative forms did under held-out light (-0.05 dB of S over
// the 100 proxies) and export exactly.
inline const std::vector<ModelRun> kAutoCandidates = {
    {"lambert+ggx+ggx", LossKind::kRel},   {"burley-2012+ggx", LossKind::kRel},
    {"lambert+abc", LossKind::kRel},       {"oren-nayar-fujii+ggx", LossKind::kRel},
    {"lambert+ggx+sheen", LossKind::kRel},
};

struct BatchFitRequest {
  std::vector<std::string> inputs;  // expanded inputs (pipeline/inputs.h ExpandInputs)
  std::vector<ModelRun> models;     // ResolveModelRuns
  SampleOptions samples;
  FitOptions fit;
  std::filesystem::path report;  // resumed from when it exists, and written
  bool force = false;  // redo this run's fits even where the report holds them (others stay)
  bool timings = true;           // false: no timings in the report (byte-identical reruns)
  int jobs = 1;                  // fits in parallel
  // Only this shard's slice of the (input x model run) work list (pipeline/shard.h). A material
  // whose fits are split over shards gets no `chosen` mark here (the shard cannot know the
  // choice among fits it does not hold): `brdfit merge` marks it over all the fits.
  Shard shard;
  // Called (serialized) as each fit finishes, with its entry (chosen not yet marked).
  std::function<void(const FitReportEntry& entry)> on_fit_done;
  // Reliability (cli/cmd_fit.cc's interrupt message): called, serialized, with the number of
  // entries the report on disk holds, once at the start and after every write.
  std::function<void(std::size_t entries)> on_report_written;
};

struct BatchFitResult {
  std::vector<FitReportEntry> fresh;      // fits made by this run, sorted (SortEntries)
  std::vector<FitReportEntry> all;        // what the report holds now: kept + fresh
  std::vector<std::string> input_errors;  // one message per unreadable input, sorted
  // Inputs whose kept fits were of other contents (a table rewritten under the same name):
  // refitted, one message each naming the input and both content hashes.
  std::vector<std::string> changed_sources;
  std::size_t skipped = 0;                // (input, model) pairs already in the report
  std::size_t planned = 0;                // fits this run set out to make
  std::size_t other_shards = 0;           // (input, model) pairs left to the other shards
};

// Called (serialized) as each fit starts, with the number of fits this run makes and a label
// "material model".
using BatchProgress = std::function<void(std::size_t planned, const std::string& label)>;

// Throws InputError for an invalid request (no inputs or models, jobs outside [1, 256], an
// existing report that is not readable without `force`); OutputError if the report cannot be
// written.
BatchFitResult RunBatchFit(const BatchFitRequest& request, const BatchProgress& on_start = nullptr);

// Marks, per material key, the fit core/model_choice.h recommends among the entries of that key
// (`chosen`, with the reason in `choice`); clears every other mark. RunBatchFit does it before
// every write, over everything the report holds (but for the split materials of a shard), and
// `brdfit merge` over everything the merged report holds.
void MarkChosenFits(std::vector<FitReportEntry>& entries);

// Model names as `brdfit fit --model` takes them: "NAME:N" is N lobes of NAME
// ("lafortune:2" -> "lafortune+lafortune"); then, with diffuse D other than "none", a name N
// becomes "D+N" (measured materials have a diffuse part); D is lambert, oren-nayar, burley,
// oren-nayar-fujii or burley-2012.
// Names that already include a diffuse lobe, diffuse models and ue4 (its own diffuse term)
// stay as given; a bare specular name without a "D+N" entry in the catalog is an InputError
// (never fitted without its diffuse lobe unless D is "none"); duplicates are dropped. Throws
// InputError for an unknown name or diffuse model.
std::vector<std::string> ResolveModelNames(const std::vector<std::string>& requested,
                                           const std::string& diffuse);

// The runs of `brdfit fit --model`: each name through ResolveModelNames under the request's
// loss, "auto" as kAutoCandidates (each under its own loss, or all under the request's
// when the user gave one: loss_given), and "factorization" as a TaskKind::kFactor run:
// the table factored as `brdfit factor` does by default, a candidate of the model choice
// (pipeline/factor_candidate.h; its textures go to FactorizationFolder(report)). Duplicate
// runs are dropped.
std::vector<ModelRun> ResolveModelRuns(const std::vector<std::string>& requested,
                                       const std::string& diffuse, bool loss_given);

}  // namespace brdfit::pipeline
