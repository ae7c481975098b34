#include "report/report_inputs.h"

#include <fmt/core.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"
#include "io/fit_report.h"
#include "io/nbrdf.h"
#include "io/table_io.h"
#include "report/bench_csv.h"

namespace brdfit::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open");
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(path, "not a JSON object");
  return j;
}

enum class Kind { kFactor, kBench, kRender, kTable, kParamsJson, kUnknown };

Kind Classify(const fs::path& p) {
  const std::string name = Lower(p.filename().string());
  if (EndsWith(name, ".factor.json")) return Kind::kFactor;
  if (EndsWith(name, ".csv")) return Kind::kBench;
  if (EndsWith(name, ".png")) return Kind::kRender;
  if (EndsWith(name, ".json")) return Kind::kParamsJson;
  if (EndsWith(name, ".binary") || EndsWith(name, ".merl") || EndsWith(name, ".h5") ||
      EndsWith(name, ".hdf5")) {
    return Kind::kTable;
  }
  return Kind::kUnknown;
}

double Get(const json& j, const char* key, double fallback = 0) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

// The rendered-image metric's summary of `parent` ("rendered", io/metrics_json.h), when there.
void ReadRendered(const json& parent, FitMetrics* m) {
  const auto r = parent.find("rendered");
  if (r == parent.end() || !r->is_object()) return;
  m->rendered.ok = r->value("ok", true);
  m->rendered.problem = r->value("problem", std::string());
  m->rendered.psnr_db = Get(*r, "psnr_db");
  m->rendered.psnr_srgb_db = Get(*r, "psnr_srgb_db");
  m->rendered.median_rel_error = Get(*r, "median_rel_error");
  m->rendered.p95_rel_error = Get(*r, "p95_rel_error");
}

// The metrics of a factorization sidecar ("fit_metrics") or a fit parameters file ("metrics",
// without "ok": ok_default) as the writers name them (core/metrics.h); absent fields are 0.
FitMetrics MetricsFromJson(const json& j, bool ok_default) {
  FitMetrics m;
  m.ok = j.value("ok", ok_default);
  m.problem = j.value("problem", std::string());
  m.log_rmse = Get(j, "log_rmse");
  m.cbrt_rmse = Get(j, "cbrt_rmse");
  m.rel_l2 = Get(j, "rel_l2");
  m.cells = j.value("cells", std::size_t{0});
  m.weighting = j.value("weighting", std::string());
  m.cutoff_deg = Get(j, "cutoff_deg");
  ReadRendered(j, &m);
  return m;
}

// A table the report can load for the theta_h slices: a file, or an NBRDF input "nbrdf:NAME"
// (tabulated by the CLI's loader, pipeline/inputs.h).
bool LoadableTable(const std::string& source) {
  std::error_code ec;
  return IsNbrdfInput(source) || fs::is_regular_file(source, ec);
}

}  // namespace

std::string MaterialName(const fs::path& table) {
  const std::string text = table.string();
  if (IsNbrdfInput(text)) return text.substr(kNbrdfInputPrefix.size());
  return table.stem().string();
}

Entry FactorEntry(const fs::path& sidecar, std::string* material, std::string* table) {
  const json j = ReadJson(sidecar);
  if (j.value("format", "") != "brdfit-factorization") {
    throw InputError(sidecar,
                     "not a brdfit factorization sidecar (no format "
                     "\"brdfit-factorization\")");
  }
  Entry e;
  e.kind = Entry::Kind::kFactor;
  e.name = "factor:" + j.value("parameterization", std::string("?"));
  e.loss = "log (linear)";
  const json solver = j.value("solver", json::object());
  e.budget = fmt::format("res {}", solver.value("resolution", 0));
  e.status = "converged";
  const json stats = j.value("stats", json::object());
  const double seconds = Get(stats, "seconds"), system = Get(stats, "system_seconds");
  e.time_ms = 1e3 * seconds;
  e.times_ms = {{"system", 1e3 * system}, {"solve", 1e3 * (seconds - system)}};
  if (stats.value("system_reused", false)) e.message = "factored system reused";
  const json metrics = j.value("metrics", json::object());
  const json fm = metrics.value("fit_metrics", json::object());
  e.metrics = MetricsFromJson(fm, false);
  // A sidecar's rendered error sits beside fit_metrics (docs/formats.md): factorizations are
  // then ranked with the fits by the same rendered score (core/model_choice.h).
  ReadRendered(metrics, &e.metrics);
  if (!e.metrics.ok) {
    e.status = "failed";
    e.message = fm.value("problem", std::string("no metrics in the sidecar"));
  }
  const std::string file = j.value("source", json::object()).value("file", std::string());
  *table = file;
  // The stem of the sidecar minus the ".factor" part, when the sidecar names no source.
  *material = file.empty() ? MaterialName(fs::path(sidecar.stem()).stem()) : MaterialName(file);
  return e;
}

