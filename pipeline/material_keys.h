// The material key of each input of a batch (docs/scale.md "Material
// identity"): a readable name, unique within the batch and the same on every machine and in
// every shard given the same tables, never the file stem alone.
//
//  * nbrdf:NAME is NAME (the archive's member names are unique).
//  * A file is its path relative to the common root of the batch's files (the deepest folder
//    holding all of them, after making the paths absolute and lexically normal), '/'-separated,
//    without its extension: a/x.binary and b/x.binary are "a/x" and "b/x". Files of one folder
//    (and a single file) keep their stem, as before: "gold-paint" for data/gold-paint.binary.
//  * Where two inputs would still share a key (x.binary and x.h5 in one folder, a file named
//    like an NBRDF member), the files keep their extension ("x.binary", "x.h5").
//  * The same file given twice (the same absolute normal path) is an InputError, as is any key
//    that is still not unique.
// The key does not depend on the working directory or the mount point: shards on hosts that
// see the tables under /data/brdf and /mnt/brdf give the same keys.
#pragma once

#include <string>
#include <vector>

namespace brdfit::pipeline {

// One key per input, in the inputs' order (inputs already expanded, pipeline/inputs.h).
std::vector<std::string> MaterialKeys(const std::vector<std::string>& inputs);

}  // namespace brdfit::pipeline
