#include "report/compare.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "core/rendered_regions.h"
#include "io/metrics_json.h"

namespace brdfit::report {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool Usable(const Entry& e) {
  return !e.Failed() && e.metrics.ok;
}
bool HasRendered(const Entry* e) { return e && Usable(*e) && e->metrics.rendered.ok; }
}  // namespace

std::size_t ErrorMetricIndex(const std::string& name) {
  for (std::size_t i = 0; i < kNumErrorMetrics; ++i) {
    if (name == kErrorMetrics[i].name) return i;
  }
  throw InputError("unknown metric '" + name + "' (expected " + ErrorMetricNames(" | ") + ")");
}

int Comparison::Count(Change c) const {
  return static_cast<int>(
      std::count_if(deltas.begin(), deltas.end(), [c](const EntryDelta& d) { return d.change == c; }));
}

int Comparison::Regressions() const {
  return static_cast<int>(
      std::count_if(deltas.begin(), deltas.end(), [](const EntryDelta& d) { return d.regression; }));
}

namespace {

EntryDelta Judge(const std::string& material, const Entry* a, const Entry* b,
                 const CompareOptions& o) {
  const Entry& any = a ? *a : *b;
  EntryDelta d;
  d.material = material;
  d.name = any.name;
  d.loss = any.loss;
  d.budget = any.budget;
  d.old_value = d.new_value = d.rel_change = kNaN;
  d.old_psnr_db = d.new_psnr_db = d.old_lum = d.new_lum = kNaN;
  d.psnr_change_db = d.lum_change_points = kNaN;
  if (HasRendered(a)) {
    d.old_psnr_db = a->metrics.rendered.psnr_db;
    d.old_lum = a->metrics.rendered.median_rel_error;
  }
  if (HasRendered(b)) {
    d.new_psnr_db = b->metrics.rendered.psnr_db;
    d.new_lum = b->metrics.rendered.median_rel_error;
  }
  if (HasRendered(a) && HasRendered(b)) {
    d.psnr_change_db = d.new_psnr_db - d.old_psnr_db;
    d.lum_change_points = 100 * (d.new_lum - d.old_lum);
    // A region that got worse counts on its own (docs/accuracy.md, "Every light"): the pooled
    // PSNR follows the brightest images and can hide a side or rim light that fell.
    const auto ra = RenderedRegions(a->metrics.rendered), rb = RenderedRegions(b->metrics.rendered);
    for (int g = 0; g < kLightRegions; ++g) {
      if (ra[g].lights == 0 || rb[g].lights == 0) continue;
      const double drop = ra[g].psnr_db - rb[g].psnr_db;
      if (d.worst_region.empty() || drop > d.region_drop_db) {
        d.worst_region = RegionName(static_cast<LightRegion>(g));
        d.region_drop_db = drop;
      }
    }
    d.rendered_regression =
        o.judge_rendered && (-d.psnr_change_db > o.psnr_drop_db ||
                             d.lum_change_points > o.lum_rise_points ||
                             (!d.worst_region.empty() && d.region_drop_db > o.psnr_drop_db));
  }
  d.factor = any.kind == Entry::Kind::kFactor;
  if (a && a->has_cost) {
    d.old_has_cost = true;
    d.old_cost = a->cost;
  }
  if (b && b->has_cost) {
    d.new_has_cost = true;
    d.new_cost = b->cost;
  }
  if (a) {
    d.status_old = a->status;
    d.old_metrics = a->metrics;
    d.old_time_ms = a->time_ms;
    if (Usable(*a)) d.old_value = a->metrics.*kErrorMetrics[o.metric].value;
  }
  if (b) {
    d.status_new = b->status;
    d.new_metrics = b->metrics;
    d.new_time_ms = b->time_ms;
    if (Usable(*b)) d.new_value = b->metrics.*kErrorMetrics[o.metric].value;
  }
  if (!b) {
    d.change = Change::kMissing;
    d.regression = o.missing_is_regression;
    return d;
  }
  if (!a) {
    d.change = Change::kAdded;
    return d;
  }
  const bool ua = Usable(*a) && std::isfinite(d.old_value);
  const bool ub = Usable(*b) && std::isfinite(d.new_value);
  if (!ua || !ub) {
    d.change = ua ? Change::kNowFails : ub ? Change::kFixed : Change::kStillFails;
    d.regression = d.change == Change::kNowFails;
    return d;
  }
  const double diff = d.new_value - d.old_value;
  d.rel_change = d.old_value > 0 ? diff / d.old_value : kNaN;
  const bool beyond_rel = d.old_value > 0 ? std::abs(diff) > o.threshold * d.old_value : true;
  if (diff > o.abs_floor && beyond_rel) {
    d.change = Change::kWorse;
  } else if (-diff > o.abs_floor && beyond_rel) {
    d.change = Change::kBetter;
  }
  if (d.change != Change::kWorse && o.time_threshold > 0 &&
      d.new_time_ms - d.old_time_ms > o.time_floor_ms &&
      d.new_time_ms > d.old_time_ms * (1 + o.time_threshold)) {
    d.change = Change::kSlower;
  }
  if (d.change != Change::kWorse && d.rendered_regression) d.change = Change::kWorseRendered;
  d.regression = d.change == Change::kWorse || d.change == Change::kSlower || d.rendered_regression;
  return d;
}

// A material's entries by key (the first of a repeated key, as a linear search would find).
using KeyMap = std::unordered_map<std::string, const Entry*>;
KeyMap EntriesByKey(const Material* m) {
  KeyMap map;
  if (m) {
    for (const Entry& e : m->entries) map.emplace(e.Key(), &e);
  }
  return map;
}
const Entry* Find(const KeyMap& map, const std::string& key) {
  const auto it = map.find(key);
  return it == map.end() ? nullptr : it->second;
}

std::unordered_map<std::string, const Material*> MaterialsByName(const Report& r) {
  std::unordered_map<std::string, const Material*> map;
  for (const Material& m : r.materials) map.emplace(m.name, &m);
  return map;
}

}  // namespace

