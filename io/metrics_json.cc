#include "io/metrics_json.h"

namespace brdfit {

nlohmann::ordered_json RenderedErrorJson(const RenderedError& e) {
  nlohmann::ordered_json j = {{"psnr_db", e.psnr_db},
                              {"psnr_srgb_db", e.psnr_srgb_db},
                              {"median_rel_error", e.median_rel_error},
                              {"p95_rel_error", e.p95_rel_error},
                              {"ok", e.ok}};
  if (!e.ok) j["problem"] = e.problem;
  return j;
}

}  // namespace brdfit
