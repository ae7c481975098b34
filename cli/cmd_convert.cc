// `brdfit convert INPUT -o OUT [--format merl|h5]`: a table in another file format — an RGL
// .bsdf or an NBRDF network tabulated on the MERL grid, a MERL file as brdfit HDF5 or back.
// The reading is LoadInput's (pipeline/inputs.h), the writing SaveTable's (io/table_io.h).
#include <fmt/core.h>

#include <filesystem>
#include <string>

#include "cli/command.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "core/input_name.h"
#include "io/output_policy.h"
#include "io/table_io.h"
#include "pipeline/inputs.h"

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct ConvertOptions {
  std::string input, out, format;
  bool quiet = false;
};

int RunConvert(const ConvertOptions& o) {
  const fs::path out = o.out;
  const TableFormat format = OutputTableFormat(out, o.format);
  std::vector<fs::path> inputs;
  if (!IsNbrdfInput(o.input)) inputs.push_back(o.input);
  CheckOutputs(inputs, {{out, "-o"}});
  const Table t = pipeline::LoadInput(o.input);
  CheckFormatHoldsGrid(format, t.grid, out);
  SaveTable(t, out, format);
  if (!o.quiet) {
    fmt::print("{} -> {} ({}; {} of {} cells valid, the others masked{})\n", TerminalSafe(o.input),
               TerminalSafe(out.string()),
               format == TableFormat::kMerl ? "MERL binary" : "brdfit HDF5 table", t.CountValid(),
               t.grid.NumCells(),
               format == TableFormat::kMerl ? ": written as -1, MERL's convention" : "");
  }
  return kExitOk;
}

Registrar reg{
    "convert",
    "Write a table in another format: an RGL .bsdf or nbrdf:NAME as MERL or HDF5, MERL <-> HDF5",
    [](CLI::App& sub) {
      auto o = std::make_shared<ConvertOptions>();
      sub.add_option("input", o->input,
                     "MERL .binary, brdfit .h5 or RGL .bsdf table, or nbrdf:NAME")
          ->required();
      sub.add_option("-o,--out", o->out, "output table (.binary or .h5)")->required();
      sub.add_option("--format", o->format, "merl | h5 (default: from the extension)");
      sub.add_flag("-q,--quiet", o->quiet, "no summary line");
      sub.footer(
          "Exit codes: 0 ok, 2 bad input or output.\n"
          "Examples:\n  brdfit convert vch_golden_yellow_rgb.bsdf -o golden.binary\n"
          "  brdfit convert nbrdf:pink-felt -o pink-felt.h5");
      return [o] { return RunConvert(*o); };
    }};

}  // namespace
}  // namespace brdfit::cli
