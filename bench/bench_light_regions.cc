// Accuracy under every light (docs/accuracy.md, "Every light"): per MERL proxy, the default fit
// (`brdfit fit T`: the --model auto candidates, each polished, one chosen by
// core/model_choice.h) scored under lights the fit never saw, in three regions of the BRDF's
// domain. A light at angle a from the view lights every pixel at the half-angle theta_d = a / 2:
//   front  a in {10, 40, 55, 75}      theta_d  5 - 37.5 deg
//   side   a in {88, 100, 112, 122}   theta_d 44 - 61 deg
//   rim    a in {130, 142, 155, 168}  theta_d 65 - 84 deg (light from behind the sphere)
//   environment: the judge's sky with another sun (35 deg from the view, to the right and up,
//          irradiance 6) and other directions (seed 7), at half the resolution
//          (fit/rendered_environment.h)
// each region's four images pooled (one PSNR, one median relative luminance error), rendered
// at 96 x 96 (the fit's judge renders 64 x 64, so a lobe narrower than a pixel cannot hide
// between the judge's pixel centres).
//   bench_light_regions [--nbrdf all|NAME,...] [--jobs N] [--model M] [--res N] [--verbose 1]
//                       [--fits FITS.json]
// --model: fit that candidate alone; --res: the held-out images' resolution; --verbose: each
// chosen fit's judge numbers per light and region, and its parameters; --fits: fit nothing,
// score the chosen fits of a `brdfit fit --json` file of these tables instead (so that the
// choices of two builds are scored by one scorer; "judge S" is then the file's).
// One line per table and a summary: mean PSNR per region, materials at >= 30 dB and <= 15 %
// median luminance error per region and in all three, the median of the medians.
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <thread>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "bench/bench_tables.h"
#include "core/model_choice.h"
#include "core/rendered_regions.h"
#include "fit/fitter.h"
#include "fit/rendered_error.h"
#include "models/registry.h"
#include "pipeline/batch_fit.h"
#include "pipeline/inputs.h"

using namespace brdfit;

