// Table inputs shared by the subcommands: files (any format io/table_io.h detects) and NBRDF
// networks ("nbrdf:NAME", "nbrdf:all": the networks of ../shared/data/merl_nbrdf.zip tabulated
// on the MERL grid in memory, io/nbrdf.h). An input's material name: core/input_name.h.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/table.h"

namespace brdfit::pipeline {

// The NBRDF archive: `given` if not empty, else $BRDFIT_NBRDF_ZIP, else
// ../shared/data/merl_nbrdf.zip relative to the working directory or beside an ancestor of the
// executable's folder. When none exists, the first candidate (the reader then names it).
std::filesystem::path NbrdfArchive(const std::string& given = "");

// "nbrdf:all" becomes one "nbrdf:NAME" per material of the archive; other inputs are kept.
std::vector<std::string> ExpandInputs(const std::vector<std::string>& inputs);

// The files the inputs read (nbrdf:NAME reads the archive), for the output policy
// (io/output_policy.h).
std::vector<std::filesystem::path> InputFiles(const std::vector<std::string>& inputs);

// Loads a file or tabulates an NBRDF network (provenance.source = the input). Throws InputError.
Table LoadInput(const std::string& input);

// A key of the input's content for caches (pipeline/cache_key.h): the file's bytes, or for
// nbrdf:NAME the archive's bytes and the name. Throws InputError if it cannot be read.
std::string InputContentKey(const std::string& input);

}  // namespace brdfit::pipeline
