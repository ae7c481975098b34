#include "io/metrics_json.h"

#include "core/model_choice.h"
#include "core/rendered_regions.h"

namespace brdfit {

nlohmann::ordered_json RenderedErrorJson(const RenderedError& e) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const RenderedSummaryField& f : kRenderedSummary) {
    if (f.NotComputed(e)) continue;
    j[f.name] = e.*f.value;
  }
  j["ok"] = e.ok;
  if (!e.ok) {
    j["problem"] = e.problem;
    return j;
  }
  j["score_db"] = RenderedScoreDb(e);
  j["regions"] = RenderedRegionsJson(e);
  nlohmann::ordered_json lights = nlohmann::ordered_json::array();
  for (int k = 0; k < e.num_lights && k < kRenderedMaxLights; ++k) {
    const RenderedLightError& l = e.lights[static_cast<std::size_t>(k)];
    lights.push_back({{"light_deg", l.light_deg},
                      {"psnr_db", l.psnr_db},
                      {"median_rel_error", l.median_rel_error}});
  }
  j["lights"] = lights;
  return j;
}

nlohmann::ordered_json RenderedRegionsJson(const RenderedError& e) {
  nlohmann::ordered_json regions = nlohmann::ordered_json::object();
  const auto by_region = RenderedRegions(e);
  for (int r = 0; r < kLightRegions; ++r) {
    const RegionError& g = by_region[static_cast<std::size_t>(r)];
    if (g.lights == 0) continue;
    regions[RegionName(static_cast<LightRegion>(r))] = {{"lights", g.lights},
                                                        {"psnr_db", g.psnr_db},
                                                        {"median_rel_error", g.median_rel_error},
                                                        {"score_db", g.score_db}};
  }
  return regions;
}

}  // namespace brdfit
