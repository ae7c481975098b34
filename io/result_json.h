// Strict reading of the JSON members of result files (factorization sidecars, fit parameters
// files), the one strictness of every reader of them (io/fit_params_json.h, `brdfit report`,
// `compare`): a member that is absent takes its documented
// default, one that is present must have its type and range, else InputError names the file
// and the member ("metrics.fit_metrics.log_rmse is null, not a number"). A null or negative
// error read as 0 made a broken result look perfect.
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/metrics.h"

namespace brdfit {

class JsonFields {
 public:
  JsonFields(std::filesystem::path file, std::string where)
      : file_(std::move(file)), where_(std::move(where)) {}

  // The members of object `key` of j (absent: an empty object) with where extended by key.
  JsonFields Child(const std::string& key) const;
  nlohmann::json Object(const nlohmann::json& j, const char* key) const;

  // Finite and >= lo; absent: fallback.
  double Number(const nlohmann::json& j, const char* key, double fallback,
                double lo = -HUGE_VAL) const;
  // Finite and >= lo; absent is an error too.
  double Required(const nlohmann::json& j, const char* key, double lo = -HUGE_VAL) const;
  std::size_t Count(const nlohmann::json& j, const char* key, std::size_t fallback) const;
  bool Bool(const nlohmann::json& j, const char* key, bool fallback) const;
  std::string String(const nlohmann::json& j, const char* key, const std::string& fallback) const;

  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const;

 private:
  std::filesystem::path file_;
  std::string where_;  // "metrics.fit_metrics" or "fits[3].metrics"; empty at the root
};

// The metrics of a sidecar's "fit_metrics" or a fit parameters file's "metrics" (the fields of
// core/metrics.h kErrorMetrics): ok (default ok_default); when ok, every error metric is
// required and >= 0; the rendered-image summary "rendered" (io/metrics_json.h) when present,
// its numbers (kRenderedSummary) required when its ok is true.
FitMetrics MetricsFromJson(const nlohmann::json& j, bool ok_default, const JsonFields& f);
// Only the rendered-image summary "rendered" of `parent`, into m (a sidecar keeps it beside
// fit_metrics).
void RenderedFromJson(const nlohmann::json& parent, const JsonFields& f, FitMetrics* m);

}  // namespace brdfit
