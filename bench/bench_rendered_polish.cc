// The rendered polish over the MERL proxies (docs/accuracy.md, "The rendered polish"): per table,
// the `--model auto` candidates fitted without and with the polish, each set's chosen fit
// (core/model_choice.h), scored on the metric's lights and on six lights it never saw.
//   bench_rendered_polish [--nbrdf all|NAME,...] [--jobs N] [--noise SIGMA]
// With --noise, the fits are made on a copy of each table with log-normal noise (every valid
// cell's channels times exp(SIGMA n), n standard normal, seeded by the material), and the
// "hold" column scores the chosen fits against the noise-free table under the metric's own
// lights: does the polish fit the noise?
// One line per table, RATIO lines (the polish's factor on each candidate's table loss), and a
// summary line; scripts/rendered_polish_summary.py makes docs/accuracy.md's table of the output.
#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <random>
#include <thread>

#include "bench/bench_tables.h"
#include "core/model_choice.h"
#include "fit/fitter.h"
#include "fit/rendered_error.h"
#include "models/registry.h"
#include "pipeline/batch_fit.h"
#include "pipeline/inputs.h"

using namespace brdfit;

namespace {

RenderedError Score(const RenderedReference& ref, const ModelInfo& m, const std::vector<double>& p) {
  return ScoreRendered(ref, ModelBrdf(m, p));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names = {"all"};
  int jobs = 2;
  double noise = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--nbrdf") names = bench::SplitList(v);
    if (a == "--jobs") jobs = std::atoi(v.c_str());
    if (a == "--noise") noise = std::atof(v.c_str());
  }
  const auto inputs = bench::NbrdfStudyInputs(names);
  RenderedErrorOptions hold;
  hold.light_angles_deg = {10, 20, 40, 55, 65, 75};  // between and beside the metric's
  std::mutex mu;
  std::atomic<std::size_t> next{0};
  // Sums over tables: S, holdout S, PSNR, holdout PSNR, median error; counts at the targets.
  struct Sum {
    double s0 = 0, s1 = 0, h0 = 0, h1 = 0, p0 = 0, p1 = 0, hp0 = 0, hp1 = 0, m0 = 0, m1 = 0;
    int n = 0, ge30_0 = 0, ge30_1 = 0, le15_0 = 0, le15_1 = 0;
  } sum;
  auto worker = [&] {
    for (std::size_t i = next++; i < inputs.size(); i = next++) {
      const Table clean = pipeline::LoadInput(inputs[i]);
      Table table = clean;
      if (noise > 0) {
        std::mt19937_64 rng(1000 + i);
        std::normal_distribution<double> n01;
        for (std::size_t c = 0; c < table.rgb.size(); ++c) table.rgb[c] *= std::exp(noise * n01(rng));
      }
      SampleOptions so;
      so.budget = DefaultFitBudget();
      std::vector<FitResult> plain, pol;
      double ms_plain = 0, ms_pol = 0;
      for (const auto& c : pipeline::kAutoCandidates) {
        FitOptions fo;
        fo.loss = *c.loss;
        fo.polish = PolishKind::kNone;
        PreparedTable pt = PrepareTable(table, so, fo);
        plain.push_back(FitPrepared(c.model, pt, fo));
        fo.polish = PolishKind::kRendered;
        pol.push_back(FitPrepared(c.model, pt, fo));
        ms_plain += plain.back().times.solve_cpu;
        if (!plain.back().Failed() && !pol.back().Failed()) {
          std::lock_guard<std::mutex> lock(mu);
          fmt::print("RATIO {} {} {:.4g} S {:.3f} -> {:.3f}\n", inputs[i].substr(6), c.model,
                     pol.back().final_cost / plain.back().final_cost,
                     RenderedScoreDb(plain.back().metrics.rendered), RenderedScoreDb(pol.back().metrics.rendered));
        }
        ms_pol += pol.back().times.solve_cpu;
      }
      auto choose = [](const std::vector<FitResult>& v) {
        std::vector<const FitResult*> ptrs;
        for (auto& f : v) ptrs.push_back(&f);
        return ChooseFit(ptrs);
      };
      const auto c0 = choose(plain), c1 = choose(pol);
      if (!c0 || !c1) continue;
      const FitResult& f0 = plain[c0->index];
      const FitResult& f1 = pol[c1->index];
      const RenderedReference href =
          noise > 0 ? PrepareRenderedReference(clean) : PrepareRenderedReference(table, hold);
      const RenderedError a0 = f0.metrics.rendered, a1 = f1.metrics.rendered;
      const RenderedError b0 = Score(href, *FindModel(f0.model), f0.params),
                          b1 = Score(href, *FindModel(f1.model), f1.params);
      std::lock_guard<std::mutex> lock(mu);
      fmt::print("{:<26} {:<15} {:<15} S {:6.2f} -> {:6.2f} ({:5.1f} dB {:5.1f}% -> {:5.1f} dB {:5.1f}%)  hold S {:6.2f} -> {:6.2f} ({:5.1f}% -> {:5.1f}%) solve cpu {:.0f} -> {:.0f} ms; log_rmse {:.4f} -> {:.4f}\n",
                 inputs[i].substr(6), f0.model, f1.model, RenderedScoreDb(a0), RenderedScoreDb(a1), a0.psnr_db,
                 100 * a0.median_rel_error, a1.psnr_db, 100 * a1.median_rel_error,
                 RenderedScoreDb(b0), RenderedScoreDb(b1), 100 * b0.median_rel_error,
                 100 * b1.median_rel_error, ms_plain, ms_pol, f0.metrics.log_rmse, f1.metrics.log_rmse);
      std::fflush(stdout);
      sum.n++;
      sum.s0 += RenderedScoreDb(a0); sum.s1 += RenderedScoreDb(a1);
      sum.h0 += RenderedScoreDb(b0); sum.h1 += RenderedScoreDb(b1);
      sum.p0 += a0.psnr_db; sum.p1 += a1.psnr_db; sum.hp0 += b0.psnr_db; sum.hp1 += b1.psnr_db;
      sum.m0 += a0.median_rel_error; sum.m1 += a1.median_rel_error;
      sum.ge30_0 += a0.psnr_db >= 30; sum.ge30_1 += a1.psnr_db >= 30;
      sum.le15_0 += a0.median_rel_error <= 0.15; sum.le15_1 += a1.median_rel_error <= 0.15;
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  const double n = sum.n;
  fmt::print("n {} | median-of-material mean {:.2f}% -> {:.2f}% | S {:.2f} -> {:.2f} | PSNR {:.2f} -> {:.2f} | >=30dB {} -> {} | <=15% {} -> {} | holdout S {:.2f} -> {:.2f}, PSNR {:.2f} -> {:.2f}\n",
             sum.n, 100 * sum.m0 / n, 100 * sum.m1 / n, sum.s0 / n, sum.s1 / n, sum.p0 / n, sum.p1 / n, sum.ge30_0, sum.ge30_1,
             sum.le15_0, sum.le15_1, sum.h0 / n, sum.h1 / n, sum.hp0 / n, sum.hp1 / n);
}
