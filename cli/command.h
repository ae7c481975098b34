// Self-registering subcommands. Each cli/cmd_<name>.cc defines one static Registrar:
//
//   static brdfit::cli::Registrar reg{"info", "Describe a table", [](CLI::App& sub) {
//     auto opts = std::make_shared<InfoOptions>();
//     sub.add_option("file", opts->path)->required();
//     return [opts] { return RunInfo(*opts); };   // returns the exit code
//   }};
//
// Exit codes (docs/cli.md): 0 ok, 1 some fit failed, 2 bad input or usage.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace brdfit::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFitFailed = 1;
inline constexpr int kExitBadInput = 2;

using RunFn = std::function<int()>;
using SetupFn = std::function<RunFn(CLI::App& sub)>;

struct CommandSpec {
  std::string name;
  std::string description;
  SetupFn setup;
};

std::vector<CommandSpec>& Commands();

struct Registrar {
  Registrar(std::string name, std::string description, SetupFn setup) {
    Commands().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

}  // namespace brdfit::cli
