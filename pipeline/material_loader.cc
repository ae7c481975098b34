#include "pipeline/material_loader.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "factor/factor.h"
#include "factor/factor_form.h"
#include "fit/fitter.h"
#include "fit/options.h"
#include "io/atomic_file.h"
#include "io/fit_cache_entry.h"
#include "io/fit_report.h"
#include "io/nbrdf.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "models/registry.h"
#include "pipeline/cache_key.h"
#include "pipeline/factor_export.h"
#include "pipeline/factor_textures.h"
#include "pipeline/factor_with_choice.h"
#include "pipeline/fit_settings.h"
#include "pipeline/inputs.h"

namespace brdfit::pipeline {
using namespace preview;  // the material types this loader fills in

namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string Fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

// Loads each table file once per render, whatever the number of materials naming it.
class TableCache {
 public:
  explicit TableCache(ExplainLog* log) : log_(log) {}
  std::shared_ptr<const Table> Get(const std::filesystem::path& path) {
    const std::string key = IsNbrdfInput(path.string())
                                ? path.string()
                                : std::filesystem::weakly_canonical(path).string();
    auto it = tables_.find(key);
    if (it != tables_.end()) {
      if (log_) log_->Add("reuse", "table " + path.string() + " (already loaded)");
      return it->second;
    }
    const auto t0 = Clock::now();
    auto t = std::make_shared<const Table>(LoadInput(path.string()));
    if (log_) {
      log_->Add("load", "table " + path.string() + " (" + std::to_string(t->grid.n_theta_h) + "x" +
                            std::to_string(t->grid.n_theta_d) + "x" +
                            std::to_string(t->grid.n_phi_d) + ", " +
                            std::to_string(t->CountValid()) + " valid cells, " + Fmt(MsSince(t0)) +
                            " ms)");
    }
    return tables_.emplace(key, std::move(t)).first->second;
  }

 private:
  ExplainLog* log_;
  std::map<std::string, std::shared_ptr<const Table>> tables_;
};

// The options of `brdfit fit TABLE --model M` with its defaults (pipeline/fit_settings.h): what
// the render cache fits with and keys on.
struct DefaultFitOptions {
  SampleOptions samples;
  FitOptions fit;
  DefaultFitOptions() { ApplyFitSettings(FitSettings{}, &samples, &fit); }
};

// Cache entry of a fit: {"model", "params", "param_names", "status", "source", "key"}.
std::vector<double> FitCached(const MaterialSpec& m, const std::filesystem::path& cache_dir,
                              TableCache* tables, ExplainLog* log) {
  // The fit `brdfit fit TABLE --model M` makes, under FitCacheKey: new defaults or a new engine
  // revision never reuse an old entry.
  const std::string key =
      FitCacheKey(InputContentKey(m.fit_table.string()), m.model, kFitEngineRevision);
  const std::filesystem::path entry = cache_dir / ("fit-" + key + ".json");
  if (std::filesystem::exists(entry)) {
    try {
      const std::vector<double> params = ReadFitCacheEntry(entry, m.model);
      if (log) {
        log->Add("reuse", "fit " + m.model + " of " + m.fit_table.string() + " from cache " +
                              entry.string());
      }
      return params;
    } catch (const InputError& e) {
      // A damaged entry (or another model's under a colliding key) is recomputed and
      // overwritten below.
      if (log) {
        log->Add("note",
                 "cache entry " + entry.string() + " unreadable (" + e.what() + "): recomputing");
      }
    }
  }
  const auto table = tables->Get(m.fit_table);
  const auto t0 = Clock::now();
  const DefaultFitOptions options;
  const FitResult r = FitTable(m.model, *table, options.samples, options.fit);
  if (r.Failed()) {
    throw InputError(m.fit_table,
                     "fit of '" + m.model + "' for material '" + m.name + "' failed: " + r.message);
  }
  FitCacheEntry cached;
  cached.model = r.model;
  cached.params = r.params;
  cached.param_names = r.param_names;
  cached.status = ToString(r.status);
  cached.source = m.fit_table.string();
  cached.key = key;
  MakeOutputFolder(cache_dir);
  WriteTextAtomically(entry, FitCacheEntryJson(cached));
  if (log) {
    log->Add("compute", "fit " + m.model + " of " + m.fit_table.string() + " (" +
                            ToString(r.status) + ", " + Fmt(MsSince(t0)) + " ms) -> " +
                            entry.string());
  }
  return r.params;
}

// Parameters of `model` for `material` from a fit report (io/fit_report.h). The material is
// matched against the entry's material name (its source's stem) or its source path.
std::vector<double> FromReport(const MaterialSpec& m, ExplainLog* log) {
  const auto entries = ReadFitReport(m.fit_report);
  const std::string wanted = m.fit_material.empty() ? m.name : m.fit_material;
  for (const auto& e : entries) {
    if (e.result.model != m.model || (e.material != wanted && e.source != wanted)) continue;
    if (e.result.Failed()) {
      throw InputError(m.fit_report, "entry " + wanted + " / " + m.model + " is a failed fit");
    }
    if (e.factorization) {
      throw InputError(m.fit_report, "entry " + wanted + " / " + m.model +
                                         " is a factorization: name its sidecar as \"factors\": " +
                                         e.factorization->sidecar);
    }
    if (log) {
      log->Add("load", "material '" + m.name + "': " + m.model + " parameters of '" + wanted +
                           "' from report " + m.fit_report.string() + " (" +
                           ToString(e.result.status) + ")");
    }
    return e.result.params;
  }
  throw InputError(m.fit_report, "no fit of model '" + m.model + "' for material '" + wanted + "'");
}

std::shared_ptr<const FactorTextures> FactorCached(const MaterialSpec& m,
                                                   const std::filesystem::path& cache_dir,
                                                   TableCache* tables, ExplainLog* log) {
  if (!m.factors.empty()) {
    auto f = ToFactorTextures(LoadFactoredBrdf(m.factors));
    if (log) {
      log->Add("load",
               "factorization " + m.factors.string() + " (" + FactorFormLabel(f->form()) + ")");
    }
    return f;
  }
  FactorOptions opt;
  opt.param = FactorParamFromString(m.factor_param);
  opt.resolution = m.factor_resolution;
  opt.rank = m.factor_rank;
  opt.diffuse = m.factor_diffuse;
  Fnv1a64 h;
  h.Add(InputContentKey(m.table.string()));
  // Every solver option (defaults included: a changed default never reuses an old entry).
  h.Add(fmt::format("|factor|{}|{}|{:.17g}|{}|{:.17g}|rank {}|diffuse {}|refine {} {} {}",
                    m.factor_param, opt.resolution, opt.lambda, static_cast<int>(opt.weighting),
                    opt.max_theta, opt.rank, opt.diffuse, opt.refine, opt.refine_iterations,
                    opt.refine_rows));
  if (m.factor_auto) {
    for (const FactorCandidate& c : kAutoFactorCandidates) h.Add(std::string("|") + c.name);
  }
  const std::string stem = "factor-" + h.Hex();
  const FactorPaths paths = FactorFilePaths(cache_dir, stem);
  if (std::filesystem::exists(paths.json)) {
    try {
      auto f = ToFactorTextures(LoadFactoredBrdf(paths.json));
      if (log) {
        log->Add("reuse", "factorization " + FactorFormLabel(f->form()) + " " +
                              std::to_string(m.factor_resolution) + " of " + m.table.string() +
                              " from cache " + paths.json.string());
      }
      return f;
    } catch (const InputError&) {
      if (log) log->Add("note", "cache entry " + paths.json.string() + " unreadable: recomputing");
    }
  }
  const auto table = tables->Get(m.table);
  const auto t0 = Clock::now();
  nlohmann::json extra = {{"source", m.table.string()}};
  Factorization r;
  std::string how;
  if (m.factor_auto) {
    // The form `brdfit factor` keeps (pipeline/factor_with_choice.h), its choice in the sidecar.
    FactorSystemCache systems;
    FactorWithChoice c = FactorChoosingForm(*table, opt, &systems, true);
    extra["choice"] = ChoiceJson(c, false);
    how = ", chosen of " + std::to_string(c.scores.size()) + " forms: " + c.reason;
    r = std::move(c.kept);
  } else {
    r = Factor(*table, opt);
  }
  MakeOutputFolder(cache_dir);
  SaveFactorization(r, cache_dir, stem, extra);
  if (log) {
    log->Add("compute", "factorization " + FactorFormLabel(FormOf(r.brdf)) + " " +
                            std::to_string(m.factor_resolution) + " of " + m.table.string() + " (" +
                            Fmt(MsSince(t0)) + " ms" + how + ") -> " + paths.json.string());
  }
  return ToFactorTextures(std::move(r.brdf));
}

}  // namespace

