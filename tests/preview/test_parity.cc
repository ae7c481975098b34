// GLSL <-> C++ parity: for every catalog model, a sphere under directional light rendered by
// the GPU twin matches the CPU reference (the C++ model in double, same camera, its own ray,
// hit and frame code) within 1e-3 relative per pixel. Silhouette pixels (n.v < 0.1 at the
// pixel centre) are excluded: there a pixel's coverage, not the BRDF, decides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "models/registry.h"
#include "preview/reference_render.h"
#include "preview/renderer.h"
#include "tests/preview/gl_test_env.h"
#include "tests/preview/reference_compare.h"

namespace brdfit::preview {
namespace {

constexpr double kTolerance = 1e-3;  // relative, per pixel and channel (issue acceptance)

Scene ParityScene(const std::string& model, const std::vector<double>& params, MaterialSet* mats) {
  Scene s;
  s.camera.position = {0.3, 0.4, 4.0};
  s.camera.target = {0, 0, 0};
  s.width = s.height = 96;
  Light key;
  key.name = "key";
  key.direction = Normalize(Vec3{0.6, 0.5, 1.0});
  key.colour = {1.0, 0.9, 0.8};
  Light rim;
  rim.name = "rim";
  rim.direction = Normalize(Vec3{-1.0, 0.2, 0.3});
  rim.colour = {0.3, 0.4, 0.5};
  s.lights = {key, rim};
  Object o;
  o.name = "sphere";
  o.material = "m";
  s.objects = {o};
  ResolvedMaterial m;
  m.name = "m";
  m.model = model;
  m.params = params;
  (*mats)["m"] = m;
  return s;
}

// Parameter sets: the defaults, and one with every parameter at 30 % of its range (log-scale
// parameters geometrically, kept above 0.02 so a lobe spans several pixels).
std::vector<std::vector<double>> ParamSets(const ModelInfo& m) {
  std::vector<double> mid;
  for (const auto& p : m.params) {
    if (p.log_scale) {
      mid.push_back(std::max(0.02, p.lower * std::pow(p.upper / p.lower, 0.3)));
    } else {
      mid.push_back(p.lower + 0.3 * (std::min(p.upper, 10.0) - p.lower));
    }
  }
  return {m.DefaultParams(), mid};
}

TEST(Parity, EveryModelGpuMatchesCpuReference) {
  BRDFIT_REQUIRE_GL();
  Renderer renderer;
  for (const ModelInfo& model : AllModels()) {
    int set = 0;
    for (const auto& params : ParamSets(model)) {
      SCOPED_TRACE(model.name + " parameter set " + std::to_string(set++));
      MaterialSet mats;
      const Scene scene = ParityScene(model.name, params, &mats);
      const Image gpu = renderer.RenderLinear(scene, mats, nullptr);
      ReferenceExtras ex;
      const Image cpu = RenderReference(scene, mats, scene.width, scene.height, &ex);
      // Values below 1e-6 of the image peak (float denormal range of a lobe's tail) are
      // compared against that floor.
      const testing::ReferenceComparison c = testing::CompareToReference(gpu, cpu, ex, 1e-6, false);
      EXPECT_GT(c.compared, scene.width * scene.height / 4);
      EXPECT_LE(c.max_rel, kTolerance);
      std::printf("parity %-20s set %d: max relative error %.3g over %ld pixels\n",
                  model.name.c_str(), set - 1, c.max_rel, c.compared);
    }
  }
}

}  // namespace
}  // namespace brdfit::preview
