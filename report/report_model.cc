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

std::vector<std::size_t> ParetoFront(const std::vector<CostError>& points) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!Usable(points[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
      if (j == i || !Usable(points[j])) continue;
      const CostError &a = points[i], &b = points[j];
      dominated = b.cost <= a.cost && b.error <= a.error && (b.cost < a.cost || b.error < a.error);
    }
    if (!dominated) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    return points[a].cost < points[b].cost;
  });
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
      return "best = the fit brdfit fit chose (highest PSNR − 20 × median luminance error, the "
             "fewest parameters within 0.5 dB of it; core/model_choice.h)";
    case BestBy::kRendered:
      return "best = highest PSNR − 20 × median luminance error (rendered-image metric, "
             "docs/accuracy.md) among the results that have it";
    case BestBy::kLogRmse:
      return "best = lowest log_rmse: no result has a rendered-image error (a report written "
             "before the metric)";
    case BestBy::kNone:
      break;
  }
  return "no usable result";
}

int BestEntry(const std::vector<Entry>& entries) { return PickBest(entries).index; }

}  // namespace brdfit::report
