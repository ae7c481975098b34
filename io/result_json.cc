#include "io/result_json.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "io/metrics_json.h"

namespace brdfit {

using nlohmann::json;

void JsonFields::Fail(const std::string& key, const std::string& problem) const {
  const std::string member = where_.empty() ? key : where_ + "." + key;
  throw InputError(file_, fmt::format("{} {}", member, problem));
}

JsonFields JsonFields::Child(const std::string& key) const {
  return {file_, where_.empty() ? key : where_ + "." + key};
}

json JsonFields::Object(const json& j, const char* key) const {
  const auto it = j.find(key);
  if (it == j.end()) return json::object();
  if (!it->is_object()) Fail(key, "is not an object");
  return *it;
}

double JsonFields::Number(const json& j, const char* key, double fallback, double lo) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (it->is_null()) Fail(key, "is null, not a number");
  if (!it->is_number()) Fail(key, fmt::format("is {}, not a number", it->type_name()));
  const double v = it->get<double>();
  if (!std::isfinite(v)) Fail(key, "is not finite");
  if (v < lo) Fail(key, fmt::format("is {}, below {}", v, lo));
  return v;
}

double JsonFields::Required(const json& j, const char* key, double lo) const {
  if (!j.contains(key)) Fail(key, "is missing");
  return Number(j, key, 0, lo);
}

std::size_t JsonFields::Count(const json& j, const char* key, std::size_t fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_number_integer() || it->get<double>() < 0) {
    Fail(key, fmt::format("is {}, not a count", it->dump()));
  }
  return it->get<std::size_t>();
}

bool JsonFields::Bool(const json& j, const char* key, bool fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_boolean()) Fail(key, fmt::format("is {}, not true or false", it->type_name()));
  return it->get<bool>();
}

std::string JsonFields::String(const json& j, const char* key, const std::string& fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_string()) Fail(key, fmt::format("is {}, not a string", it->type_name()));
  return it->get<std::string>();
}

void RenderedFromJson(const json& parent, const JsonFields& f, FitMetrics* m) {
  if (!parent.contains("rendered")) return;
  const json r = f.Object(parent, "rendered");
  const JsonFields rf = f.Child("rendered");
  RenderedError& e = m->rendered;
  e.ok = rf.Bool(r, "ok", true);
  e.problem = rf.String(r, "problem", "");
  if (e.ok) {
    for (const RenderedSummaryField& s : kRenderedSummary) {
      e.*s.value =
          s.required ? rf.Required(r, s.name, s.min_value)
                     : rf.Number(r, s.name, std::numeric_limits<double>::quiet_NaN(), s.min_value);
    }
    if (const std::string bad = RenderedLightsFromJson(r, &e); !bad.empty()) {
      const std::size_t space = bad.find(' ');  // "member problem"
      rf.Fail(bad.substr(0, space), bad.substr(space + 1));
    }
  }
}

FitMetrics MetricsFromJson(const json& j, bool ok_default, const JsonFields& f) {
  FitMetrics m;
  m.ok = f.Bool(j, "ok", ok_default);
  m.problem = f.String(j, "problem", "");
  for (const ErrorMetricField& e : kErrorMetrics) {
    m.*e.value = m.ok ? f.Required(j, e.name, 0) : f.Number(j, e.name, 0, 0);
  }
  m.cells = f.Count(j, "cells", 0);
  m.weighting = f.String(j, "weighting", "");
  m.cutoff_deg = f.Number(j, "cutoff_deg", 0, 0);
  RenderedFromJson(j, f, &m);
  return m;
}

}  // namespace brdfit
