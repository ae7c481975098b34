// The factorization options as `brdfit factor` takes them, checked with the CLI's messages into
// FactorOptions. Shared by cli/cmd_factor.cc and the Python module (python/py_factor.cc).
#pragma once

#include <string>

#include "factor/factor.h"

namespace brdfit::pipeline {

inline constexpr int kMaxRefineIterations = 10000;

struct FactorSettings {
  std::string param = "mccool";
  int resolution = 64;
  double lambda = FactorOptions{}.lambda;
  std::string weighting = "solid-angle";
  double max_theta_deg = 90;
  bool diffuse = false;
  int rank = 1;
  bool refine = false;
  int refine_iterations = FactorOptions{}.refine_iterations;
  std::string refine_loss = "rel";
};

// Throws InputError naming the option ("--res 2 outside [4, 1024]") for a bad value.
FactorOptions MakeFactorOptions(const FactorSettings& s);

}  // namespace brdfit::pipeline