namespace {

constexpr int kRegions = 4;
const char* const* kRegionNames = kRenderedRegionNames;
const std::array<std::vector<double>, 3> kHeldOut = {std::vector<double>{10, 40, 55, 75},
                                                     std::vector<double>{88, 100, 112, 122},
                                                     std::vector<double>{130, 142, 155, 168}};

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names = {"all"};
  int jobs = 2, res = 96;
  bool verbose = false;
  std::string only_model, fits_json;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--nbrdf") names = bench::SplitList(v);
    if (a == "--jobs") jobs = std::atoi(v.c_str());
    if (a == "--model") only_model = v;
    if (a == "--res") res = std::atoi(v.c_str());
    if (a == "--verbose") verbose = v != "0";
    if (a == "--fits") fits_json = v;
  }
  // The chosen fit per source of a fits JSON: its model and parameters in the model's order.
  struct Given {
    FitResult fit;
    double score_db = 0;  // the file's S
  };
  std::map<std::string, Given> given;
  if (!fits_json.empty()) {
    std::ifstream in(fits_json);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& fit : j.at("fits")) {
      if (!fit.value("chosen", false)) continue;
      FitResult r;
      r.model = fit.at("model").get<std::string>();
      const ModelInfo* m = FindModel(r.model);
      if (!m) continue;  // a factorization: not an analytic model
      for (const std::string& name : m->param_names) {
        r.param_names.push_back(name);
        r.params.push_back(fit.at("params").at(name).get<double>());
      }
      const auto& re = fit.at("metrics").at("rendered");
      given[fit.at("source").get<std::string>()] = {
          r, re.contains("score_db") ? re.at("score_db").get<double>() : NAN};
    }
  }
  const auto inputs = bench::NbrdfStudyInputs(names);
  std::mutex mu;
  std::atomic<std::size_t> next{0};
  struct Row {
    std::array<double, kRegions> psnr{}, median{}, body{};
    double judge_s = 0, solve_ms = 0;
  };
  std::vector<Row> rows;
  // The fit under the held-out lights, region by region, into row; the line printed for it.
  const auto score_held_out = [&](const Table& table, const FitResult& f, Row* row) {
    std::string line;
    for (int r = 0; r < kRegions; ++r) {
      RenderedErrorOptions o;
      o.resolution = res;
      const bool env = r == static_cast<int>(LightRegion::kEnvironment);
      o.light_angles_deg = env ? std::vector<double>{0} : kHeldOut[r];
      if (env) {
        o.environment.sun_polar_deg = 35;
        o.environment.sun_azimuth_deg = 40;
        o.environment.sun_irradiance = 6;
        o.environment.seed = 7;
        o.environment.resolution = std::max(8, res / 2);
      } else {
        o.environment.samples = 0;
      }
      const RenderedError e =
          ComputeRenderedError(table, ModelBrdf(*FindModel(f.model), f.params), o);
      const RenderedRegionError& g = e.regions[static_cast<std::size_t>(r)];
      row->psnr[r] = e.ok ? (env ? g.psnr_db : e.psnr_db) : 0;
      row->median[r] = e.ok ? (env ? g.median_rel_error : e.median_rel_error) : 1;
      // The body's colour is the directional images' (core/metrics.h): none for the environment.
      row->body[r] = e.ok ? (env ? 0 : e.body_color_error) : 1;
      line += fmt::format("  {} {:5.1f} dB {:5.1f}% body {:4.0f}%", kRegionNames[r], row->psnr[r],
                          100 * row->median[r], 100 * row->body[r]);
    }
    return line;
  };
  auto worker = [&] {
    for (std::size_t i = next++; i < inputs.size(); i = next++) {
      const Table table = pipeline::LoadInput(inputs[i]);
      if (!fits_json.empty()) {
        const auto it = given.find(inputs[i]);
        if (it == given.end()) continue;
        const FitResult& f = it->second.fit;
        Row row;
        row.judge_s = it->second.score_db;
        const std::string line = score_held_out(table, f, &row);
        std::lock_guard<std::mutex> lock(mu);
        fmt::print("{:<28} {:<18} judge S {:6.2f}{}\n", inputs[i].substr(6), f.model, row.judge_s,
                   line);
        std::fflush(stdout);
        rows.push_back(row);
        continue;
      }
      SampleOptions so;
      so.budget = DefaultFitBudget();
      std::vector<FitResult> fits;
      double solve_ms = 0;
      for (const auto& c : pipeline::kAutoCandidates) {
        if (!only_model.empty() && c.model != only_model) continue;
        FitOptions fo;
        fo.loss = *c.loss;
        fo.polish = PolishKind::kRendered;
        PreparedTable pt = PrepareTable(table, so, fo);
        fits.push_back(FitPrepared(c.model, pt, fo));
        solve_ms += fits.back().times.solve_cpu;
      }
      std::vector<const FitResult*> ptrs;
      for (const auto& f : fits) ptrs.push_back(&f);
      const auto choice = ChooseFit(ptrs);
      if (!choice) continue;
      const FitResult& f = fits[choice->index];
      Row row;
      row.judge_s = choice->score_db;
      row.solve_ms = solve_ms;
      const std::string line = score_held_out(table, f, &row);
      std::lock_guard<std::mutex> lock(mu);
      fmt::print("{:<28} {:<18} judge S {:6.2f}{}  solve cpu {:.0f} ms\n", inputs[i].substr(6),
                 f.model, row.judge_s, line, solve_ms);
      if (verbose) {
        const RenderedError& j = f.metrics.rendered;
        for (int k = 0; k < j.num_lights; ++k) {
          fmt::print("   judge light {:5.1f}: {:5.1f} dB {:5.1f}%\n", j.lights[k].light_deg,
                     j.lights[k].psnr_db, 100 * j.lights[k].median_rel_error);
        }
        for (const RegionError& g : RenderedRegions(j)) {
          fmt::print("   judge region: {:5.1f} dB {:5.1f}% S {:6.2f}\n", g.psnr_db,
                     100 * g.median_rel_error, g.score_db);
        }
        std::string ps;
        for (std::size_t k = 0; k < f.params.size(); ++k) {
          const bool bound = k < f.at_bound.size() && f.at_bound[k];
          ps += fmt::format(" {}={:.4g}{}", k < f.param_names.size() ? f.param_names[k] : "?",
                            f.params[k], bound ? "(bound)" : "");
        }
        fmt::print("   params{}\n", ps);
      }
      std::fflush(stdout);
      rows.push_back(row);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (rows.empty()) return 0;
  const double n = static_cast<double>(rows.size());
  int all_ok = 0, body_off = 0;
  std::vector<double> solve;
  for (const Row& row : rows) {
    bool ok = true, off = false;
    for (int r = 0; r < kRegions; ++r) {
      ok = ok && row.psnr[r] >= 30 && row.median[r] <= 0.15;
      off = off || row.body[r] > kBodyColorTolerance;
    }
    all_ok += ok;
    body_off += off;
    solve.push_back(row.solve_ms);
  }
  for (int r = 0; r < kRegions; ++r) {
    double sum = 0;
    int ge30 = 0, le15 = 0, body_le = 0;
    std::vector<double> med, body;
    for (const Row& row : rows) {
      sum += row.psnr[r];
      ge30 += row.psnr[r] >= 30;
      le15 += row.median[r] <= 0.15;
      body_le += row.body[r] <= kBodyColorTolerance;
      med.push_back(row.median[r]);
      body.push_back(row.body[r]);
    }
    fmt::print(
        "REGION {:<11} n {} | mean PSNR {:.2f} dB | >= 30 dB {} | median lum <= 15 % {} | "
        "median of medians {:.1f} % | body colour within {:.0f} % {} (median {:.1f} %)\n",
        kRegionNames[r], rows.size(), sum / n, ge30, le15, 100 * Median(med),
        100 * kBodyColorTolerance, body_le, 100 * Median(body));
  }
  fmt::print(
      "ALL n {} | >= 30 dB and <= 15 % in every region {} | body colour off in a region {} | "
      "solve CPU per table median {:.0f} ms\n",
      rows.size(), all_ok, body_off, Median(solve));
}
