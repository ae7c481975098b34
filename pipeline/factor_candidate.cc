#include "pipeline/factor_candidate.h"

#include <fmt/core.h>

#include <chrono>
#include <exception>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/factor_form.h"
#include "core/file_stem.h"
#include "factor/factor_choice.h"
#include "factor/factor_form.h"
#include "factor/factor_metrics.h"
#include "fit/options.h"
#include "pipeline/factor_export.h"
#include "pipeline/factor_settings.h"
#include "pipeline/factor_sidecar.h"
#include "pipeline/factor_table.h"
#include "pipeline/factor_with_choice.h"

namespace brdfit::pipeline {

namespace fs = std::filesystem;

fs::path FactorizationFolder(const fs::path& report) {
  fs::path folder = report;
  folder.replace_extension(".factors");
  return folder;
}

std::string FactorizationOptionsJson(const SampleOptions& samples) {
  const FactorOptions f = MakeFactorOptions(FactorSettings{});
  // Canonical (sorted keys, fixed number format) as OptionsJson: equal settings, equal text.
  const nlohmann::json j = {
      {"factorization",
       {{"forms", "auto"},
        {"resolution", f.resolution},
        {"lambda", f.lambda},
        {"weighting", FactorSettings{}.weighting},
        {"max_theta_deg", FactorSettings{}.max_theta_deg},
        {"refine_iterations", f.refine_iterations}}},
      {"loss", "factor"},
      {"metrics",
       {{"cutoff_deg", samples.cutoff_deg}, {"weighting", ToString(samples.weighting)}}}};
  return j.dump();
}

FitReportEntry FactorizationEntry(const FactorizationJob& job) {
  using Clock = std::chrono::steady_clock;
  const Table& table = *job.table;
  FitReportEntry e = NewFactorizationEntry(job.source, job.material,
                                           FactorizationOptionsJson(job.samples), job.source_hash);
  FitResult& r = e.result;
  const auto t0 = Clock::now();
  FactorWithChoice c;
  FactorSystemCache own;  // when the caller shares none
  try {
    c = FactorChoosingForm(table, MakeFactorOptions(FactorSettings{}), job.cache ? job.cache : &own,
                           job.last);
  } catch (const std::exception& ex) {  // InputError (no usable cell), a solver's failure
    r.status = FitStatus::kFailed;
    r.message = std::string("factorization failed: ") + ex.what();
    return e;
  }
  if (job.last && job.cache) job.cache->Clear();
  const auto t1 = Clock::now();
  const FactoredBrdf& brdf = c.kept.brdf;
  // The fits' metric set: every usable cell inside the same cut-off, with the same weights,
  // whatever the fits' budget (fit/metrics.h); and the rendered metric that chose the form.
  SampleOptions metric_set = job.samples;
  metric_set.budget = Budget{};
  r.metrics = ScoreFactorization(table, brdf, metric_set);
  r.metrics.rendered = c.rendered;
  const FactorForm form = FormOf(brdf);
  const FactorCost cost = ComputeFactorCost(form);
  FactorizationRef ref;
  ref.form = FactorFormLabel(form);
  ref.texture_bytes = cost.texture_bytes;
  ref.values = cost.texture_bytes / sizeof(float);  // float32 values, the diffuse RGB included
  const std::string stem = SafeFileStem(job.material);
  ref.sidecar = (job.folder / (stem + ".factor.json")).string();
  r.status = r.metrics.ok ? FitStatus::kConverged : FitStatus::kFailed;
  r.message = fmt::format("{} {}^2, {} of {} forms: {}", ref.form, c.kept.options.resolution,
                          kAutoFactorCandidates[c.chosen].name, c.scores.size(), c.reason);
  if (!r.metrics.ok) r.message += "; " + r.metrics.problem;
  r.iterations = c.kept.stats.refine_iterations;
  r.starts = 1;
  const auto t2 = Clock::now();
  r.times.solve = std::chrono::duration<double, std::milli>(t1 - t0).count();
  r.times.metrics = std::chrono::duration<double, std::milli>(t2 - t1).count();
  // The textures and the sidecar `brdfit factor TABLE` writes, with the candidates' scores.
  const double ln_rmse = FactorLnRatioRmse(table, brdf, c.kept.options.max_theta);
  // Files that cannot be written (a file in the folder's place, a read-only folder, a full
  // disk) fail this entry, not the run: the report keeps the fits and says why.
  try {
    std::error_code ec;
    fs::create_directories(job.folder, ec);
    if (ec) throw OutputError(job.folder, "cannot create the folder: " + ec.message());
    WriteFactorFiles(c.kept, table, job.folder, stem, job.material, job.source, r.metrics,
                     c.rendered, ln_rmse, ChoiceJson(c, job.timings), nullptr, job.timings);
  } catch (const OutputError& ex) {
    r.status = FitStatus::kFailed;
    r.message = std::string("textures not written: ") + ex.what();
    return e;
  }
  e.factorization = ref;
  return e;
}

}  // namespace brdfit::pipeline
