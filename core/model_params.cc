#include "core/model_params.h"

#include <fmt/core.h>

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace brdfit {

namespace {

// Every spelling that names parameter i: its registry name ("ggx.alpha" in a sum, "alpha" in a
// single model), its bare name, and "<model>.<name>" for single models.
std::vector<std::string> Spellings(const ModelInfo& m, std::size_t i) {
  std::vector<std::string> s = {m.param_names[i]};
  const std::string bare(m.params[i].name);
  if (bare != s[0]) s.push_back(bare);
  if (m.param_names[i].find('.') == std::string::npos) s.push_back(m.name + "." + bare);
  return s;
}

bool IsUnqualified(const ModelInfo& m, std::size_t i, std::string_view name) {
  return name == m.params[i].name && name != m.param_names[i];
}

}  // namespace

std::string CheckModelParams(const std::string& model, const std::vector<double>& params) {
  const ModelInfo* info = FindModel(model);
  if (!info) return "unknown model '" + model + "'";
  if (params.size() != info->params.size()) {
    return fmt::format("{} parameters, model {} has {}", params.size(), model, info->params.size());
  }
  for (std::size_t k = 0; k < params.size(); ++k) {
    const ParamSpec& s = info->params[k];
    if (!std::isfinite(params[k]) || params[k] < s.lower || params[k] > s.upper) {
      return fmt::format("parameter {} = {} outside the model's bounds [{}, {}]",
                         info->param_names[k], params[k], s.lower, s.upper);
    }
  }
  return "";
}

std::string CheckModelParamNames(const ModelInfo& model, const std::vector<std::string>& names) {
  if (names.size() != model.param_names.size()) {
    return fmt::format("{} names, model {} has {} parameters", names.size(), model.name,
                       model.param_names.size());
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] != model.param_names[k]) {
      return fmt::format("parameter {} is '{}', model {} calls it '{}'", k, names[k], model.name,
                         model.param_names[k]);
    }
  }
  return "";
}

std::string ValidParamNames(const ModelInfo& m) {
  std::string out;
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    std::size_t same_bare = 0;
    for (const auto& p : m.params) same_bare += p.name == m.params[i].name;
    out += (out.empty() ? "" : ", ") + m.param_names[i];
    if (same_bare == 1 && m.param_names[i] != m.params[i].name) {
      out += " (" + std::string(m.params[i].name) + ")";
    }
  }
  return out;
}

std::size_t FindParamIndex(const ModelInfo& m, std::string_view name) {
  std::vector<std::size_t> hits;
  // A qualified (exact registry) name wins over a bare one.
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    if (m.param_names[i] == name) return i;
  }
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    for (const auto& s : Spellings(m, i)) {
      if (s == name) {
        hits.push_back(i);
        break;
      }
    }
  }
  if (hits.size() == 1) return hits[0];
  if (hits.empty()) {
    throw InputError(fmt::format("unknown parameter '{}' for model {}; valid: {}", name, m.name,
                                 ValidParamNames(m)));
  }
  std::string choices;
  for (std::size_t i : hits) {
    if (IsUnqualified(m, i, name)) choices += (choices.empty() ? "" : ", ") + m.param_names[i];
  }
  throw InputError(fmt::format("parameter '{}' is ambiguous for model {}; use one of {}", name,
                               m.name, choices));
}

std::vector<double> ResolveModelParams(const ModelInfo& m,
                                       const std::vector<std::string>& assignments) {
  std::vector<double> p = m.DefaultParams();
  std::vector<bool> given(p.size(), false);
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(fmt::format("--param '{}': expected name=value", a));
    }
    const std::string name = a.substr(0, eq), text = a.substr(eq + 1);
    const std::size_t i = FindParamIndex(m, name);
    double v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
      throw InputError(fmt::format("--param {}: '{}' is not a finite number", name, text));
    }
    const ParamSpec& s = m.params[i];
    if (v < s.lower || v > s.upper) {
      throw InputError(fmt::format("--param {}={} is outside the bounds [{}, {}] of {}", name, text,
                                   s.lower, s.upper, m.param_names[i]));
    }
    if (given[i]) throw InputError(fmt::format("--param {} given twice", m.param_names[i]));
    given[i] = true;
    p[i] = v;
  }
  return p;
}

std::string ParamsToJson(const ModelInfo& m, const std::vector<double>& params) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < params.size(); ++i) j[m.param_names[i]] = params[i];
  return j.dump();
}

}  // namespace brdfit
