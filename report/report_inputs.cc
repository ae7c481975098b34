#include "report/report_inputs.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"
#include "core/model_params.h"
#include "io/factor_io.h"
#include "io/fit_params_json.h"
#include "io/fit_report.h"
#include "io/image_io.h"
#include "io/nbrdf.h"
#include "io/result_json.h"
#include "io/table_io.h"
#include "models/registry.h"
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

// A table the report can load for the theta_h slices: a file, or an NBRDF input "nbrdf:NAME"
// (tabulated by the CLI's loader, pipeline/inputs.h).
bool LoadableTable(const std::string& source) {
  std::error_code ec;
  return IsNbrdfInput(source) || fs::is_regular_file(source, ec);
}

// The table a result names for its material: kept for the slices and renders when it can be
// loaded, else remembered as named but not there (unless the material has a table already).
void NoteNamedTable(const std::string& material, const std::string& source, ReportSources* out) {
  if (source.empty() || out->tables.count(material)) return;
  if (LoadableTable(source)) {
    out->tables[material] = source;
    out->unloadable_tables.erase(material);
  } else {
    out->unloadable_tables.emplace(material, source);
  }
}

// The declared size of every texture of the first `rank` terms ("textures": p, q, p2, q2, ...,
// io/factor_io.h), or nothing when one is missing or not a pair of integers >= 0.
std::vector<FactorForm::Term> TermSizes(const json& j, int rank) {
  const json textures = j.value("textures", json::object());
  if (!textures.is_object()) return {};
  std::vector<FactorForm::Term> terms(static_cast<std::size_t>(rank));
  for (int k = 0; k < rank; ++k) {
    for (const bool q : {false, true}) {
      const json t = textures.value(FactorTextureName(k, q), json());
      if (!t.is_object()) return {};
      const json w = t.value("width", json()), h = t.value("height", json());
      if (!w.is_number_unsigned() || !h.is_number_unsigned() || w.get<std::uint64_t>() > 1u << 20 ||
          h.get<std::uint64_t>() > 1u << 20) {
        return {};
      }
      FactorTextureSize& size = q ? terms[k].q : terms[k].p;
      size = {w.get<int>(), h.get<int>()};
    }
  }
  return terms;
}

}  // namespace

