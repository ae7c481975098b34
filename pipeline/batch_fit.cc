#include "pipeline/batch_fit.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>
#include <thread>
#include <tuple>

#include "core/error.h"
#include "core/model_choice.h"
#include "core/provenance.h"
#include "core/suggest.h"
#include "fit/fitter.h"
#include "fit/prepare_cache.h"
#include "models/registry.h"
#include "pipeline/batch_hold.h"
#include "pipeline/batch_schedule.h"
#include "pipeline/factor_candidate.h"
#include "pipeline/inputs.h"
#include "pipeline/material_keys.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Task {
  std::size_t input;
  TaskKind kind;
  std::string model;    // the entry's model: a catalog model, or a factorization's
  FitOptions fit;       // the request's, with the run's own loss if it has one
  std::string options;  // OptionsJson of the fit (FactorizationOptionsJson of a factorization)
};

// An input loaded and prepared once, shared by the tasks of its model runs; freed after the
// last.
struct InputState {
  std::mutex mu;
  bool ready = false;
  std::optional<PreparedTable> prepared;  // when the input has fits to make
  std::optional<Table> table;             // kept while a factorization of it is to be made
  std::array<int, 2> left{};              // tasks of the input left, per TaskKind (mu)
  std::string error;                      // InputError message if loading failed
  double load_ms = 0, prepare_ms = 0;
  std::string content_hash;  // core/provenance.h TableContentHash
  std::atomic<int> remaining{0};
};

int& TasksLeft(InputState& st, TaskKind kind) {
  return st.left[static_cast<std::size_t>(kind)];
}

// What every task of a batch shares besides its input.
struct TaskContext {
  const BatchFitRequest& req;
  const std::vector<std::string>& keys;  // material key per input
  PrepareCache* prepare_cache;           // nullptr: a table fitted alone (nothing to share)
  FactorSystemCache* factor_cache;
  bool single_input;  // one input has tasks: the factor systems go after it
};

// Loads and prepares the task's input once (under st.mu): the table is kept while a
// factorization of it is to be made, its samples while fits are. A failure to load is the
// input's error, reported once its last task is done.
void LoadInputOnce(const Task& t, InputState& st, const TaskContext& c, BatchSchedule& schedule) {
  std::lock_guard<std::mutex> lock(st.mu);
  if (st.ready) return;
  const std::string& input = c.req.inputs[t.input];
  try {
    auto t0 = Clock::now();
    Table table = LoadInput(input);
    st.content_hash = TableContentHash(table);
    st.load_ms = MsSince(t0);
    t0 = Clock::now();
    const bool fits = TasksLeft(st, TaskKind::kFit) > 0;
    if (TasksLeft(st, TaskKind::kFactor) > 0) {
      st.table.emplace(std::move(table));
      if (fits)
        st.prepared.emplace(PrepareTable(*st.table, c.req.samples, c.req.fit, c.prepare_cache));
    } else {
      st.prepared.emplace(
          PrepareTable(std::move(table), c.req.samples, c.req.fit, c.prepare_cache));
    }
    st.prepare_ms = MsSince(t0);
  } catch (const InputError& e) {
    st.error = e.what();
  } catch (const std::exception& e) {  // e.g. out of memory: reported, not fatal
    st.error = input + ": " + e.what();
  }
  st.ready = true;
  schedule.MarkLoaded(t.input);
}

// A fit of the task's model to its prepared input; the prepared samples go with the input's
// last fit, before a factorization of it that may still run (peak memory).
FitReportEntry RunFitTask(const Task& t, InputState& st, const TaskContext& c) {
  FitResult r;
  try {
    r = FitPrepared(t.model, *st.prepared, t.fit);
  } catch (const std::exception& ex) {  // never expected; a failed entry, not a crash
    r = FitResult{};
    r.model = t.model;
    r.status = FitStatus::kFailed;
    r.message = std::string("internal error: ") + ex.what();
  }
  r.times.load = st.load_ms;
  r.times.prepare = st.prepare_ms;
  {
    std::lock_guard<std::mutex> lock(st.mu);
    if (--TasksLeft(st, TaskKind::kFit) == 0) st.prepared.reset();
  }
  FitReportEntry e;
  e.source = c.req.inputs[t.input];
  e.material = c.keys[t.input];
  e.options = t.options;
  e.result = std::move(r);
  e.source_hash = st.content_hash;
  return e;
}