namespace {

// "log", "log+huber(0.1)", "l2 (no cosine)": the loss and what else changes the objective.
std::string LossLabel(const json& options) {
  std::string loss = options.value("loss", std::string("?"));
  const std::string robust = options.value("robust", std::string("none"));
  if (robust != "none") loss += fmt::format("+{}({})", robust, options.value("robust_scale", 0.0));
  if (!options.value("cosine", true)) loss += " (no cosine)";
  const std::string weighting = options.value("weighting", std::string("bin-measure"));
  if (weighting != "bin-measure") loss += ", " + weighting;
  return loss;
}

// Materials by name and the keys their entries use, so that adding n entries costs O(n log n)
// however many share a key (each duplicate scanned all entries for every suffix it tried:
// cubic in the fits of one material, issue 14 item 8).
class EntryIndex {
 public:
  explicit EntryIndex(Report* r) : report_(r) {
    for (std::size_t i = 0; i < r->materials.size(); ++i) {
      materials_.emplace(r->materials[i].name, i);
      for (const Entry& e : r->materials[i].entries) keys_[r->materials[i].name].insert(e.Key());
    }
  }

  Material& GetOrAddMaterial(const std::string& name) {
    const auto [it, added] = materials_.emplace(name, report_->materials.size());
    if (added) {
      report_->materials.emplace_back();
      report_->materials.back().name = name;
    }
    return report_->materials[it->second];
  }

  // Adds e to its material; a second entry with the same key is told apart by a suffix in its
  // name, base_name keeping the name: " (FILE)" when file_suffix is given (factorizations),
  // then "#2", "#3", ... while the key is still taken.
  const Entry& Add(const std::string& material, Entry e, const std::string& file_suffix = "") {
    Material& m = GetOrAddMaterial(material);
    auto& used = keys_[material];
    if (used.count(e.Key())) {
      e.base_name = e.name;
      if (!file_suffix.empty()) e.name += " (" + file_suffix + ")";
      if (used.count(e.Key())) {
        const std::string stem = e.name;
        int& k = next_[material + '\n' + e.Key()];
        for (k = std::max(k, 2); used.count((e.name = fmt::format("{} #{}", stem, k), e.Key()));
             ++k) {
        }
        ++k;
      }
    }
    used.insert(e.Key());
    m.entries.push_back(std::move(e));
    return m.entries.back();
  }