Entry FactorEntry(const fs::path& sidecar, std::string* material, std::string* table) {
  const json j = ReadJson(sidecar);
  const JsonFields root(sidecar, "");
  if (root.String(j, "format", "") != kFactorFormat) {
    throw InputError(sidecar,
                     "not a brdfit factorization sidecar (no format "
                     "\"brdfit-factorization\")");
  }
  // Version, rank, diffuse (io/factor_io.h), then the textures too: a sidecar whose EXR is
  // missing, damaged or of another size is refused here, not found out while drawing.
  const FactorSidecarHeader header = ReadFactorSidecarHeader(j, sidecar);
  ReadFactorFiles(sidecar);
  FactorForm form;
  form.parameterization = root.String(j, "parameterization", "");
  form.diffuse = header.diffuse[0] > 0 || header.diffuse[1] > 0 || header.diffuse[2] > 0;
  form.terms = TermSizes(j, header.rank);
  const bool sized = !form.terms.empty();
  form.terms.resize(static_cast<std::size_t>(header.rank));  // the label's rank, sizes or not
  Entry e;
  e.kind = Entry::Kind::kFactor;
  e.name = "factor:" + FactorFormLabel(form);
  if (sized) {
    try {
      e.cost = ComputeFactorCost(form);
      e.has_cost = true;
    } catch (const std::invalid_argument&) {
      // An unknown parameterization: named in the entry, refused when its textures are loaded.
    }
  }
  const json solver = root.Object(j, "solver");
  if (!solver.contains("resolution")) root.Child("solver").Fail("resolution", "is missing");
  e.budget = fmt::format("res {}", root.Child("solver").Count(solver, "resolution", 0));
  e.status = "converged";
  const JsonFields sf = root.Child("stats");
  const json stats = root.Object(j, "stats");
  // Sidecars before refine_loss existed were refined under the relative loss.
  const std::string refine_loss =
      solver.contains("refine_loss") && solver["refine_loss"].is_string()
          ? solver["refine_loss"].get<std::string>()
          : "rel";
  e.loss = sf.Bool(stats, "refined", false) ? "log (linear) + " + refine_loss + " (refined)"
                                            : "log (linear)";
  const double seconds = sf.Number(stats, "seconds", 0, 0);
  const double system = sf.Number(stats, "system_seconds", 0, 0);
  e.time_ms = 1e3 * seconds;
  e.times_ms = {{"system", 1e3 * system}, {"solve", 1e3 * (seconds - system)}};
  if (sf.Bool(stats, "system_reused", false)) e.message = "factored system reused";
  if (!j.contains("metrics")) root.Fail("metrics", "is missing");
  const JsonFields mf = root.Child("metrics");
  const json metrics = root.Object(j, "metrics");
  if (!metrics.contains("fit_metrics")) mf.Fail("fit_metrics", "is missing");
  const json fm = mf.Object(metrics, "fit_metrics");
  e.metrics = MetricsFromJson(fm, false, mf.Child("fit_metrics"));
  // A sidecar's rendered error sits beside fit_metrics (docs/formats.md): factorizations are
  // then ranked with the fits by the same rendered score (core/model_choice.h).
  RenderedFromJson(metrics, mf, &e.metrics);
  if (!e.metrics.ok) {
    e.status = "failed";
    e.message = e.metrics.problem.empty() ? "no metrics in the sidecar" : e.metrics.problem;
  }
  const std::string file = root.Child("source").String(root.Object(j, "source"), "file", "");
  *table = file;
  // The material key brdfit factor recorded (pipeline/material_keys.h); in older sidecars,
  // the source's material name, or the stem of the sidecar minus the ".factor" part.
  const std::string key = root.String(j, "material", "");
  *material = !key.empty()   ? key
              : file.empty() ? MaterialName(fs::path(sidecar.stem()).stem())
                             : MaterialName(file);
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
// cubic in the fits of one material).
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

// A factorization's sidecar named by a fit report or JSON `from` (io/fit_report.h): as written
// (relative to the run's working directory), else beside `from`, else in the folder beside
// `from` that `brdfit fit` writes them to (pipeline/factor_candidate.h: fits.h5 ->
// fits.factors/). Empty when none exists.
fs::path FindSidecar(const std::string& sidecar, const fs::path& from) {
  const fs::path given(sidecar);
  fs::path beside_folder = from;
  beside_folder.replace_extension(".factors");
  for (const fs::path& p : {given, from.parent_path() / given, beside_folder / given.filename()}) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p;
  }
  return {};
}

// A factorization among a fit report's candidates: its sidecar's entry (renders, slices, cost)
// with the report's choice mark, or, when the textures are not found, an entry that says so.
void AddFactorizationEntry(const std::string& material, const std::string& source,
                           const FactorizationRef& ref, bool chosen, const std::string& choice,
                           const fs::path& from, Builder* b) {
  const fs::path sidecar = FindSidecar(ref.sidecar, from);
  Entry e;
  if (!sidecar.empty()) {
    std::string m, table;
    e = FactorEntry(sidecar, &m, &table);
  } else {
    e.kind = Entry::Kind::kFactor;
    e.name = "factor:" + ref.form;
    e.status = "failed";
    e.message = "textures not found: " + ref.sidecar + " (named by " + from.string() + ")";
  }
  e.chosen = chosen;
  e.choice = choice;
  AddEntry(b, material, source, std::move(e));
  if (!sidecar.empty()) b->out.factors.push_back({material, "factor:" + ref.form, sidecar});
}