Comparison Compare(const Report& old_report, const Report& new_report,
                   const CompareOptions& options) {
  if (!(options.threshold >= 0) || !(options.abs_floor >= 0) || !(options.time_threshold >= 0) ||
      !(options.psnr_drop_db >= 0) || !(options.lum_rise_points >= 0)) {
    throw InputError("compare: thresholds must be >= 0");
  }
  Comparison c;
  c.options = options;
  // Lookups by name and key: linear in the entries, not quadratic.
  const auto old_materials = MaterialsByName(old_report);
  const auto new_materials = MaterialsByName(new_report);
  for (const Material& ma : old_report.materials) {
    const auto found = new_materials.find(ma.name);
    const Material* mb = found == new_materials.end() ? nullptr : found->second;
    if (!mb) c.missing_materials.push_back(ma.name);
    const KeyMap old_keys = EntriesByKey(&ma), new_keys = EntriesByKey(mb);
    for (const Entry& ea : ma.entries) {
      c.deltas.push_back(Judge(ma.name, &ea, Find(new_keys, ea.Key()), options));
    }
    if (mb) {
      for (const Entry& eb : mb->entries) {
        if (!Find(old_keys, eb.Key())) c.deltas.push_back(Judge(ma.name, nullptr, &eb, options));
      }
    }
  }
  for (const Material& mb : new_report.materials) {
    if (old_materials.count(mb.name)) continue;
    c.added_materials.push_back(mb.name);
    for (const Entry& eb : mb.entries) c.deltas.push_back(Judge(mb.name, nullptr, &eb, options));
  }
  std::set<std::string> regressed;
  for (const EntryDelta& d : c.deltas) {
    if (d.regression && regressed.insert(d.material).second) {
      c.regressed_materials.push_back(d.material);
    }
  }
  return c;
}

namespace {
nlohmann::ordered_json Num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}
nlohmann::ordered_json MetricsJson(const FitMetrics& m) {
  nlohmann::ordered_json j = {{"ok", m.ok}};
  for (const ErrorMetricField& f : kErrorMetrics) j[f.name] = Num(m.*f.value);
  const RenderedError& r = m.rendered;
  if (r.ok) {
    nlohmann::ordered_json& rj = j["rendered"];
    for (const RenderedSummaryField& f : kRenderedSummary) {
      if (f.NotComputed(r)) continue;
      rj[f.name] = Num(r.*f.value);
    }
    rj["regions"] = RenderedRegionsJson(r);
  }
  return j;
}

