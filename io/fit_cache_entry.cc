#include "io/fit_cache_entry.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/model_params.h"
#include "io/input_file.h"

namespace brdfit {

std::string FitCacheEntryJson(const FitCacheEntry& e) {
  nlohmann::json j;
  j["model"] = e.model;
  j["params"] = e.params;
  j["param_names"] = e.param_names;
  j["status"] = e.status;
  j["source"] = e.source;
  j["key"] = e.key;
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<double> ReadFitCacheEntry(const std::filesystem::path& path, const std::string& model) {
  const std::vector<char> bytes = ReadWholeFile(path);
  const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(path, "not a JSON object");
  const auto m = j.find("model");
  if (m == j.end() || !m->is_string()) throw InputError(path, "\"model\" is not a string");
  if (m->get<std::string>() != model) {
    throw InputError(path, "a fit of model '" + m->get<std::string>() + "', not '" + model + "'");
  }
  const auto p = j.find("params");
  if (p == j.end() || !p->is_array()) throw InputError(path, "\"params\" is not an array");
  std::vector<double> params;
  for (const auto& v : *p) {
    if (!v.is_number()) throw InputError(path, "\"params\" holds something other than numbers");
    params.push_back(v.get<double>());
  }
  if (const std::string bad = CheckModelParams(model, params); !bad.empty()) {
    throw InputError(path, bad);
  }
  return params;
}

}  // namespace brdfit
