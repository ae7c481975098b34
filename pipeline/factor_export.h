// Saving and loading factorizations: the textures and sidecar of io/factor_io.h, with the
// parameterization's formula, maps, units and gauge written into every EXR header.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "factor/factor.h"
#include "io/factor_io.h"

namespace brdfit {

// Writes <dir>/<stem>.p.exr, .q.exr (then .p2.exr, .q2.exr, ... for every further term) and
// .factor.json, with the diffuse value and rank in the sidecar. `extra` members (e.g.
// "source", "metrics", "provenance") are merged into the sidecar; the string members of
// "provenance" and the source's "file" and "hash" also go into every EXR header (as
// brdfit:<member>, brdfit:source, brdfit:source_hash). Without timings, the sidecar's stats
// leave out what depends on the run (system_seconds, seconds, refine_seconds, system_reused,
// system_rebuilt_for_mask): the same table and options give the same bytes in any process.
// Returns the paths written.
FactorPaths SaveFactorization(const Factorization& r, const std::filesystem::path& dir,
                              const std::string& stem,
                              const nlohmann::json& extra = nlohmann::json::object(),
                              bool include_timings = true);

// Reads a sidecar and its textures (every term, the diffuse value; version 1 files are rank 1
// without diffuse) into an evaluable BRDF. Throws InputError naming the file if the sidecar is
// inconsistent (io/factor_io.h), the parameterization is unknown, an EXR's map does not match
// it, or a texture is unusable.
FactoredBrdf LoadFactoredBrdf(const std::filesystem::path& json_path,
                              nlohmann::json* sidecar = nullptr);

// The sidecar members describing a factorization (parameterization, formula, gauge, solver
// options, every texture's map and units, stats with those of the refinement).
nlohmann::json DescribeFactorization(const Factorization& r);

}  // namespace brdfit