// A fit report (HDF5, io/fit_report.h): every fit of every material, and its tables.
void AddFitReport(const std::vector<FitReportEntry>& entries, const fs::path& from, Builder* b) {
  ReportSources* out = &b->out;
  for (const FitReportEntry& f : entries) {
    const std::string material = f.material.empty() ? MaterialName(f.source) : f.material;
    if (f.factorization) {
      AddFactorizationEntry(material, f.source, *f.factorization, f.chosen, f.choice, from, b);
    } else {
      Entry e = FitEntry(f);
      if (IsFactorizationModel(f.result.model)) e.kind = Entry::Kind::kFactor;  // failed: no files
      AddEntry(b, material, f.source, std::move(e));
    }
    NoteNamedTable(material, f.source, out);
  }
}

void AddInputOf(const fs::path& p, bool explicit_input, Builder* b);

// A table: the source of its material's θh slices and renders (loaded by the caller).
void AddTable(const fs::path& p, Builder* b) {
  b->out.tables[MaterialName(p)] = p;
  b->out.unloadable_tables.erase(MaterialName(p));
  Material& m = b->index.GetOrAddMaterial(MaterialName(p));
  if (m.source.empty()) m.source = p.string();
}

// Any JSON library error (a member of the wrong type deep inside) names the file too.
void AddInput(const fs::path& p, bool explicit_input, Builder* b) {
  try {
    AddInputOf(p, explicit_input, b);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(p, std::string("unexpected JSON content: ") + e.what());
  }
}

void AddInputOf(const fs::path& p, bool explicit_input, Builder* b) {
  const Kind kind = Classify(p);
  ReportSources* out = &b->out;
  Report& r = out->report;
  switch (kind) {
    case Kind::kFactor: {
      std::string material, table;
      Entry e = FactorEntry(p, &material, &table);
      Material& m = b->index.GetOrAddMaterial(material);
      if (m.source.empty()) m.source = table;
      NoteNamedTable(material, table, out);
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
      // Decoded whole, so that a truncated or damaged PNG is refused here (the page embeds the
      // file's bytes as they are).
      ReadPng(p);
      r.renders.push_back({p.stem().string(), p.string()});
      break;
    case Kind::kParamsJson:
      // In a folder the fit report beside it holds the same fits (and their times).
      if (!explicit_input) break;
      // The parameters JSON of `brdfit fit` (io/fit_params_json.h): fits without timings.
      AddFitReport(ReadFitParamsJson(p), p, b);
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
          AddFitReport(fits, p, b);
          break;
        }
      }
      AddTable(p, b);
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

namespace {

// Why a path that is neither a regular file nor a folder cannot be read: "no such file or
// folder" only when nothing is there (a FIFO or /dev/zero was reported as missing).
std::string NotReadable(const fs::path& p) {
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) return "cannot be read: " + ec.message();
  switch (st.type()) {
    case fs::file_type::not_found:
      return "no such file or folder";
    case fs::file_type::fifo:
      return "is a FIFO, not a regular file";
    case fs::file_type::character:
      return "is a character device, not a regular file";
    case fs::file_type::block:
      return "is a block device, not a regular file";
    case fs::file_type::socket:
      return "is a socket, not a regular file";
    default:
      return "is not a regular file";
  }
}

// Runs add(); with `skipped`, an InputError is recorded there instead of thrown.
template <class F>
void Guarded(std::vector<std::string>* skipped, F add) {
  if (!skipped) return add();
  try {
    add();
  } catch (const InputError& e) {
    skipped->push_back(e.what());
  }
}

}  // namespace

ReportSources ReadReportInputs(const std::vector<fs::path>& inputs,
                               std::vector<std::string>* skipped) {
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
      for (const auto& f : files) Guarded(skipped, [&] { AddInput(f, false, &b); });
    } else if (fs::is_regular_file(p, ec)) {
      Guarded(skipped, [&] { AddInput(p, true, &b); });
    } else if (IsNbrdfInput(p.string())) {
      // A table like any other, tabulated by the caller when it is drawn (pipeline/inputs.h).
      Guarded(skipped, [&] {
        if (MaterialName(p).empty()) throw InputError(p, "names no NBRDF material");
        AddTable(p, &b);
      });
    } else {
      Guarded(skipped, [&] { throw InputError(p, NotReadable(p)); });
    }
    out.report.inputs.push_back(p.string());
  }
  return std::move(out);
}

}  // namespace brdfit::report
