// Factorizations as seen: the rendered-image metric (docs/accuracy.md) of `brdfit factor`'s
// factorizations over the NBRDF proxies of the 100 MERL materials, per form (parameterization,
// diffuse, rank, refinement) and resolution, with the columns of the fit study in
// docs/accuracy.md (bench_accuracy). The "Rendered error" section of docs/factorization.md is
// made with it.
//
//   bench_factor_accuracy --csv FILE [--params mccool,halfdiff,mccool+d+r2,...] [--res 64]
//                         [--lambda 1e-8]
//                         [--nbrdf all|m1,m2] [--jobs 2] [--rendered-only 1]
//                         [--refine-iterations 30] [--refine-rows 16384]
//
// Each material is scored exactly as `brdfit factor` scores it (factor/factor_metrics.h: the
// float32 textures through FactoredBrdf::Eval, what the preview draws; the default scene). One
// CSV row per factorization: material, param, res, ln_ratio_rmse, log_rmse (E2), psnr_db,
// psnr_srgb_db, median and p95 relative luminance error, factor time; the summary per
// configuration on stdout (bench/rendered_summary.h).
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "bench/bench_tables.h"
#include "bench/rendered_summary.h"
#include "factor/factor.h"
#include "factor/factor_metrics.h"
#include "io/atomic_file.h"
#include "pipeline/inputs.h"

