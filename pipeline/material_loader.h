// Resolves a scene's materials: loads only what its objects reference, computes missing fits
// and factorizations once and caches them on disk, keyed by the input's content and the
// options (pipeline/cache_key.h). Every decision is logged for `brdfit render --explain`.
#pragma once

#include <filesystem>
#include <set>
#include <string>

#include "preview/explain.h"
#include "preview/material.h"
#include "preview/scene.h"

namespace brdfit::pipeline {

struct LoadOptions {
  // Where computed fits and factorizations are kept. Empty: $BRDFIT_CACHE_DIR, else
  // $XDG_CACHE_HOME/brdfit, else ~/.cache/brdfit.
  std::filesystem::path cache_dir;
};

std::filesystem::path DefaultCacheDir();

// The cache key (hex) of the fit `brdfit fit TABLE --model MODEL` makes with its defaults: the
// table's content key (pipeline/inputs.h), the model, every option (OptionsJson) and the fit
// engine's revision (fit/options.h kFitEngineRevision): an entry of another revision is never read.
std::string FitCacheKey(const std::string& table_content_key, const std::string& model,
                        int engine_revision);

// Throws InputError naming the file for unreadable tables, reports, factor files.
// `used`: the material names to load (UsedMaterials); the others are skipped and logged.
preview::MaterialSet LoadMaterials(const preview::Scene& scene, const std::set<std::string>& used,
                                   const LoadOptions& options, preview::ExplainLog* log);

}  // namespace brdfit::pipeline
