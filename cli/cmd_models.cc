// `brdfit models [NAME...] [--json]`: every registered model with its parameters, units,
// bounds, defaults, scales and roles (models/registry.h).
#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/error.h"
#include "core/suggest.h"
#include "models/registry.h"

namespace brdfit::cli {
namespace {

struct ModelsOptions {
  std::vector<std::string> names;
  bool json = false;
};

std::string_view RoleName(ParamRole role) {
  switch (role) {
    case ParamRole::kWeightR:
      return "weight_r";
    case ParamRole::kWeightG:
      return "weight_g";
    case ParamRole::kWeightB:
      return "weight_b";
    case ParamRole::kShape:
      break;
  }
  return "shape";
}

nlohmann::json ToJson(const ModelInfo& m) {
  nlohmann::json params = nlohmann::json::array();
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    const ParamSpec& p = m.params[i];
    params.push_back({{"name", m.param_names[i]},
                      {"unit", std::string(p.unit)},
                      {"lower", p.lower},
                      {"upper", p.upper},
                      {"default", p.init},
                      {"log_scale", p.log_scale},
                      {"role", std::string(RoleName(p.role))},
                      {"doc", std::string(p.doc)}});
  }
  return {{"name", m.name},
          {"doc", m.doc},
          {"value", "f_r in 1/sr per linear-RGB channel, without the cosine"},
          {"energy_conserving", m.energy_conserving},
          {"params", params}};
}

void PrintText(const ModelInfo& m) {
  fmt::print("{}\n  {}\n  energy conserving: {}\n", m.name, m.doc,
             m.energy_conserving ? "yes, for colour weights <= 1 (summed over lobes)" : "no");
  fmt::print("  {:<22} {:<4} {:>9} {:>9} {:>9} {:<5} {:<8} {}\n", "parameter", "unit", "lower",
             "upper", "default", "scale", "role", "description");
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    const ParamSpec& p = m.params[i];
    fmt::print("  {:<22} {:<4} {:>9.4g} {:>9.4g} {:>9.4g} {:<5} {:<8} {}\n", m.param_names[i],
               p.unit, p.lower, p.upper, p.init, p.log_scale ? "log" : "lin", RoleName(p.role),
               p.doc);
  }
}

int RunModels(const ModelsOptions& opts) {
  std::vector<const ModelInfo*> selected;
  if (opts.names.empty()) {
    for (const auto& m : AllModels()) selected.push_back(&m);
  } else {
    for (const auto& name : opts.names) {
      const ModelInfo* m = FindModel(name);
      if (m == nullptr) {
        throw InputError("unknown model '" + name + "'" + SuggestionAfter(name, AllModelNames()) +
                         "; known models: " + ModelNames());
      }
      selected.push_back(m);
    }
  }
  if (opts.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const ModelInfo* m : selected) out.push_back(ToJson(*m));
    fmt::print("{}\n", out.dump(2));
    return kExitOk;
  }
  fmt::print(
      "Every model returns f_r in 1/sr per linear-RGB channel, without the cosine; directions "
      "point away\nfrom the surface; alpha is the slope-space roughness (docs/models.md).\n"
      "Roles: weight_* parameters enter linearly (colour weights), shape parameters do not.\n\n");
  for (const ModelInfo* m : selected) {
    PrintText(*m);
    fmt::print("\n");
  }
  return kExitOk;
}

Registrar reg{"models", "List every model with its parameters and bounds", [](CLI::App& sub) {
                auto opts = std::make_shared<ModelsOptions>();
                sub.add_option("names", opts->names, "only these models (default: all)");
                sub.add_flag("--json", opts->json, "machine-readable output");
                sub.footer(
                    "Exit codes: 0 ok, 2 unknown model name.\n"
                    "Examples:\n  brdfit models\n  brdfit models lambert+ggx cook-torrance\n"
                    "  brdfit models --json > models.json");
                return [opts] { return RunModels(*opts); };
              }};

}  // namespace
}  // namespace brdfit::cli
