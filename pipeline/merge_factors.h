// `brdfit merge OUT_DIR PART_DIRS...`: the output folders of `brdfit factor --shard I/N`
// (docs/scale.md) into one folder, equal file for file to the folder one process would have
// written (with --no-timings parts: byte for byte, the sidecars hold nothing run-dependent).
//
//  * A part's files are its sidecars (*.factor.json) and the textures each names (its
//    "textures" member); other files are not copied.
//  * A file name in two parts: kept once when the bytes are identical, a conflict otherwise
//    (InputError naming both folders and the file).
//  * Written into OUT_DIR (created) atomically file by file (io/atomic_file.h); the parts are
//    only read.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

namespace brdfit::pipeline {

struct MergedFactors {
  std::size_t sidecars = 0;    // factorizations in the merged folder
  std::size_t files = 0;       // files written
  std::size_t duplicates = 0;  // identical files met again and kept once
};

// Throws InputError for an unreadable part or sidecar, a texture a sidecar names but its folder
// lacks, or a conflict; OutputError if OUT_DIR cannot be written.
MergedFactors MergeFactorFolders(const std::filesystem::path& out,
                                 const std::vector<std::filesystem::path>& parts);

}  // namespace brdfit::pipeline
