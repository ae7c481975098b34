// The output policy every command applies to its outputs before doing any work
// (docs/reliability.md, "Output policy"): an output may not be one of the run's inputs or
// another output of the same run, and may not be an existing folder, FIFO, device node or
// socket. Identity is the (device, inode) of what a path resolves to after following links;
// for paths that do not exist yet, their weakly canonical form. "-" (standard output) is
// exempt.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfit {

struct PlannedOutput {
  std::filesystem::path path;
  std::string option;  // how the user named it, for the message: "-o", "--json", "--plot"
};

// Throws OutputError naming the output and the problem; writes nothing. Inputs that do not
// exist are ignored (their reader reports them). On success, removes the temporaries that dead
// processes' atomic writes left beside each output (io/temp_files.h).
void CheckOutputs(const std::vector<std::filesystem::path>& inputs,
                  const std::vector<PlannedOutput>& outputs);

// An output folder (factor -o DIR, demo -o DIR): may be missing or a folder, nothing else.
void CheckOutputFolder(const std::filesystem::path& dir, const std::string& option);

// Creates an output folder and its parents; OutputError naming it with the system's reason
// (was "filesystem error: cannot create directories").
void MakeOutputFolder(const std::filesystem::path& dir);

}  // namespace brdfit