// The input's factorization (pipeline/factor_candidate.h); the table goes after it.
FitReportEntry RunFactorTask(const Task& t, InputState& st, const TaskContext& c) {
  FitReportEntry e;
  try {
    e = FactorizationEntry({&*st.table, c.req.inputs[t.input], c.keys[t.input], st.content_hash,
                            c.req.samples, FactorizationFolder(c.req.report), c.req.timings,
                            c.factor_cache, /*last=*/c.single_input});
  } catch (const std::exception& ex) {  // never expected; a failed entry, not a crash
    e = NewFactorizationEntry(c.req.inputs[t.input], c.keys[t.input], t.options, st.content_hash);
    e.result.status = FitStatus::kFailed;
    e.result.message = std::string("internal error: ") + ex.what();
  }
  {
    std::lock_guard<std::mutex> lock(st.mu);
    if (--TasksLeft(st, TaskKind::kFactor) == 0) st.table.reset();
  }
  e.result.times.load = st.load_ms;
  return e;
}

// The report's entries (none when it does not exist). `force` redoes this run's fits; it does
// not drop the report's other fits: only a report that cannot be read is replaced whole.
std::vector<FitReportEntry> ReadKept(const fs::path& report, bool force) {
  if (!fs::exists(report)) return {};
  try {
    return ReadFitReport(report);
  } catch (const InputError& e) {
    if (force) return {};
    throw InputError(report, std::string("exists but is not a readable fit report (use --force "
                                         "to overwrite): ") +
                                 e.what());
  }
}

// The diffuse bodies `--diffuse` may name, and the single models that carry a diffuse term of
// their own (ue4's (1 - m) base / pi): neither is a bare specular name.
constexpr std::array<std::string_view, 5> kDiffuseModels = {"lambert", "oren-nayar", "burley",
                                                            "oren-nayar-fujii", "burley-2012"};
constexpr std::array<std::string_view, 1> kOwnDiffuseModels = {"ue4"};

bool IsDiffuseModel(std::string_view name) {
  return std::find(kDiffuseModels.begin(), kDiffuseModels.end(), name) != kDiffuseModels.end();
}

// A name without a diffuse lobe: one specular lobe or a sum of them ("ggx", "ggx+ggx").
bool IsBareSpecular(const std::string& name) {
  const std::string first = name.substr(0, name.find('+'));
  return !IsDiffuseModel(first) && std::find(kOwnDiffuseModels.begin(), kOwnDiffuseModels.end(),
                                             first) == kOwnDiffuseModels.end();
}

// The specular parts S of the catalog's "diffuse+S" sums, for the error message.
std::string SpecularPartsOf(const std::string& diffuse) {
  std::string out;
  for (const std::string& k : FittableModels()) {
    if (k.rfind(diffuse + "+", 0) == 0)
      out += (out.empty() ? "" : ", ") + k.substr(diffuse.size() + 1);
  }
  return out;
}

// MarkChosenFits, then no mark on the materials split over shards.
void MarkShardChosenFits(std::vector<FitReportEntry>& entries,
                         const std::set<std::string>& split_materials) {
  MarkChosenFits(entries);
  if (split_materials.empty()) return;
  for (FitReportEntry& e : entries) {
    if (!split_materials.count(e.material)) continue;
    e.chosen = false;
    e.choice.clear();
  }
}

