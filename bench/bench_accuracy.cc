// Accuracy as seen: the rendered-image metric (docs/accuracy.md) of fits over the NBRDF
// proxies of the 100 MERL materials, for every (model, loss, multistart) configuration asked
// for. The study of docs/accuracy.md is made with it.
//
//   bench_accuracy --csv FILE [--models lambert+ggx,...] [--losses log,cbrt,rel,l2]
//                  [--multistart 1,4] [--budget stride:8] [--nbrdf all|m1,m2] [--jobs 2]
//                  [--polish none|rendered]
//
// One CSV row per fit: material, model, loss, multistart, budget, status, log_rmse, psnr_db,
// psnr_srgb_db, median and p95 relative luminance error, fit time; then per configuration the
// mean PSNR, the median and worst material's median luminance error, and how many materials
// reach >= 30 dB and <= 15 % (the targets of docs/accuracy.md) on stdout (bench/
// rendered_summary.h; a fit whose metric failed is left out and counted).
#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_tables.h"
#include "bench/rendered_summary.h"
#include "fit/fitter.h"
#include "io/atomic_file.h"
#include "io/nbrdf.h"
#include "pipeline/inputs.h"

namespace {

using namespace brdfit;
namespace fs = std::filesystem;

struct Config {
  std::string model, loss;
  int multistart = 1;
  std::string Key() const { return model + " " + loss + " ms" + std::to_string(multistart); }
};

struct Row {
  std::string material;
  Config config;
  FitResult result;
};

}  // namespace

int main(int argc, char** argv) {
  std::string csv = "accuracy.csv", budget = "stride:8", polish = "none";
  std::vector<std::string> models = {"lambert+ggx"}, losses = {"log"}, nbrdf = {"all"};
  std::vector<int> multistarts = {1};
  int jobs = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--csv")
      csv = v;
    else if (a == "--models")
      models = bench::SplitList(v);
    else if (a == "--losses")
      losses = bench::SplitList(v);
    else if (a == "--budget")
      budget = v;
    else if (a == "--polish")
      polish = v;
    else if (a == "--nbrdf")
      nbrdf = bench::SplitList(v);
    else if (a == "--jobs")
      jobs = std::max(1, std::atoi(v.c_str()));
    else if (a == "--multistart") {
      multistarts.clear();
      for (const auto& m : bench::SplitList(v))
        multistarts.push_back(std::max(1, std::atoi(m.c_str())));
    } else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 2;
    }
  }
  const std::vector<std::string> inputs = bench::NbrdfStudyInputs(nbrdf);
  if (inputs.empty()) return 0;
  std::vector<Config> configs;
  for (const auto& m : models) {
    for (const auto& l : losses) {
      for (int ms : multistarts) configs.push_back({m, l, ms});
    }
  }

  std::vector<Row> rows;
  std::mutex mu;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < inputs.size(); i = next++) {
      const Table table = pipeline::LoadInput(inputs[i]);
      const std::string material = inputs[i].substr(6);
      std::map<std::string, PreparedTable> prepared;  // per loss
      for (const Config& c : configs) {
        SampleOptions so;
        so.budget = Budget::Parse(budget);
        FitOptions fo;
        fo.loss = LossKindFromString(c.loss);
        fo.multistart = c.multistart;
        fo.polish = FromString<PolishKind>(polish);
        auto it = prepared.find(c.loss);
        if (it == prepared.end()) it = prepared.emplace(c.loss, PrepareTable(table, so, fo)).first;
        FitResult r = FitPrepared(c.model, it->second, fo);
        std::lock_guard<std::mutex> lock(mu);
        fmt::print(stderr, "{:<28} {:<32} {:>8.5f} {:>6.1f} dB {:>6.1f} %\n", material, c.Key(),
                   r.metrics.log_rmse, r.metrics.rendered.psnr_db,
                   100 * r.metrics.rendered.median_rel_error);
        rows.push_back({material, c, std::move(r)});
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return std::tie(a.material, a.config.model, a.config.loss, a.config.multistart) <
           std::tie(b.material, b.config.model, b.config.loss, b.config.multistart);
  });

  std::string out =
      "material,model,loss,multistart,budget,status,log_rmse,psnr_db,psnr_srgb_db,"
      "median_rel_error,p95_rel_error,fit_ms,params,polish\n";
  for (const Row& r : rows) {
    const RenderedError& e = r.result.metrics.rendered;
    std::string params;
    for (std::size_t k = 0; k < r.result.params.size(); ++k) {
      params +=
          fmt::format("{}{}={:.6g}", k ? ";" : "", r.result.param_names[k], r.result.params[k]);
    }
    out += fmt::format("{},{},{},{},{},{},{:.6g},{:.4f},{:.4f},{:.6f},{:.6f},{:.1f},{},{}\n",
                       r.material, r.config.model, r.config.loss, r.config.multistart, budget,
                       ToString(r.result.status), r.result.metrics.log_rmse, e.psnr_db,
                       e.psnr_srgb_db, e.median_rel_error, e.p95_rel_error,
                       r.result.times.init + r.result.times.solve, params, polish);
  }
  WriteTextAtomically(csv, out);

  bench::PrintRenderedSummaryHeader(stdout);
  for (const Config& c : configs) {
    bench::RenderedSummarizer summary;
    for (const Row& r : rows) {
      if (r.config.Key() == c.Key()) summary.Add(r.material, r.result.metrics.rendered);
    }
    bench::PrintRenderedSummaryRow(stdout, c.Key(), summary.Get());
  }
  fmt::print("wrote {} ({} rows)\n", csv, rows.size());
  return 0;
}
