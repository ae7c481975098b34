// A cached fit of `brdfit render` (`render --cache DIR`, fit-<key>.json;
// pipeline/material_loader.h): {"model", "params", "param_names", "status", "source", "key"}.
// A cache entry is a file like any other and may hold anything: the reader checks it as
// strictly as a fit report (docs/reliability.md, "Render cache").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfit {

struct FitCacheEntry {
  std::string model;
  std::vector<double> params;
  std::vector<std::string> param_names;
  std::string status, source, key;
};

// The entry as JSON text (indented, one trailing newline).
std::string FitCacheEntryJson(const FitCacheEntry& e);

// The parameters of a cached fit of `model`. Throws InputError naming the file: not a JSON
// object, "model" or "params" missing or of the wrong type, another model, parameters that are
// not the model's (core/model_params.h CheckModelParams).
std::vector<double> ReadFitCacheEntry(const std::filesystem::path& path, const std::string& model);

}  // namespace brdfit
