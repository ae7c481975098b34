// Where an output came from (docs/formats.md, "Provenance"): brdfit's version, the command
// line and the date of the run, and the input's name and content hash. Written into fit reports
// (HDF5 and JSON), factorization sidecars, EXR headers and the HTML report.
//
// The command line and the date change from run to run, so they are left out wherever a run
// promises byte-identical output (`--no-timings`); the version and the content hashes never
// change for the same work and are always written. Paths are recorded as the user gave them:
// never made absolute.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace brdfit {

struct Table;

// The CMake project version (as `brdfit --version` and brdfit.__version__).
std::string_view BrdfitVersion();

struct RunProvenance {
  std::string version;       // BrdfitVersion()
  std::string command_line;  // the process's arguments, shell-quoted where needed; may be empty
  std::string created;       // UTC, ISO 8601 ("2026-12-02T09:30:00Z"), $SOURCE_DATE_EPOCH
                             // when set; may be empty
};

// Records the process's command line (main() calls it once, before any thread starts).
void SetCommandLine(int argc, const char* const* argv);
// The command line recorded by SetCommandLine, or "" (a library caller, e.g. Python).
const std::string& CommandLine();

// This run's provenance; with_run_details = false (`--no-timings`): version only.
RunProvenance CurrentRunProvenance(bool with_run_details);

// A content hash of a table as loaded: its grid, values (bit patterns) and validity, not the
// bytes of its file, so a table saved to HDF5 and read back hashes as it did. "t64:" + 16 hex digits
// (FNV-1a over 8-byte words in four lanes, SplitMix64-finalized; an identity, not a
// cryptographic hash).
std::string TableContentHash(const Table& table);

}  // namespace brdfit
