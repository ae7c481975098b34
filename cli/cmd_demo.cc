// `brdfit demo`: the whole pipeline on built-in synthetic materials, into one folder.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>

#include "cli/command.h"
#include "cli/demo.h"
#include "io/output_policy.h"

namespace brdfit::cli {
namespace {

struct DemoOptions {
  std::string out_dir = "demo-out";
  bool quick = false;
};

int RunDemo(const DemoOptions& opts) {
  DemoContext ctx;
  ctx.out_dir = opts.out_dir;
  ctx.quick = opts.quick;
  CheckOutputFolder(ctx.out_dir, "-o");
  MakeOutputFolder(ctx.out_dir);
  auto steps = DemoSteps();
  std::stable_sort(steps.begin(), steps.end(),
                   [](const DemoStep& a, const DemoStep& b) { return a.order < b.order; });
  for (const auto& step : steps) {
    fmt::print("== demo: {}\n", step.name);
    const int code = step.run(ctx);
    if (code != kExitOk) {
      fmt::print(stderr, "brdfit: demo step '{}' failed (exit {})\n", step.name, code);
      return code;
    }
  }
  fmt::print("demo outputs ({} files) in {}\n", ctx.outputs.size(),
             std::filesystem::absolute(ctx.out_dir).string());
  for (const auto& p : ctx.outputs) fmt::print("  {}\n", p.string());
  if (!ctx.report.empty()) {
    fmt::print("report: {}\n", std::filesystem::absolute(ctx.report).string());
  }
  return kExitOk;
}

Registrar reg{"demo", "Run the pipeline on built-in synthetic materials", [](CLI::App& sub) {
                auto opts = std::make_shared<DemoOptions>();
                sub.add_option("-o,--out", opts->out_dir, "output folder")->capture_default_str();
                sub.add_flag("--quick", opts->quick, "smaller grids and budgets (for tests)");
                sub.footer(
                    "Synthesizes tables, fits, factors, renders, benchmarks and ends by printing "
                    "the HTML report's path.\n"
                    "Exit codes: 0 ok, 1 some fit failed, 2 bad input or an output not writable.\n"
                    "Examples:\n  brdfit demo -o demo-out\n  brdfit demo --quick -o /tmp/d");
                return [opts] { return RunDemo(*opts); };
              }};

}  // namespace
}  // namespace brdfit::cli
