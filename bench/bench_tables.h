// Tables shared by the benchmark programs.
#pragma once

#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/model_params.h"
#include "core/synth.h"
#include "models/registry.h"
#include "pipeline/inputs.h"

namespace brdfit::bench {

// The NBRDF archive of the studies (../shared/data; absent on a machine without the data).
inline std::filesystem::path NbrdfZip() {
  return std::filesystem::path(BRDFIT_SHARED_DATA) / "merl_nbrdf.zip";
}

// The MERL proxies of the bench tables (with the synthetic table below, "the six bench tables"
// of docs/fitting.md): bench_fit and bench_fit_cli.
inline const std::vector<std::string> kBenchNbrdf = {"gold-metallic-paint", "blue-acrylic",
                                                     "pink-felt", "chrome",
                                                     "specular-black-phenolic"};

// "a,b,,c" -> {"a", "b", "c"}: the comma-separated lists of the programs' options.
inline std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string part;
  while (std::getline(ss, part, ',')) {
    if (!part.empty()) out.push_back(part);
  }
  return out;
}

// Lambert + GGX (alpha 0.08, warm colours) on the full MERL grid with 5 % log-normal noise and
// 10 % holes, seed 1: the synthetic table of bench_fit and bench_metrics.
// The inputs nbrdf:NAME of a study over ../shared/data/merl_nbrdf.zip ("all": every material),
// or none, with a message, when the archive is absent.
inline std::vector<std::string> NbrdfStudyInputs(const std::vector<std::string>& names) {
  const std::filesystem::path zip = NbrdfZip();
  if (!std::filesystem::exists(zip)) {
    fmt::print(stderr, "{} not found: nothing to measure\n", zip.string());
    return {};
  }
  setenv("BRDFIT_NBRDF_ZIP", zip.c_str(), 1);
  std::vector<std::string> inputs;
  for (const auto& n : names) inputs.push_back("nbrdf:" + n);
  return pipeline::ExpandInputs(inputs);
}

inline Table SyntheticLambertGgxTable() {
  const ModelInfo& m = *FindModel("lambert+ggx");
  const std::vector<double> p = ResolveModelParams(
      m, {"kd_r=0.2", "kd_g=0.1", "kd_b=0.05", "ks_r=0.5", "ks_g=0.4", "ks_b=0.3", "alpha=0.08"});
  SynthOptions o;
  o.noise = 0.05;
  o.missing_fraction = 0.1;
  o.seed = 1;
  return SynthesizeTable(
      Grid::Merl(), [&](const Geometry& g, double rgb[3]) { m.eval(p.data(), g, rgb); }, o);
}

}  // namespace brdfit::bench