 private:
  Report* report_;
  std::unordered_map<std::string, std::size_t> materials_;
  std::unordered_map<std::string, std::unordered_set<std::string>> keys_;
  std::unordered_map<std::string, int> next_;  // material + key -> next suffix to try
};

// What the inputs read so far add up to.
struct Builder {
  ReportSources out;
  EntryIndex index{&out.report};
};

// Adds an entry to its material (recording the material's table source if it has none).
void AddEntry(Builder* b, const std::string& material, const std::string& source, Entry e) {
  Material& m = b->index.GetOrAddMaterial(material);
  if (m.source.empty()) m.source = source;
  b->index.Add(material, std::move(e));
}

Entry FitEntry(const FitReportEntry& f) {
  const FitResult& r = f.result;
  const json options = json::parse(f.options.empty() ? "{}" : f.options, nullptr, false);
  Entry e;
  e.kind = Entry::Kind::kFit;
  e.name = r.model;
  e.loss = options.is_object() ? LossLabel(options) : "?";
  e.budget = options.is_object() ? options.value("budget", std::string("?")) : "?";
  e.status = ToString(r.status);
  e.message = r.message;
  e.param_names = r.param_names;
  e.params = r.params;
  e.at_bound = r.at_bound;
  e.iterations = r.iterations;
  e.metrics = r.metrics;
  e.chosen = f.chosen;
  e.choice = f.choice;
  if (!e.metrics.ok && e.message.empty()) e.message = r.metrics.problem;
  const FitTimes& t = r.times;
  e.times_ms = {
      {"prepare", t.prepare}, {"init", t.init}, {"solve", t.solve}, {"metrics", t.metrics}};
  e.time_ms = t.prepare + t.init + t.solve;
  return e;
}

// A fit report (HDF5, io/fit_report.h): every fit of every material, and its tables.
void AddFitReport(const std::vector<FitReportEntry>& entries, Builder* b) {
  ReportSources* out = &b->out;
  for (const FitReportEntry& f : entries) {
    const std::string material = f.material.empty() ? MaterialName(f.source) : f.material;
    AddEntry(b, material, f.source, FitEntry(f));
    if (!f.source.empty() && !out->tables.count(material) && LoadableTable(f.source)) {
      out->tables[material] = f.source;
    }
  }
}

// The parameters JSON of `brdfit fit` (FitParamsJson): fits without timings.
bool AddFitParamsJson(const fs::path& p, Builder* b) {
  ReportSources* out = &b->out;
  // Ordered: the parameters must keep the model's order.
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(p, "cannot open");
  const auto j = nlohmann::ordered_json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(p, "not a JSON object");
  if (j.value("format", "") != "brdfit-fit-params") return false;
  const auto fits = j.value("fits", nlohmann::ordered_json::array());
  if (!fits.is_array()) throw InputError(p, "\"fits\" is not an array");
  for (const auto& f : fits) {
    if (!f.is_object()) throw InputError(p, "an element of \"fits\" is not an object");
    Entry e;
    e.kind = Entry::Kind::kFit;
    e.name = f.value("model", std::string("?"));
    const json options = f.value("options", nlohmann::ordered_json::object());
    e.loss = LossLabel(options);
    e.budget = options.value("budget", std::string("?"));
    e.status = f.value("status", std::string("?"));
    e.message = f.value("message", std::string());
    const auto params = f.value("params", nlohmann::ordered_json::object());
    for (const auto& [name, value] : params.items()) {
      if (!value.is_number()) throw InputError(p, "parameter " + name + " is not a number");
      e.param_names.push_back(name);
      e.params.push_back(value.get<double>());
    }
    e.metrics =
        MetricsFromJson(f.value("metrics", nlohmann::ordered_json::object()), e.status != "failed");
    e.chosen = f.value("chosen", false);
    e.choice = f.value("choice", std::string());
    const std::string source = f.value("source", std::string());
    const std::string material = f.value("material", MaterialName(source));
    AddEntry(b, material, source, std::move(e));
    if (!source.empty() && !out->tables.count(material) && LoadableTable(source)) {
      out->tables[material] = source;
    }
  }
  return true;
}

void AddInput(const fs::path& p, bool explicit_input, Builder* b) {
  const Kind kind = Classify(p);
  ReportSources* out = &b->out;
  Report& r = out->report;
  switch (kind) {
    case Kind::kFactor: {
      std::string material, table;
      Entry e = FactorEntry(p, &material, &table);
      Material& m = b->index.GetOrAddMaterial(material);
      if (m.source.empty()) m.source = table;
      if (!table.empty() && !out->tables.count(material) && LoadableTable(table)) {
        out->tables[material] = table;
      }
      // Two factorizations with the same name and budget (e.g. --suffix runs): keep both apart.
      const Entry& added = b->index.Add(material, std::move(e), p.filename().string());
      out->factors.push_back({material, added.name, p});
      break;
    }
    case Kind::kBench: {
      auto points = ReadBenchCsv(p);
      r.bench.insert(r.bench.end(), points.begin(), points.end());
      break;
    }
    case Kind::kRender:
      r.renders.push_back({p.stem().string(), p.string()});
      break;
    case Kind::kParamsJson:
      // In a folder the fit report beside it holds the same fits (and their times).
      if (!explicit_input) break;
      if (!AddFitParamsJson(p, b)) {
        throw InputError(p, "not a brdfit fit parameters file (format \"brdfit-fit-params\")");
      }
      break;
    case Kind::kTable: {
      TableFormat format;
      try {
        format = DetectTableFormat(p);
      } catch (const InputError&) {
        if (explicit_input) throw;
        return;
      }
      if (format == TableFormat::kHdf5) {
        // An HDF5 file is a fit report or a table.
        std::vector<FitReportEntry> fits;
        bool is_report = true;
        try {
          fits = ReadFitReport(p);
        } catch (const InputError& e) {
          is_report = false;
          if (std::string(e.what()).find(kFitReportFormat) == std::string::npos) {
            // Not a format mismatch: a damaged fit report. Say so unless it is a table.
            try {
              LoadTable(p);
            } catch (const InputError&) {
              throw InputError(p, std::string("neither a fit report nor a table: ") + e.what());
            }
          }
        }
        if (is_report) {
          AddFitReport(fits, b);
          break;
        }
      }
      out->tables[MaterialName(p)] = p;
      Material& m = b->index.GetOrAddMaterial(MaterialName(p));
      if (m.source.empty()) m.source = p.string();
      break;
    }
    case Kind::kUnknown:
      if (explicit_input) {
        throw InputError(p,
                         "not a known report input (fit report, .factor.json, bench .csv, "
                         ".png render, table)");
      }
      break;
  }
}

}  // namespace

void AddBenchEntries(Report* report) {
  EntryIndex index(report);
  for (const BenchPoint& b : report->bench) {
    Entry e;
    e.kind = Entry::Kind::kFit;
    e.name = b.model;
    e.loss = b.loss;
    e.budget = b.budget;
    e.status = b.status;
    e.message = b.message;
    e.iterations = b.iterations;
    e.metrics = b.metrics;
    e.time_ms = b.time_ms;
    e.times_ms = {{"prepare", b.prepare_ms}, {"init", b.init_ms}, {"solve", b.solve_ms}};
    // Not renamed: a repeated bench point stays a repeat of its key.
    index.GetOrAddMaterial(b.material).entries.push_back(std::move(e));
  }
}

ReportSources ReadReportInputs(const std::vector<fs::path>& inputs) {
  Builder b;
  ReportSources& out = b.out;
  for (const fs::path& p : inputs) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(p)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& f : files) AddInput(f, false, &b);
    } else if (fs::is_regular_file(p, ec)) {
      AddInput(p, true, &b);
    } else {
      throw InputError(p, "no such file or folder");
    }
    out.report.inputs.push_back(p.string());
  }
  return std::move(out);
}

}  // namespace brdfit::report
