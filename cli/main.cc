// brdfit: fit, factor, preview and report tabulated isotropic BRDFs.
#include <fmt/core.h>

#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/interrupt.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "core/provenance.h"
#include "core/suggest.h"

namespace brdfit::cli {
std::vector<CommandSpec>& Commands() {
  static std::vector<CommandSpec> commands;
  return commands;
}
std::vector<DemoStep>& DemoSteps() {
  static std::vector<DemoStep> steps;
  return steps;
}
}  // namespace brdfit::cli

using brdfit::cli::kExitBadInput;
using brdfit::cli::kExitOk;

namespace {

// A command's output that never reached standard output (a full disk, a closed pipe) is an
// output error: exit 2, not the command's 0.
int CheckStdout(int code) {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return code;
  fmt::print(stderr, "brdfit: error: cannot write to standard output: {}\n",
             errno ? std::strerror(errno) : "write failed");
  return code == kExitOk ? kExitBadInput : code;
}

// Large arrays (a table's samples, weights, plans: 1-30 MB each, allocated and freed several
// times per fit) come from the heap and are reused, instead of each being a fresh mmap whose
// pages the kernel faults in and zeroes one by one and unmaps at its free. On the 2-core VM a
// page fault costs ~0.5 ms per MB: `brdfit fit` of a MERL table takes 2,300 faults (11 %) less
// (docs/fitting.md, "Whole command"). 32 MiB is the largest threshold glibc accepts (a table's
// 35 MB value array stays an mmap, allocated once). Up to 16 MiB of freed heap is kept rather
// than trimmed: the 100-table batch's peak RSS stays ~255 MB (512 MiB kept 340 MB; glibc's
// 128 KiB default trimmed and regrew the heaps: 15 s of system time) and its system time falls
// from ~4.3 to ~3.6 s. The executable's choice only: the library leaves its host's allocator
// alone.
void KeepLargeArraysOnTheHeap() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 16 << 20);
}

// For a usage error: the command or option the user most likely meant (core/suggest.h), as
// "unknown command 'fti' (did you mean fit?)" or " (did you mean --model?)" for the first
// unknown long option of the command; "" when nothing is close.
std::string UsageHint(CLI::App& app, int argc, char** argv, bool* replaces) {
  *replaces = false;
  if (argc < 2) return "";
  const std::string first = argv[1];
  std::vector<std::string> commands;
  CLI::App* command = nullptr;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    commands.push_back(sub->get_name());
    if (sub->get_name() == first) command = sub;
  }
  if (!command) {
    if (first.starts_with("-")) return "";
    const std::string hint = brdfit::SuggestionAfter(first, commands);
    *replaces = !hint.empty();
    return hint.empty() ? "" : "unknown command '" + first + "'" + hint;
  }
  std::vector<std::string> options;
  for (const CLI::Option* o : command->get_options()) {
    for (const std::string& l : o->get_lnames()) options.push_back("--" + l);
  }
  for (int i = 2; i < argc; ++i) {
    const std::string a = std::string(argv[i]).substr(0, std::string(argv[i]).find('='));
    if (a == "--") break;
    if (!a.starts_with("--") || std::find(options.begin(), options.end(), a) != options.end()) {
      continue;
    }
    return brdfit::SuggestionAfter(a, options);
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace brdfit::cli;
  KeepLargeArraysOnTheHeap();
  InstallInterruptHandler();  // before any thread: they all inherit the blocked signals
  brdfit::SetCommandLine(argc, argv);  // provenance of every output (core/provenance.h)
  CLI::App app{
      "brdfit: fit analytic models to tabulated isotropic BRDFs, factor them, preview "
      "and report.\nRun 'brdfit <command> --help' for a command's options and examples."};
  app.set_version_flag("--version", "brdfit " BRDFIT_VERSION);  // CMake project version
  app.require_subcommand(1);
  std::map<CLI::App*, RunFn> runs;
  for (auto& spec : Commands()) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    runs[sub] = spec.setup(*sub);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print as CLI11 does; a usage error gets brdfit's prefix like every
    // other error.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    bool replaces = false;
    const std::string hint = UsageHint(app, argc, argv, &replaces);
    fmt::print(stderr,
               "brdfit: error: {}\nRun 'brdfit --help' or 'brdfit <command> --help' for "
               "the options.\n",
               TerminalSafe(replaces ? hint : e.what() + hint));
    return kExitBadInput;
  }
  try {
    for (auto& [sub, run] : runs) {
      if (sub->parsed()) return CheckStdout(run());
    }
  } catch (const brdfit::InputError& e) {
    fmt::print(stderr, "brdfit: error: {}\n", TerminalSafe(e.what()));
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "brdfit: error: {}\n", TerminalSafe(e.what()));
    return kExitBadInput;
  }
  return kExitBadInput;
}
