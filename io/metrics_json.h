// JSON of the metric structs of core/metrics.h, shared by every writer of JSON results (fit
// parameters, io/fit_report.h; factorization sidecars, cli/cmd_factor.cc), so that a fit and a
// factorization name and lay out the same numbers alike (docs/formats.md).
#pragma once

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "core/metrics.h"

namespace brdfit {

// The rendered-image metric (docs/accuracy.md) as written under "metrics"/"rendered":
//   {the numbers of core/metrics.h kRenderedSummary, "ok"}
// plus "problem" when ok is false (the numbers are then zeros, as RenderedError holds them),
// and when ok: "score_db" (S, core/model_choice.h), "regions" ({"front"|"side"|"rim"|"environment":
// {"lights", "psnr_db", "median_rel_error", "score_db"}}, the regions with lights;
// core/rendered_regions.h) and "lights" ([{"light_deg", "psnr_db", "median_rel_error"}]).
nlohmann::ordered_json RenderedErrorJson(const RenderedError& e);
// Its "regions" object alone (also `compare --json`'s).
nlohmann::ordered_json RenderedRegionsJson(const RenderedError& e);

// Whether a RenderedError was computed at all (a failed fit is not scored): the writers leave
// "rendered" out when it was not.
inline bool RenderedErrorComputed(const RenderedError& e) { return e.num_lights > 0; }

// The per-light and per-region numbers of a "rendered" object into e->lights, e->num_lights
// and e->regions. Without "lights" (files written before the metric had regions), the pooled
// numbers as one light at 0 degrees, so that S is what it was then. Returns the problem
// ("lights[2].psnr_db is missing or not a number in [-1000, 1000]"), empty when none.
template <class Json>
std::string RenderedLightsFromJson(const Json& rendered, RenderedError* e) {
  if (const auto rg = rendered.find("regions"); rg != rendered.end()) {
    if (!rg->is_object()) return "regions is not an object";
    for (const auto& [name, value] : rg->items()) {
      int g = 0;
      while (g < kRenderedRegions && name != kRenderedRegionNames[g]) ++g;
      if (g == kRenderedRegions) return fmt::format("regions has no region '{}'", name);
      if (!value.is_object() || !value.contains("lights") || !value["lights"].is_number_integer() ||
          value["lights"].template get<long long>() < 1 ||
          value["lights"].template get<long long>() > kRenderedMaxLights ||
          !value.contains("psnr_db") || !value["psnr_db"].is_number() ||
          !value.contains("median_rel_error") || !value["median_rel_error"].is_number() ||
          !(value["median_rel_error"].template get<double>() >= 0)) {
        return fmt::format("regions.{} needs lights (1 to {}), psnr_db and median_rel_error >= 0",
                           name, kRenderedMaxLights);
      }
      e->regions[g] = {static_cast<int>(value["lights"].template get<long long>()),
                       value["psnr_db"].template get<double>(),
                       value["median_rel_error"].template get<double>()};
    }
  }
  const auto it = rendered.find("lights");
  if (it == rendered.end()) {
    e->num_lights = 1;
    e->lights[0] = {};
    e->lights[0].psnr_db = e->psnr_db;
    e->lights[0].median_rel_error = e->median_rel_error;
    e->lights[0].p95_rel_error = e->p95_rel_error;
    return "";
  }
  if (!it->is_array() || it->empty() || it->size() > static_cast<std::size_t>(kRenderedMaxLights)) {
    return fmt::format("lights is not an array of 1 to {} lights", kRenderedMaxLights);
  }
  e->num_lights = static_cast<int>(it->size());
  for (std::size_t k = 0; k < it->size(); ++k) {
    const Json& l = (*it)[k];
    RenderedLightError& out = e->lights[k];
    out = {};
    for (const auto& [key, value, lo, hi] :
         {std::tuple<const char*, double*, double, double>{"light_deg", &out.light_deg, 0, 180},
          {"psnr_db", &out.psnr_db, -1e3, 1e3},
          {"median_rel_error", &out.median_rel_error, 0, 1e300}}) {
      if (!l.is_object() || !l.contains(key) || !l[key].is_number() ||
          !(l[key].template get<double>() >= lo && l[key].template get<double>() <= hi)) {
        return fmt::format("lights[{}].{} is missing or not a number in [{}, {}]", k, key, lo, hi);
      }
      *value = l[key].template get<double>();
    }
  }
  return "";
}

}  // namespace brdfit