namespace {

using namespace brdfit;
namespace fs = std::filesystem;

// A factored form: "mccool", "halfdiff", with "+d" (diffuse), "+rK" (rank K), "+ref"
// (refinement of rank 1 without diffuse; the others always refine), "+lr" (log-ratio loss
// instead of the relative one), e.g. "mccool+d+r2", "mccool+d+lr".
struct Config {
  std::string form;
  FactorParam param;
  int resolution;
  bool diffuse = false, refine = false, logratio = false;
  int rank = 1;
  std::string Key() const { return fmt::format("{} {}^2", form, resolution); }
};

Config ParseForm(const std::string& form, int resolution) {
  Config c{form, FactorParam::kMcCool, resolution};
  std::size_t start = 0;
  for (int part = 0;; ++part) {
    const std::size_t end = form.find('+', start);
    const std::string t = form.substr(start, end == std::string::npos ? end : end - start);
    if (part == 0) {
      c.param = FactorParamFromString(t);
    } else if (t == "d") {
      c.diffuse = true;
    } else if (t == "ref") {
      c.refine = true;
    } else if (t == "lr") {
      c.logratio = true;
    } else if (t.size() == 2 && t[0] == 'r' && t[1] >= '1' && t[1] <= '4') {
      c.rank = t[1] - '0';
    } else {
      throw std::invalid_argument("unknown part '" + t + "' of form '" + form +
                                  "' (d, ref, lr, r1..r4)");
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return c;
}

struct Row {
  std::string material;
  std::size_t config = 0;
  std::string error;  // factorization failed (InputError / runtime_error)
  double ln_ratio_rmse = 0, factor_ms = 0;
  FactorStats stats;
  std::array<double, 3> diffuse{0, 0, 0};
  FitMetrics fit;
  RenderedError rendered;
};

}  // namespace

int main(int argc, char** argv) {
  std::string csv = "factor_accuracy.csv";
  std::vector<std::string> params = {"mccool", "halfdiff"}, nbrdf = {"all"};
  std::vector<int> resolutions = {64};
  double lambda = FactorOptions{}.lambda;
  int jobs = 2;
  bool rendered_only = false;  // --rendered-only 1: skip ln-ratio RMSE and E2 (the slow part)
  FactorOptions refine_budget;  // --refine-iterations, --refine-rows (the refinement's budget)
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      fmt::print(stderr, "option {} needs a value\n", a);
      return 2;
    }
    const std::string v = argv[i + 1];
    if (a == "--csv") {
      csv = v;
    } else if (a == "--params") {
      params = bench::SplitList(v);
    } else if (a == "--res") {
      resolutions.clear();
      for (const auto& r : bench::SplitList(v)) resolutions.push_back(std::atoi(r.c_str()));
    } else if (a == "--lambda") {
      lambda = std::atof(v.c_str());
    } else if (a == "--nbrdf") {
      nbrdf = bench::SplitList(v);
    } else if (a == "--rendered-only") {
      rendered_only = v == "1";
    } else if (a == "--refine-iterations") {
      refine_budget.refine_iterations = std::atoi(v.c_str());
    } else if (a == "--refine-rows") {
      refine_budget.refine_rows = static_cast<std::size_t>(std::atoll(v.c_str()));
    } else if (a == "--jobs") {
      jobs = std::max(1, std::atoi(v.c_str()));
    } else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 2;
    }
  }
  std::vector<Config> configs;
  try {
    for (const auto& p : params) {
      for (int r : resolutions) configs.push_back(ParseForm(p, r));
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 2;
  }
  const std::vector<std::string> inputs = bench::NbrdfStudyInputs(nbrdf);
  if (inputs.empty()) return 0;

  const auto t0 = std::chrono::steady_clock::now();
  FactorSystemCache cache(16);  // thread-safe; one system per configuration and reduced mask
  std::vector<Row> rows;
  std::mutex mu;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < inputs.size(); i = next++) {
      const Table table = pipeline::LoadInput(inputs[i]);
      for (std::size_t c = 0; c < configs.size(); ++c) {
        Row row;
        row.material = inputs[i].substr(6);
        row.config = c;
        FactorOptions o;
        o.param = configs[c].param;
        o.resolution = configs[c].resolution;
        o.lambda = lambda;
        o.diffuse = configs[c].diffuse;
        o.rank = configs[c].rank;
        o.refine = configs[c].refine;
        o.refine_loss = configs[c].logratio ? RefineLoss::kLogRatio : RefineLoss::kRel;
        o.refine_iterations = refine_budget.refine_iterations;
        o.refine_rows = refine_budget.refine_rows;
        try {
          const Factorization r = Factor(table, o, &cache);
          row.factor_ms = 1e3 * r.stats.seconds;
          row.stats = r.stats;
          row.diffuse = r.brdf.diffuse();
          if (!rendered_only) {
            row.ln_ratio_rmse = FactorLnRatioRmse(table, r.brdf, o.max_theta);
            row.fit = ScoreFactorization(table, r.brdf);
          }
          row.rendered = ScoreFactorizationRendered(table, r.brdf);
        } catch (const std::exception& e) {
          row.error = e.what();
        }
        std::lock_guard<std::mutex> lock(mu);
        fmt::print(stderr, "{:<28} {:<16} {:>8.5f} {:>6.1f} dB {:>6.1f} %{}\n", row.material,
                   configs[c].Key(), row.fit.log_rmse, row.rendered.psnr_db,
                   100 * row.rendered.median_rel_error,
                   row.error.empty() ? std::string() : "  failed: " + row.error);
        rows.push_back(std::move(row));
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return std::tie(a.material, a.config) < std::tie(b.material, b.config);
  });

  std::string out =
      "material,param,res,status,ln_ratio_rmse,log_rmse,psnr_db,psnr_srgb_db,median_rel_error,"
      "p95_rel_error,factor_ms,refine_ms,refine_iterations,refine_rel_rms_start,refine_rel_rms,"
      "diffuse_r,diffuse_g,"
      "diffuse_b\n";
  for (const Row& r : rows) {
    const RenderedError& e = r.rendered;
    const std::string status = !r.error.empty() ? "failed" : e.ok ? "ok" : "metric_failed";
    out += fmt::format(
        "{},{},{},{},{:.6g},{:.6g},{:.4f},{:.4f},{:.6f},{:.6f},{:.1f},{:.1f},{},{:.5g},{:.5g},"
        "{:.5g},{:.5g},{:.5g}\n",
        r.material, configs[r.config].form, configs[r.config].resolution, status, r.ln_ratio_rmse,
        r.fit.log_rmse, e.psnr_db, e.psnr_srgb_db, e.median_rel_error, e.p95_rel_error, r.factor_ms,
        1e3 * r.stats.refine_seconds, r.stats.refine_iterations, r.stats.refine_rel_rms_start,
        r.stats.refine_rel_rms, r.diffuse[0], r.diffuse[1], r.diffuse[2]);
  }
  WriteTextAtomically(csv, out);

  bench::PrintRenderedSummaryHeader(stdout);
  for (std::size_t c = 0; c < configs.size(); ++c) {
    bench::RenderedSummarizer summary;
    for (const Row& r : rows) {
      if (r.config == c) summary.Add(r.material, r.rendered);
    }
    bench::PrintRenderedSummaryRow(stdout, configs[c].Key(), summary.Get());
  }
  fmt::print("wrote {} ({} rows) in {:.0f} s with {} jobs\n", csv, rows.size(), seconds, jobs);
  return 0;
}
