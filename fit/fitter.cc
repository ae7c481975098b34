#include "fit/fitter.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>

#include "core/error.h"
#include "core/model_choice.h"
#include "fit/model_ops.h"
#include "fit/narrow_peak.h"
#include "fit/prepare_cache.h"
#include "fit/sample_plan.h"
#include "fit/threads.h"
#include "models/registry.h"

namespace brdfit {

namespace {

const std::vector<internal::ModelOps>& Fitters() {
  static const std::vector<internal::ModelOps> fitters = [] {
    std::vector<internal::ModelOps> out;
    internal::RegisterModels0(out);
    internal::RegisterModels1(out);
    internal::RegisterModels2(out);
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return a.catalog_index < b.catalog_index; });
    return out;
  }();
  return fitters;
}

const internal::ModelOps& Find(std::string_view model) {
  for (const auto& f : Fitters()) {
    if (f.name == model) return f;
  }
  std::string names;
  for (const auto& f : Fitters()) names += (names.empty() ? "" : ", ") + f.name;
  throw InputError("unknown model '" + std::string(model) + "' (known: " + names + ")");
}

}  // namespace

namespace {

bool SubSampled(const SampleOptions& o) {
  return o.budget.kind != Budget::Kind::kFull;
}

}  // namespace

namespace {

// The grid's plans: the cache's, or for a table prepared alone, the rendered one made for it and
// no stored sample plan (its rows are computed as they are applied: 15 MB less at the peak).
struct Plans {
  std::shared_ptr<const SamplePlan> samples;
  std::shared_ptr<const RenderedPlan> rendered, rendered_check;
};

RenderedErrorOptions CheckLattice() {
  RenderedErrorOptions o;
  o.resolution = kRenderedCheckResolution;
  // The environment's image at other directions too (its pixels are not the lights'): a spike
  // that falls between one set of directions falls on another.
  o.environment.seed = 2;
  return o;
}

Plans GetPlans(const Grid& grid, const SampleOptions& options, PrepareCache* cache) {
  if (cache) {
    return {cache->Samples(grid, options), cache->Rendered(grid),
            cache->Rendered(grid, CheckLattice())};
  }
  return {nullptr, std::make_shared<const RenderedPlan>(MakeRenderedPlan(grid)),
          std::make_shared<const RenderedPlan>(MakeRenderedPlan(grid, CheckLattice()))};
}

void PrepareRendered(const Table& table, const Plans& plans, PreparedTable* t) {
  t->rendered = PrepareRenderedReference(table, *plans.rendered);
  t->rendered_check = PrepareRenderedReference(table, *plans.rendered_check);
}

Samples PrepareWith(const Plans& plans, const Table& table, const SampleOptions& options,
                    GeometryStorage storage = GeometryStorage::kStored) {
  return plans.samples ? PrepareSamples(table, *plans.samples, options, storage)
                       : PrepareSamples(table, options, storage);
}

}  // namespace

PreparedTable PrepareTable(const Table& table, const SampleOptions& sample_options,
                           const FitOptions& fit_options, PrepareCache* cache) {
  const Plans plans = GetPlans(table.grid, sample_options, cache);
  PreparedTable t;
  PrepareRendered(table, plans, &t);
  if (!SubSampled(sample_options)) {
    t.fit = PrepareWith(plans, table, sample_options);
  } else {
    // The metric set is every cell; the fit set is selected from it (no geometry twice).
    SampleOptions full = sample_options;
    full.budget = Budget{};
    t.metric_own = PrepareWith(plans, table, full, GeometryStorage::kOnDemand);
    t.fit = SelectBudget(t.metric_own, sample_options.budget, sample_options.seed);
    t.has_own_metric = true;
  }
  t.loss = PrepareLoss(t.fit, fit_options);
  return t;
}

