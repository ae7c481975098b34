#include "pipeline/refit_source.h"

#include <fmt/core.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "core/error.h"
#include "pipeline/batch_fit.h"
#include "pipeline/fit_settings.h"

namespace brdfit::pipeline {

namespace {

namespace fs = std::filesystem;

// A folder of its own under the system's temporary directory, removed with everything in it.
class ScratchFolder {
 public:
  ScratchFolder() {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           fmt::format("brdfit-refit-{}-{}", static_cast<long>(::getpid()), counter++);
    fs::create_directories(dir_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

}  // namespace

SourceRefit RefitSource(const FitReportEntry& of, const std::vector<std::string>& models) {
  ScratchFolder scratch;
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