nlohmann::ordered_json CostJson(bool has, const FactorCost& c) {
  if (!has) return nullptr;
  return {{"texture_bytes", c.texture_bytes},
          {"fetches_per_light", c.fetches_per_light},
          {"fetches_per_fragment", c.fetches_per_fragment}};
}
}  // namespace

nlohmann::ordered_json ComparisonToJson(const Comparison& c) {
  nlohmann::ordered_json j;
  j["metric"] = kErrorMetrics[c.options.metric].name;
  j["threshold"] = c.options.threshold;
  j["abs_floor"] = c.options.abs_floor;
  j["time_threshold"] = c.options.time_threshold;
  j["missing_is_regression"] = c.options.missing_is_regression;
  j["judge_rendered"] = c.options.judge_rendered;
  j["psnr_drop_db"] = c.options.psnr_drop_db;
  j["lum_rise_points"] = c.options.lum_rise_points;
  j["regressed"] = c.Regressed();
  j["regressions"] = c.Regressions();
  nlohmann::ordered_json counts;
  for (Change ch : {Change::kSame, Change::kBetter, Change::kWorse, Change::kWorseRendered,
                    Change::kSlower,
                    Change::kNowFails, Change::kFixed, Change::kStillFails, Change::kMissing,
                    Change::kAdded}) {
    counts[ToString(ch)] = c.Count(ch);
  }
  j["counts"] = counts;
  j["regressed_materials"] = c.regressed_materials;
  j["missing_materials"] = c.missing_materials;
  j["added_materials"] = c.added_materials;
  nlohmann::ordered_json deltas = nlohmann::ordered_json::array();
  for (const EntryDelta& d : c.deltas) {
    deltas.push_back({{"material", d.material},
                      {"name", d.name},
                      {"loss", d.loss},
                      {"budget", d.budget},
                      {"change", ToString(d.change)},
                      {"regression", d.regression},
                      {"status_old", d.status_old},
                      {"status_new", d.status_new},
                      {"old", Num(d.old_value)},
                      {"new", Num(d.new_value)},
                      {"rel_change", Num(d.rel_change)},
                      {"old_metrics", MetricsJson(d.old_metrics)},
                      {"new_metrics", MetricsJson(d.new_metrics)},
                      {"old_time_ms", d.old_time_ms},
                      {"new_time_ms", d.new_time_ms},
                      {"old_psnr_db", Num(d.old_psnr_db)},
                      {"new_psnr_db", Num(d.new_psnr_db)},
                      {"psnr_change_db", Num(d.psnr_change_db)},
                      {"old_median_rel_error", Num(d.old_lum)},
                      {"new_median_rel_error", Num(d.new_lum)},
                      {"lum_change_points", Num(d.lum_change_points)},
                      {"rendered_regression", d.rendered_regression},
                      {"kind", d.factor ? "factorization" : "fit"},
                      {"old_cost", CostJson(d.old_has_cost, d.old_cost)},
                      {"new_cost", CostJson(d.new_has_cost, d.new_cost)}});
  }
  j["deltas"] = deltas;
  return j;
}