// The run's input of each material key, and the input a kept entry of one of these keys but of
// another source would be mistaken for (nullptr when the entry is of no key or of its source).
using SourceOfKey = std::map<std::string, const std::string*>;
SourceOfKey SourcesOfKeys(const std::vector<std::string>& inputs,
                          const std::vector<std::string>& keys) {
  SourceOfKey source_of;
  for (std::size_t f = 0; f < inputs.size(); ++f) source_of[keys[f]] = &inputs[f];
  return source_of;
}
const std::string* OfAnotherSource(const FitReportEntry& e, const SourceOfKey& source_of) {
  const auto it = source_of.find(e.material);
  return it == source_of.end() || e.source == *it->second ? nullptr : it->second;
}

// A report holds one source per material key: a kept entry of one of this run's keys but of
// another source (b/x.binary fitted into a report of a/x.binary, both "x") would be mistaken for
// it. InputError naming both.
void CheckKeptMaterials(const std::vector<FitReportEntry>& kept,
                        const std::vector<std::string>& inputs,
                        const std::vector<std::string>& keys, const fs::path& report) {
  const SourceOfKey source_of = SourcesOfKeys(inputs, keys);
  for (const FitReportEntry& e : kept) {
    const std::string* input = OfAnotherSource(e, source_of);
    if (!input) continue;
    throw InputError(report, "holds material '" + e.material + "' fitted from " + e.source +
                                 ", and this run's " + *input +
                                 " has the same material key (docs/scale.md, \"Material "
                                 "identity\"): write another report (-o), give both tables in one "
                                 "run, or --force");
  }
}

// Resume keeps a fit only of the table it was made from: the material keys of this run's
// inputs whose kept entries record another content hash (core/provenance.h TableContentHash)
// than the table has now, e.g. a table regenerated under the same name. Their fits are made
// again and replace the old entries; each is said in result->changed_sources. Entries without
// a hash (older reports) cannot be compared and are kept. An input that cannot be loaded any
// more is an input error of the run (not hidden behind "skipped"); its kept fits stay.
std::set<std::string> ChangedSources(const std::vector<FitReportEntry>& kept,
                                     const std::vector<std::string>& inputs,
                                     const std::vector<std::string>& keys, BatchFitResult* result) {
  std::map<std::string, std::string> hash_of;  // key -> the hash its kept entries record
  for (const FitReportEntry& e : kept) {
    if (!e.source_hash.empty()) hash_of.emplace(e.material, e.source_hash);
  }
  std::set<std::string> changed;
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    const auto it = hash_of.find(keys[f]);
    if (it == hash_of.end()) continue;
    std::string now;
    try {
      now = TableContentHash(LoadInput(inputs[f]));
    } catch (const InputError& e) {
      result->input_errors.push_back(e.what());  // its kept fits stay; nothing is refitted
      continue;
    }
    if (now == it->second) continue;
    changed.insert(keys[f]);
    result->changed_sources.push_back(
        inputs[f] + ": its contents changed since the report's fits (content hash " + it->second +
        ", now " + now + "): fitted again");
  }
  return changed;
}

}  // namespace