PreparedTable PrepareTable(Table&& table, const SampleOptions& sample_options,
                           const FitOptions& fit_options, PrepareCache* cache) {
  const Plans plans = GetPlans(table.grid, sample_options, cache);
  if (!SubSampled(sample_options)) {
    PreparedTable t;
    PrepareRendered(table, plans, &t);
    t.fit = PrepareWith(plans, table, sample_options);
    table = Table{};  // released before the loss constants exist (36 MB for MERL)
    t.loss = PrepareLoss(t.fit, fit_options);
    return t;
  }
  // The lowest peak (docs/fitting.md, "Memory"): the rendered reference first, then the metric
  // set takes the table's values over (no copy) and the table is gone before the fit set and
  // the loss constants exist.
  PreparedTable t;
  PrepareRendered(table, plans, &t);
  t.metric_own = plans.samples
                     ? PrepareMetricSamples(std::move(table), *plans.samples, sample_options)
                     : PrepareMetricSamples(std::move(table), sample_options);
  t.fit = SelectBudget(t.metric_own, sample_options.budget, sample_options.seed);
  t.has_own_metric = true;
  t.loss = PrepareLoss(t.fit, fit_options);
  return t;
}

FitResult FitPrepared(std::string_view model, const PreparedTable& table,
                      const FitOptions& options) {
  // A table prepared under another loss (brdfit fit --model auto fits candidates under their
  // own losses): the per-observation constants are rebuilt, O(observations).
  std::optional<LossData> own_loss;
  if (table.loss.kind != options.loss || table.loss.cosine != options.cosine) {
    own_loss = PrepareLoss(table.fit, options);
  }
  const bool polish = options.polish == PolishKind::kRendered && !table.rendered.Empty();
  FitResult r = internal::FitWithOps(Find(model), table.fit, own_loss ? *own_loss : table.loss,
                                     table.metric(), options, polish ? &table.rendered : nullptr);
  const ModelInfo* info = FindModel(model);
  if (!r.Failed() && info && !table.rendered.Empty() && !r.metrics.rendered.ok) {
    // The rendered-image metric of the fitted parameters (docs/accuracy.md), unless the polish
    // scored them already.
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = internal::ThreadCpuMs();
    r.metrics.rendered = ScoreRendered(table.rendered, ModelBrdf(*info, r.params));
    r.times.metrics +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.times.metrics_cpu += internal::ThreadCpuMs() - c0;
  }
  if (info) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = internal::ThreadCpuMs();
    CheckNarrowPeak(*info, table.rendered_check, &r);
    // Said in the fit's message: a channel of the body lost or cast (core/model_choice.h
    // BodyColorHolds; the choice then prefers a fit whose body holds).
    if (r.metrics.rendered.ok && !BodyColorHolds(r.metrics.rendered)) {
      r.message +=
          fmt::format("{}the body's colour is off by {:.0f} % in a channel",
                      r.message.empty() ? "" : "; ", 100 * r.metrics.rendered.body_color_error);
    }
    r.times.metrics +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.times.metrics_cpu += internal::ThreadCpuMs() - c0;
  }
  return r;
}

FitResult FitTable(std::string_view model, const Table& table, const SampleOptions& sample_options,
                   const FitOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const PreparedTable prepared = PrepareTable(table, sample_options, options);
  const double prepare_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  FitResult r = FitPrepared(model, prepared, options);
  r.times.prepare = prepare_ms;
  return r;
}

std::vector<std::string> FittableModels() {
  std::vector<std::string> names;
  for (const auto& f : Fitters()) names.push_back(f.name);
  return names;
}

bool IsFittable(std::string_view model) {
  return std::any_of(Fitters().begin(), Fitters().end(),
                     [&](const auto& f) { return f.name == model; });
}

NormalEquations EvaluateNormalEquations(std::string_view model, const Samples& samples,
                                        const LossData& loss, const FitOptions& options,
                                        const std::vector<double>& params) {
  return internal::NormalEquationsWithOps(Find(model), samples, loss, options, params);
}

}  // namespace brdfit
