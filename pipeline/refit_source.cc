#include "pipeline/refit_source.h"

#include <fmt/core.h>

#include "core/error.h"
#include "pipeline/batch_fit.h"
#include "pipeline/fit_settings.h"
#include "pipeline/scratch_folder.h"

namespace brdfit::pipeline {

SourceRefit RefitSource(const FitReportEntry& of, const std::vector<std::string>& models) {
  ScratchFolder scratch("refit");
  BatchFitRequest req;
  req.inputs = {of.source};
  req.models = ResolveModelRuns(models, "none", /*loss_given=*/false);
  ApplyFitSettings(FitSettings{}, &req.samples, &req.fit);
  req.report = scratch.dir() / "refit.h5";
  req.timings = false;
  BatchFitResult r = RunBatchFit(req);
  if (!r.input_errors.empty()) throw InputError(r.input_errors.front());
  SourceRefit out;
  out.same_options = true;
  for (FitReportEntry& e : r.fresh) {
    if (!of.source_hash.empty() && !e.source_hash.empty() && e.source_hash != of.source_hash) {
      throw InputError(of.source, fmt::format("its contents ({}) are not the ones the report's "
                                              "fits were made from ({}): the table changed",
                                              e.source_hash, of.source_hash));
    }
    out.same_options = out.same_options && e.options == of.options;
    e.material = of.material;
    e.chosen = false;
    e.choice.clear();
    out.entries.push_back(std::move(e));
  }
  return out;
}

}  // namespace brdfit::pipeline