std::vector<std::string> ResolveModelNames(const std::vector<std::string>& requested,
                                           const std::string& diffuse) {
  if (diffuse != "none" && !IsDiffuseModel(diffuse)) {
    throw InputError("--diffuse '" + diffuse +
                     "' is not a diffuse model (expected none, lambert, oren-nayar, burley, "
                     "oren-nayar-fujii or burley-2012)");
  }
  std::vector<std::string> out;
  for (const std::string& n : requested) {
    if (n.empty()) continue;
    std::string name = n;
    if (const auto colon = n.find(':'); colon != std::string::npos) {
      const std::string base = n.substr(0, colon), count = n.substr(colon + 1);
      const bool digits =
          !count.empty() && count.size() <= 2 && std::all_of(count.begin(), count.end(), ::isdigit);
      const int lobes = digits ? std::stoi(count) : 0;
      if (base.empty() || lobes < 1) {
        throw InputError("model '" + n + "': expected NAME:N with N >= 1 lobes");
      }
      name = base;
      for (int k = 1; k < lobes; ++k) name += "+" + base;
    }
    // Every bare specular name gets the diffuse lobe, or is refused: fitting it alone would
    // silently drop the diffuse part of the material.
    if (diffuse != "none" && IsBareSpecular(name)) {
      if (IsFittable(diffuse + "+" + name)) {
        name = diffuse + "+" + name;
      } else if (IsFittable(name)) {
        throw InputError("model '" + n + "' with --diffuse " + diffuse + ": the catalog has no " +
                         diffuse + "+" + name + " (" + diffuse +
                         "+ pairs with: " + SpecularPartsOf(diffuse) + "); --diffuse none fits " +
                         name + " without a diffuse lobe");
      }
    }
    if (!IsFittable(name)) {
      std::string known;
      for (const auto& k : FittableModels()) known += (known.empty() ? "" : ", ") + k;
      throw InputError("unknown model '" + n + "'" + SuggestionAfter(n, FittableModels()) +
                       " (known: " + known + ")");
    }
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  }
  if (out.empty()) throw InputError("--model: no model given");
  return out;
}

std::vector<ModelRun> ResolveModelRuns(const std::vector<std::string>& requested,
                                       const std::string& diffuse, bool loss_given) {
  std::vector<ModelRun> out;
  auto add = [&](const ModelRun& run) {
    for (const ModelRun& m : out) {
      if (m.model == run.model && m.loss == run.loss) return;
    }
    out.push_back(run);
  };
  for (const std::string& n : requested) {
    if (IsFactorizationModel(n)) {
      add({n, std::nullopt, TaskKind::kFactor});  // pipeline/factor_candidate.h: no loss
      continue;
    }
    if (n != "auto") {
      if (n.empty()) continue;
      add({ResolveModelNames({n}, diffuse).front(), std::nullopt});
      continue;
    }
    for (const ModelRun& c : kAutoCandidates) {
      // With --loss given, every candidate is fitted under it.
      add({c.model, loss_given ? std::nullopt : c.loss});
    }
  }
  if (out.empty()) throw InputError("--model: no model given");
  return out;
}

