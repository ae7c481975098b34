// The options of one fit as `brdfit fit` takes them (strings and numbers, CLI defaults), turned
// into SampleOptions + FitOptions with the CLI's checks and messages. Shared by cli/cmd_fit.cc
// and the Python module (python/), so that a fit asked for in either way is the same fit.
#pragma once

#include <cstdint>
#include <string>

#include "fit/options.h"
#include "fit/samples.h"

namespace brdfit::pipeline {

struct FitSettings {
  std::string loss;  // empty: not given (kDefaultLoss; --model auto: each candidate's own)
  bool no_cosine = false;
  std::string robust = "none";
  double robust_scale = FitOptions{}.robust_scale;
  double cutoff = SampleOptions{}.cutoff_deg;
  std::string weighting = "bin-measure";
  std::string budget = DefaultFitBudget().ToString();  // stride:32 (fit/samples.h)
  std::uint64_t seed = 1;
  int multistart = 1;
  int max_iterations = FitOptions{}.max_iterations;
  int threads = 1;
  // The rendered polish (fit/rendered_polish.h); the default is FitOptions'.
  std::string polish = ToString(FitOptions{}.polish);
};

// Throws InputError naming the option ("--cutoff must be in (0, 90]") for a bad value.
void ApplyFitSettings(const FitSettings& s, SampleOptions* samples, FitOptions* fit);

}  // namespace brdfit::pipeline
