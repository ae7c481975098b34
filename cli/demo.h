// `brdfit demo` is assembled from steps that each area registers (cmd_demo.cc runs them in
// order): synthesize tables, fit them, factor them, render, report. A step writes into
// ctx.out_dir and appends the paths it wrote to ctx.outputs.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace brdfit::cli {

struct DemoContext {
  std::filesystem::path out_dir;
  std::vector<std::filesystem::path> tables;   // synthetic tables written by the synth step
  std::vector<std::filesystem::path> outputs;  // everything written, for the final summary
  std::filesystem::path report;                // the HTML report, printed last
  bool quick = false;                          // smaller grids / budgets (tests)
};

struct DemoStep {
  int order;  // 10 synth, 20 fit, 30 factor, 40 render, 90 report
  std::string name;
  std::function<int(DemoContext&)> run;  // returns an exit code; non-zero stops the demo
};

std::vector<DemoStep>& DemoSteps();

struct DemoStepRegistrar {
  DemoStepRegistrar(int order, std::string name, std::function<int(DemoContext&)> run) {
    DemoSteps().push_back({order, std::move(name), std::move(run)});
  }
};

}  // namespace brdfit::cli