BatchFitResult RunBatchFit(const BatchFitRequest& req, const BatchProgress& on_start) {
  if (req.inputs.empty()) throw InputError("no input files");
  if (req.models.empty()) throw InputError("no model to fit");
  if (req.jobs < 1 || req.jobs > 256) throw InputError("jobs must be in [1, 256]");
  // The options of each model run: the request's, with the run's loss where it has one.
  std::vector<FitOptions> run_fit;
  std::vector<std::string> run_options;
  for (const ModelRun& m : req.models) {
    FitOptions fo = req.fit;
    if (m.loss) fo.loss = *m.loss;
    run_fit.push_back(fo);
    run_options.push_back(m.kind == TaskKind::kFactor ? FactorizationOptionsJson(req.samples)
                                                      : OptionsJson(req.samples, fo));
  }
  const std::vector<std::string>& inputs = req.inputs;
  // Fits are identified by (material key, model, options) (pipeline/material_keys.h).
  const std::vector<std::string> keys = MaterialKeys(inputs);

  // Resume: keep what the report holds; skip fits already done with the same options.
  std::vector<FitReportEntry> kept = ReadKept(req.report, req.force);
  if (req.on_report_written) req.on_report_written(kept.size());  // reliability hook
  const BatchHold hold = BatchHold::FromEnvironment();            // tests only (batch_hold.h)
  hold.HoldAt(0);
  BatchFitResult result;
  std::set<std::tuple<std::string, std::string, std::string>> done;
  if (req.force) {
    // Every fit of the run is redone; entries of its keys from another table go (they would
    // be mistaken for this run's material).
    const SourceOfKey source_of = SourcesOfKeys(inputs, keys);
    std::erase_if(
        kept, [&](const FitReportEntry& e) { return OfAnotherSource(e, source_of) != nullptr; });
  } else {
    CheckKeptMaterials(kept, inputs, keys, req.report);
    const std::set<std::string> changed = ChangedSources(kept, inputs, keys, &result);
    for (const auto& e : kept) {
      if (!e.result.Failed() && !changed.count(e.material)) {
        done.insert({e.material, e.result.model, e.options});
      }
    }
  }
  // The shard's slice of the work list, before resuming: it never depends on what is done.
  std::vector<ShardRun> shard_runs;
  for (std::size_t k = 0; k < req.models.size(); ++k) {
    shard_runs.push_back({req.models[k].model, run_options[k]});
  }
  const std::vector<bool> in_shard = ShardMembership(keys, shard_runs, req.shard);
  std::set<std::string> split_materials;  // materials with fits in this shard and in others
  std::vector<Task> tasks;
  std::vector<std::unique_ptr<InputState>> states;
  for (std::size_t f = 0; f < inputs.size(); ++f) {
    states.push_back(std::make_unique<InputState>());
    const auto row = in_shard.begin() + static_cast<std::ptrdiff_t>(f * req.models.size());
    const auto n_in = std::count(row, row + static_cast<std::ptrdiff_t>(req.models.size()), true);
    if (n_in > 0 && n_in < static_cast<std::ptrdiff_t>(req.models.size())) {
      split_materials.insert(keys[f]);
    }
    for (std::size_t k = 0; k < req.models.size(); ++k) {
      const std::string& m = req.models[k].model;
      if (!in_shard[f * req.models.size() + k]) {
        ++result.other_shards;
        continue;
      }
      if (done.count({keys[f], m, run_options[k]})) {
        ++result.skipped;
        continue;
      }
      tasks.push_back({f, req.models[k].kind, m, run_fit[k], run_options[k]});
      ++states[f]->remaining;
      ++TasksLeft(*states[f], req.models[k].kind);
    }
  }
  result.planned = tasks.size();
  std::set<std::tuple<std::string, std::string, std::string>> planned_keys;
  for (const Task& t : tasks) planned_keys.insert({keys[t.input], t.model, t.options});
  // Entries replaced by this run leave the kept set.
  std::erase_if(kept, [&](const FitReportEntry& e) {
    return planned_keys.count({e.material, e.result.model, e.options}) > 0;
  });

  std::mutex mu;                   // guards result, progress, checkpoints and write_error
  std::exception_ptr write_error;  // a failed checkpoint's OutputError
  auto last_write = Clock::now();
  auto write_report = [&](bool final) {
    std::vector<FitReportEntry> all = kept;
    all.insert(all.end(), result.fresh.begin(), result.fresh.end());
    // Nothing fitted (every input unreadable) and no report before: none is written.
    std::error_code ec;
    if (final && all.empty() && !fs::exists(req.report, ec)) return;
    MarkShardChosenFits(all, split_materials);
    const std::size_t entries = all.size();
    WriteFitReport(std::move(all), req.report, req.timings);
    if (req.on_report_written) req.on_report_written(entries);  // reliability hook
    if (!final) last_write = Clock::now();
  };

  // The per-grid work of preparing a table (sample and rendered-metric plans), made once for
  // the batch's tables of one grid and shared by the workers (fit/prepare_cache.h). A table
  // fitted alone is prepared without it: nothing to share, and its plan would add 15 MB to the
  // peak (docs/fitting.md, "Memory").
  PrepareCache prepare_cache;
  const auto inputs_fitted =
      std::count_if(states.begin(), states.end(), [](const auto& st) { return st->remaining > 0; });
  PrepareCache* const cache = inputs_fitted > 1 ? &prepare_cache : nullptr;
  // The factorizations' systems (~100 MB each on the MERL grid): one per parameterization,
  // shared by the workers from table to table; a single table drops them when done.
  FactorSystemCache factor_cache(/*capacity=*/2);
  std::vector<std::size_t> task_inputs;
  for (const Task& t : tasks) task_inputs.push_back(t.input);
  BatchSchedule schedule(std::move(task_inputs));
  const TaskContext context{req, keys, cache, &factor_cache, inputs_fitted == 1};
  auto worker = [&] {
    while (true) {
      const std::optional<std::size_t> i = schedule.Next();
      if (!i) return;
      const Task& t = tasks[*i];
      InputState& st = *states[t.input];
      if (on_start) {
        std::lock_guard<std::mutex> lock(mu);
        on_start(tasks.size(), keys[t.input] + " " + t.model);
      }
      LoadInputOnce(t, st, context, schedule);
      if (st.error.empty()) {
        FitReportEntry e = t.kind == TaskKind::kFactor ? RunFactorTask(t, st, context)
                                                       : RunFitTask(t, st, context);
        std::lock_guard<std::mutex> lock(mu);
        {
          if (req.on_fit_done) req.on_fit_done(e);
          result.fresh.push_back(std::move(e));
          const std::size_t fits_done = result.fresh.size();
          if (!write_error && (MsSince(last_write) > 5000 || hold.CheckpointAfter(fits_done))) {
            // A checkpoint that cannot be written (a full disk) ends the run: no fit after it
            // could be kept. The error is raised once the workers stopped.
            try {
              write_report(false);  // checkpoint for resuming
            } catch (const OutputError&) {
              write_error = std::current_exception();
              schedule.Stop();
            }
          }
          hold.HoldAt(fits_done);
        }
      }
      if (--st.remaining == 0) {
        std::lock_guard<std::mutex> lock(st.mu);
        if (!st.error.empty()) {
          std::lock_guard<std::mutex> lock2(mu);
          result.input_errors.push_back(st.error);
        }
        st.prepared.reset();
      }
    }
  };
  std::vector<std::thread> pool;
  const int n_workers =
      std::min<int>(req.jobs, static_cast<int>(std::max<std::size_t>(tasks.size(), 1)));
  for (int j = 0; j < n_workers; ++j) pool.emplace_back(worker);
  for (auto& th : pool) th.join();
  if (write_error) std::rethrow_exception(write_error);

  write_report(true);
  result.all = kept;
  result.all.insert(result.all.end(), result.fresh.begin(), result.fresh.end());
  MarkShardChosenFits(result.all, split_materials);
  SortEntries(result.all);
  // The fresh entries carry the same marks as in the report.
  result.fresh.clear();
  for (const FitReportEntry& e : result.all) {
    if (!planned_keys.count({e.material, e.result.model, e.options})) continue;
    result.fresh.push_back(e);
  }
  std::sort(result.input_errors.begin(), result.input_errors.end());
  result.input_errors.erase(std::unique(result.input_errors.begin(), result.input_errors.end()),
                            result.input_errors.end());
  return result;
}

void MarkChosenFits(std::vector<FitReportEntry>& entries) {
  std::map<std::string, std::vector<std::size_t>> by_material;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    entries[i].chosen = false;
    entries[i].choice.clear();
    by_material[entries[i].material].push_back(i);
  }
  for (const auto& [material, indices] : by_material) {
    std::vector<ChoiceCandidate> fits;
    for (std::size_t i : indices) {
      const FitReportEntry& e = entries[i];
      fits.push_back({&e.result, e.ParameterCount(),
                      e.factorization ? "factorization " + e.factorization->form : e.result.model});
    }
    const std::optional<ModelChoice> c = ChooseCandidate(fits);
    if (!c) continue;
    FitReportEntry& e = entries[indices[c->index]];
    e.chosen = true;
    e.choice = c->reason;
  }
}

}  // namespace brdfit::pipeline
