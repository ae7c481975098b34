#include "pipeline/merge_reports.h"

#include <fmt/core.h>

#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>

#include "core/error.h"
#include "pipeline/batch_fit.h"
#include "pipeline/scratch_folder.h"

namespace brdfit::pipeline {
namespace {

namespace fs = std::filesystem;

using Key = std::tuple<std::string, std::string, std::string>;  // material, model, options

// The bytes of the entry written alone, without timings or choice marks: what must agree.
std::string Canonical(FitReportEntry e, const fs::path& scratch) {
  e.chosen = false;
  e.choice.clear();
  const fs::path p = scratch / "entry.h5";
  WriteFitReport({std::move(e)}, p, /*include_timings=*/false);
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

MergedReports MergeFitReports(const std::vector<fs::path>& parts) {
  if (parts.empty()) throw InputError("merge: no fit report to merge");
  MergedReports out;
  std::map<Key, std::size_t> seen;  // key -> index into out.entries
  std::vector<std::size_t> from;    // part of each kept entry
  std::map<std::string, std::pair<std::string, std::size_t>> source_of;  // material -> source, part
  std::unique_ptr<ScratchFolder> scratch;
  // The parts of one batch: written by one brdfit version, each model fitted under one set of
  // options, each material from one table's contents. Anything else is a mix of runs whose
  // fits do not compare (the choice would weigh them as if they did).
  std::string version;
  std::map<std::string, std::map<std::size_t, std::set<std::string>>> options_of;  // model, part
  std::map<std::string, std::pair<std::string, std::size_t>> hash_of;  // material -> hash, part
  for (std::size_t p = 0; p < parts.size(); ++p) {
    std::vector<FitReportEntry> entries = ReadFitReport(parts[p]);
    const std::string v = ReadFitReportWriterVersion(parts[p]);
    if (p == 0) version = v;
    if (v != version) {
      throw InputError(fmt::format(
          "{} was written by brdfit {} but {} by brdfit {}; refusing to merge fits of two "
          "versions (refit one part with the other's brdfit)",
          parts[0].string(), version.empty() ? "(unknown)" : version, parts[p].string(),
          v.empty() ? "(unknown)" : v));
    }
    out.read += entries.size();
    for (FitReportEntry& e : entries) {
      // One source per material key (pipeline/material_keys.h).
      const auto [src, fresh] = source_of.emplace(e.material, std::make_pair(e.source, p));
      if (!fresh && src->second.first != e.source) {
        throw InputError(fmt::format(
            "material '{}' is {} in {} but {} in {}: two tables under one material key; "
            "refusing to merge (fit both in one run, or give every shard the same paths)",
            e.material, src->second.first, parts[src->second.second].string(), e.source,
            parts[p].string()));
      }
      options_of[e.result.model][p].insert(e.options);
      if (!e.source_hash.empty()) {
        const auto [h, new_hash] = hash_of.emplace(e.material, std::make_pair(e.source_hash, p));
        if (!new_hash && h->second.first != e.source_hash) {
          throw InputError(fmt::format(
              "material '{}' ({}) was fitted to contents {} in {} but {} in {}: the table "
              "changed between the runs; refusing to merge (refit the stale part)",
              e.material, e.source, h->second.first, parts[h->second.second].string(),
              e.source_hash, parts[p].string()));
        }
      }
      const Key key{e.material, e.result.model, e.options};
      const auto it = seen.find(key);
      if (it == seen.end()) {
        seen.emplace(key, out.entries.size());
        from.push_back(p);
        out.entries.push_back(std::move(e));
        continue;
      }
      if (!scratch) scratch = std::make_unique<ScratchFolder>("merge");
      const FitReportEntry& kept = out.entries[it->second];
      if (Canonical(kept, scratch->dir()) != Canonical(e, scratch->dir())) {
        const fs::path& a = parts[from[it->second]];
        throw InputError(fmt::format(
            "conflicting fits of {} with model {} and options {}: {} and {} hold different "
            "results (final cost {} vs {}, status {} vs {}); refusing to merge (drop one part "
            "or refit that table with --force)",
            e.source, e.result.model, e.options, a.string(), parts[p].string(),
            kept.result.final_cost, e.result.final_cost, ToString(kept.result.status),
            ToString(e.result.status)));
      }
      ++out.duplicates;
    }
  }
  for (const auto& [model, by_part] : options_of) {
    const auto& [p0, o0] = *by_part.begin();
    for (const auto& [p, o] : by_part) {
      if (o == o0) continue;
      const auto join = [](const std::set<std::string>& set) {
        std::string s;
        for (const std::string& x : set) s += (s.empty() ? "" : " and ") + x;
        return s;
      };
      throw InputError(fmt::format(
          "model {} was fitted with options {} in {} but {} in {}; refusing to merge parts of "
          "different runs (fit every shard with the same options)",
          model, join(o0), parts[p0].string(), join(o), parts[p].string()));
    }
  }
  for (const FitReportEntry& e : out.entries) out.timed = out.timed || e.timed;
  MarkChosenFits(out.entries);
  SortEntries(out.entries);
  return out;
}

}  // namespace brdfit::pipeline