std::string FitCacheKey(const std::string& table_content_key, const std::string& model,
                        int engine_revision) {
  const DefaultFitOptions options;
  Fnv1a64 h;
  h.Add(table_content_key);
  h.Add("|fit|" + model + "|" + OptionsJson(options.samples, options.fit) + "|engine " +
        std::to_string(engine_revision));
  return h.Hex();
}

std::filesystem::path DefaultCacheDir() {
  if (const char* d = std::getenv("BRDFIT_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) {
    return std::filesystem::path(d) / "brdfit";
  }
  if (const char* d = std::getenv("HOME"); d && *d) {
    return std::filesystem::path(d) / ".cache" / "brdfit";
  }
  return std::filesystem::temp_directory_path() / "brdfit-cache";
}

MaterialSet LoadMaterials(const Scene& scene, const std::set<std::string>& used,
                          const LoadOptions& options, ExplainLog* log) {
  const std::filesystem::path cache_dir =
      options.cache_dir.empty() ? DefaultCacheDir() : options.cache_dir;
  TableCache tables(log);
  MaterialSet out;
  for (const MaterialSpec& m : scene.materials) {
    if (!used.count(m.name)) {
      if (log) log->Add("skip", "material '" + m.name + "' (not used by this render)");
      continue;
    }
    ResolvedMaterial r;
    r.name = m.name;
    r.kind = m.kind;
    switch (m.kind) {
      case MaterialKind::kAnalytic:
        r.model = m.model;
        if (!m.fit_table.empty()) {
          r.params = FitCached(m, cache_dir, &tables, log);
        } else if (!m.fit_report.empty()) {
          r.params = FromReport(m, log);
        } else {
          r.params = m.params;
          if (log)
            log->Add("load", "material '" + m.name + "': " + m.model + " from scene parameters");
        }
        break;
      case MaterialKind::kMeasured:
        r.table = tables.Get(m.table);
        break;
      case MaterialKind::kFactored:
        r.factors = FactorCached(m, cache_dir, &tables, log);
        break;
    }
    out.emplace(m.name, std::move(r));
  }
  return out;
}

}  // namespace brdfit::pipeline
