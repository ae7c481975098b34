#include "report/report_model.h"

#include <algorithm>
#include <cmath>

#include "core/model_choice.h"

namespace brdfit::report {

std::string Entry::Key() const { return name + " | " + loss + " | " + budget; }

Material* Report::FindMaterial(const std::string& name) {
  for (auto& m : materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const Material* Report::FindMaterial(const std::string& name) const {
  return const_cast<Report*>(this)->FindMaterial(name);
}

Material& Report::GetOrAddMaterial(const std::string& name) {
  if (Material* m = FindMaterial(name)) return *m;
  materials.push_back({});
  materials.back().name = name;
  return materials.back();
}

namespace {
bool Usable(const CostError& p) {
  return p.usable && std::isfinite(p.cost) && std::isfinite(p.error);
}
}  // namespace

// Sorted by (cost, error), a point is on the front when it has the least error of its cost and
// less error than every cheaper point: O(n log n).
std::vector<std::size_t> ParetoFront(const std::vector<CostError>& points) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (Usable(points[i])) order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const CostError &pa = points[a], &pb = points[b];
    if (pa.cost != pb.cost) return pa.cost < pb.cost;
    if (pa.error != pb.error) return pa.error < pb.error;
    return a < b;
  });
  std::vector<std::size_t> front;
  double cheaper_min = INFINITY;  // least error among points cheaper than the current cost
  for (std::size_t k = 0; k < order.size();) {
    const double cost = points[order[k]].cost, least = points[order[k]].error;
    std::size_t end = k;
    while (end < order.size() && points[order[end]].cost == cost) ++end;
    if (least < cheaper_min) {
      for (std::size_t j = k; j < end && points[order[j]].error == least; ++j) {
        front.push_back(order[j]);
      }
      cheaper_min = least;
    }
    k = end;
  }
  return front;
}

namespace {
bool EntryUsable(const Entry& e) { return !e.Failed() && e.metrics.ok; }
}  // namespace

std::vector<std::size_t> ParetoFront(const std::vector<Entry>& entries) {
  std::vector<CostError> points;
  for (const Entry& e : entries) points.push_back({e.time_ms, e.metrics.log_rmse, EntryUsable(e)});
  return ParetoFront(points);
}

double RenderedScore(const RenderedError& r) { return RenderedScoreDb(r); }

BestPick PickBest(const std::vector<Entry>& entries) {
  BestPick pick;
  double best = 0;
  for (const bool only_chosen : {true, false}) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Entry& e = entries[i];
      if (!EntryUsable(e) || (only_chosen && !e.chosen)) continue;
      const double score = e.metrics.rendered.ok ? RenderedScore(e.metrics.rendered) : NAN;
      if (!std::isfinite(score) && !(only_chosen && pick.index < 0)) continue;
      if (pick.index < 0 || score > best) {
        pick = {static_cast<int>(i), only_chosen ? BestBy::kChosen : BestBy::kRendered};
        best = score;
      }
    }
    if (pick.index >= 0) return pick;
  }
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    if (!EntryUsable(e) || !std::isfinite(e.metrics.log_rmse)) continue;
    if (pick.index < 0 || e.metrics.log_rmse < best) {
      pick = {static_cast<int>(i), BestBy::kLogRmse};
      best = e.metrics.log_rmse;
    }
  }
  return pick;
}

std::string BestRule(BestBy by) {
  switch (by) {
    case BestBy::kChosen:
      return "best = the fit brdfit fit chose (highest rendered score S: per region min(PSNR, "
             "60 dB) − 20 × median luminance error, weighted over front, side and rim light; the "
             "fewest parameters within 0.5 dB of it; core/model_choice.h)";
    case BestBy::kRendered:
      return "best = highest rendered score S (per region min(PSNR, 60 dB) − 20 × median "
             "luminance error, weighted over front, side and rim light; docs/accuracy.md) among "
             "the results that have it";
    case BestBy::kLogRmse:
      return "best = lowest log_rmse: no result has a rendered-image error (a report written "
             "before the metric)";
    case BestBy::kNone:
      break;
  }
  return "no usable result";
}

int BestEntry(const std::vector<Entry>& entries) { return PickBest(entries).index; }

std::vector<std::size_t> RankEntries(const std::vector<Entry>& entries) {
  auto rendered = [](const Entry& e) { return EntryUsable(e) && e.metrics.rendered.ok; };
  std::vector<std::size_t> order(entries.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const Entry &ea = entries[a], &eb = entries[b];
    if (EntryUsable(ea) != EntryUsable(eb)) return EntryUsable(ea);
    if (!EntryUsable(ea)) return false;
    if (rendered(ea) != rendered(eb)) return rendered(ea);
    if (rendered(ea)) return RenderedScore(ea.metrics.rendered) > RenderedScore(eb.metrics.rendered);
    return ea.metrics.log_rmse < eb.metrics.log_rmse;
  });
  return order;
}

}  // namespace brdfit::report