std::string FormatComparison(const Comparison& c, bool all) {
  const char* metric = kErrorMetrics[c.options.metric].name;
  std::string out;
  std::string material;
  auto pct = [](double r) { return std::isfinite(r) ? fmt::format("{:+.1f} %", 100 * r) : "–"; };
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "–"; };
  for (const EntryDelta& d : c.deltas) {
    if (!all && d.change == Change::kSame) continue;
    if (d.material != material) {
      material = d.material;
      out += fmt::format("{}\n", material);
    }
    std::string what = fmt::format("{} ({}, {})", d.name, d.loss, d.budget);
    std::string detail;
    switch (d.change) {
      case Change::kNowFails:
        detail = fmt::format("status {} -> {}", d.status_old, d.status_new);
        break;
      case Change::kMissing:
        detail = "only in the old report";
        break;
      case Change::kAdded:
        detail = fmt::format("only in the new report ({} {})", metric, num(d.new_value));
        break;
      case Change::kSlower:
        detail = fmt::format("time {:.1f} -> {:.1f} ms", d.old_time_ms, d.new_time_ms);
        break;
      default:
        detail = fmt::format("{} {} -> {} ({}); time {:.1f} -> {:.1f} ms", metric,
                             num(d.old_value), num(d.new_value), pct(d.rel_change), d.old_time_ms,
                             d.new_time_ms);
    }
    if (std::isfinite(d.psnr_change_db)) {
      detail += fmt::format("; PSNR {:.2f} -> {:.2f} dB ({:+.2f}), lum. err. {:.1f} -> {:.1f} % "
                            "({:+.1f} pt)",
                            d.old_psnr_db, d.new_psnr_db, d.psnr_change_db, 100 * d.old_lum,
                            100 * d.new_lum, d.lum_change_points);
      if (!d.worst_region.empty() && d.region_drop_db > 0) {
        detail += fmt::format("; {} light PSNR {:+.2f} dB", d.worst_region, -d.region_drop_db);
      }
    } else if (std::isfinite(d.old_psnr_db) != std::isfinite(d.new_psnr_db) &&
               d.change != Change::kMissing && d.change != Change::kAdded) {
      detail += std::isfinite(d.old_psnr_db) ? "; rendered error only in the old report"
                                             : "; rendered error only in the new report";
    }
    if (d.factor && (d.old_has_cost || d.new_has_cost)) {
      const bool same = d.old_has_cost && d.new_has_cost &&
                        d.old_cost.texture_bytes == d.new_cost.texture_bytes &&
                        d.old_cost.fetches_per_light == d.new_cost.fetches_per_light &&
                        d.old_cost.fetches_per_fragment == d.new_cost.fetches_per_fragment;
      if (same || !d.old_has_cost) {
        detail += "; " + FactorCostText(d.new_cost);
      } else if (!d.new_has_cost) {
        detail += "; " + FactorCostText(d.old_cost) + " (old)";
      } else {
        detail += "; " + FactorCostText(d.old_cost) + " -> " + FactorCostText(d.new_cost);
      }
    }
    out += fmt::format("  {:<12} {:<44} {}{}\n", ToString(d.change), what, detail,
                       d.regression ? "   <- REGRESSION" : "");
  }
  out += fmt::format(
      "\n{} entries compared on {} (regression: > {:.3g} % worse and > {:.3g} absolute{}{}): "
      "{} better, {} same, {} worse, {} worse rendered, {} slower, {} now fail, {} fixed, "
      "{} still fail, {} missing, {} added\n",
      c.deltas.size(), metric, 100 * c.options.threshold, c.options.abs_floor,
      c.options.judge_rendered
          ? fmt::format("; or rendered PSNR down > {:.3g} dB or median lum. err. up > {:.3g} pt",
                        c.options.psnr_drop_db, c.options.lum_rise_points)
          : "",
      c.options.time_threshold > 0
          ? fmt::format("; time > {:.3g} % slower", 100 * c.options.time_threshold)
          : "",
      c.Count(Change::kBetter), c.Count(Change::kSame), c.Count(Change::kWorse),
      c.Count(Change::kWorseRendered), c.Count(Change::kSlower), c.Count(Change::kNowFails), c.Count(Change::kFixed),
      c.Count(Change::kStillFails), c.Count(Change::kMissing), c.Count(Change::kAdded));
  for (const auto& m : c.missing_materials) out += fmt::format("material {} is missing\n", m);
  for (const auto& m : c.added_materials) out += fmt::format("material {} is new\n", m);
  if (c.Regressed()) {
    std::string names;
    for (const auto& m : c.regressed_materials) names += (names.empty() ? "" : ", ") + m;
    out += fmt::format("REGRESSED: {} ({} regressions)\n", names, c.Regressions());
  } else {
    out += "no regressions\n";
  }
  return out;
}

}  // namespace brdfit::report
