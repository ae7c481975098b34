#include "pipeline/build_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include "core/error.h"
#include "core/metrics.h"
#include "pipeline/factor_export.h"
#include "pipeline/inputs.h"
#include "pipeline/rendered_views.h"
#include "report/report_slices.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;
using report::Entry;

// What could not be read. Without keep_going the first problem ends the build; with it, each is
// recorded and its text becomes a note.
class Problems {
 public:
  Problems(bool keep_going, std::vector<std::string> all)
      : keep_going_(keep_going), all_(std::move(all)) {}
  // Throws e unless keep-going; else records it and returns its text for a note.
  std::string Add(const InputError& e) {
    if (!keep_going_) throw e;
    all_.push_back(e.what());
    return e.what();
  }
  std::vector<std::string>& All() { return all_; }

 private:
  bool keep_going_;
  std::vector<std::string> all_;
};

// Slices of one material: its table against its best results (the pick, then by
// report::RankEntries), at most kMaxSliceResults of them.
void AddSlices(const report::ReportSources& src, const ReportRequest& q, const Table& table,
               report::Material* m) {
  std::map<std::string, int> uses;  // entries per name: a shared name gets budget and loss
  for (const Entry& e : m->entries) ++uses[e.name];
  std::vector<std::size_t> order = report::RankEntries(m->entries);
  const int best = report::BestEntry(m->entries);
  if (best >= 0) {
    std::stable_partition(order.begin(), order.end(),
                          [&](std::size_t i) { return static_cast<int>(i) == best; });
  }
  std::vector<report::NamedPredictor> predictors;
  std::size_t drawable = 0;
  for (const std::size_t i : order) {
    const Entry& e = m->entries[i];
    if (e.Failed() || (e.kind == Entry::Kind::kFit && e.params.empty())) continue;
    if (++drawable > kMaxSliceResults) continue;  // counted for the note, not drawn
    try {
      if (e.kind == Entry::Kind::kFit) {
        const std::string label =
            uses[e.name] > 1 ? e.name + " (" + e.budget + ", " + e.loss + ")" : e.name;
        predictors.push_back({label, "fitted", report::ModelPredictor(e.Model(), e.params)});
        continue;
      }
      const auto f = std::find_if(src.factors.begin(), src.factors.end(), [&](const auto& r) {
        return r.material == m->name && r.label == e.name;
      });
      if (f == src.factors.end()) continue;
      auto brdf = std::make_shared<FactoredBrdf>(LoadFactoredBrdf(f->sidecar));
      predictors.push_back(
          {f->label, "factored", [brdf](const HalfDiffAngles& a) { return brdf->Eval(a); }});
    } catch (const InputError& err) {
      m->notes.push_back(fmt::format("{}: not drawn in the slices: {}", e.name, err.what()));
    }
  }
  if (drawable > kMaxSliceResults) {
    m->notes.push_back(fmt::format(
        "The θh slices draw the best {} of this material's {} results (the ★ one first, then "
        "in the table's order).",
        kMaxSliceResults, drawable));
  }
  m->slices = report::ComputeThetaHSlices(table, q.theta_d, q.phi_d, predictors);
}

// A material's slices and renders, or the notes that say why it has none.
void AddViews(const report::ReportSources& src, const ReportRequest& q, Problems& problems,
              report::Material& m) {
  const auto t = src.tables.find(m.name);
  if (t == src.tables.end()) {
    std::string why =
        "the table of this material was not given and the results do not name "
        "a readable one";
    if (const auto u = src.unloadable_tables.find(m.name); u != src.unloadable_tables.end()) {
      std::error_code ec;
      if (fs::exists(u->second, ec)) {
        // A device, a folder, a socket where a table should be: bad input, like a damaged one.
        why = problems.Add(InputError(
            u->second, "named as the table of material '" + m.name + "' but not a regular file"));
      } else {
        // Results moved without their tables still report their numbers; said, not silent.
        why = "its table " + u->second.string() + " (named by the results) is missing";
        if (q.on_warning) q.on_warning(m.name, why);
      }
    }
    if (q.slices) m.notes.push_back(fmt::format("No θh slices: {}.", why));
    if (q.renders) m.views.missing = fmt::format("No renders: {}.", why);
    return;
  }
  // A table that is there but cannot be read is an error, not a note.
  Table table;
  try {
    table = LoadInput(t->second);
  } catch (const InputError& e) {
    const std::string why = problems.Add(e);
    if (q.slices) m.notes.push_back(fmt::format("No θh slices: {}", why));
    if (q.renders) m.views.missing = fmt::format("No renders: {}", why);
    return;
  }
  if (q.slices) {
    try {
      AddSlices(src, q, table, &m);
    } catch (const InputError& e) {
      m.notes.push_back(fmt::format("No θh slices: {}", problems.Add(e)));
    }
  }
  if (q.renders) {
    try {
      m.views = RenderMaterialViews(table, m, src.factors, q.render_lights);
    } catch (const InputError& e) {
      m.views.missing = fmt::format("No renders: {}", problems.Add(e));
    }
  }
}

}  // namespace

BuiltReport BuildReport(report::ReportSources src, std::vector<std::string> unreadable,
                        const ReportRequest& q) {
  Problems problems(q.keep_going, std::move(unreadable));
  report::Report& r = src.report;
  for (const std::string& p : problems.All()) r.notes.push_back("Left out (unreadable): " + p);
  if (!q.title.empty()) r.title = q.title;
  r.metric_definition = MetricsDefinition();
  if (r.materials.empty() && r.bench.empty() && r.renders.empty()) {
    throw InputError(
        "nothing to report: no fit report, factorization, bench CSV, render or table "
        "among the inputs");
  }
  if (q.slices || q.renders) {
    for (report::Material& m : r.materials) {
      if (q.on_material) q.on_material(r.materials.size(), m.name);
      AddViews(src, q, problems, m);
    }
  }
  return {std::move(src.report), std::move(problems.All())};
}

}  // namespace brdfit::pipeline
