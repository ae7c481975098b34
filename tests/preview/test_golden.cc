// Golden images: sphere set-ups of two shading tutorials (docs/models.md) rendered headless and
// compared with PNGs in data/golden/ (docs/preview.md, "Golden images").
//   ggx_{directional,point,spot}: mebiusbox 2018's Three.js sample (its
//     metallic/roughness material as the catalog's ue4 model, alpha = roughness^2) under each of
//     its three light types, with range, decay, cone and penumbra; the pi punctual convention.
//   urp_steps: the URP workshop 2025's spheres from Lambert to PBR (steps 3, 5, 6, 12, 13,
//     14, 15) under Unity's default directional light, the workshop's parameters, no pi factor.
//   mesh_torus: a triangle mesh (data/scenes/torus.obj, scripts/make_torus_obj.py) with
//     lambert+ggx under a directional and a point light.
// Origin: rendered by this renderer (Mesa llvmpipe, EGL surfaceless), inspected by eye, and
// cross-checked numerically by the parity tests (GPU vs the C++ models). Update after an
// intended change with BRDFIT_UPDATE_GOLDEN=1 (the test then writes the PNGs and passes).
// Tolerance: 8-bit channels may differ by at most 2 levels, except 0.1 % of the channel values
// (silhouette coverage, driver rounding); llvmpipe output is bit-identical run to run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "pipeline/material_loader.h"
#include "preview/renderer.h"
#include "preview/scene.h"
#include "tests/preview/gl_test_env.h"

namespace brdfit::preview {
namespace {

namespace fs = std::filesystem;

bool UpdateGolden() {
  const char* v = std::getenv("BRDFIT_UPDATE_GOLDEN");
  return v && std::string(v) == "1";
}

class Golden : public ::testing::TestWithParam<std::string> {};

TEST_P(Golden, MatchesStoredImage) {
  BRDFIT_REQUIRE_GL();
  const fs::path root = BRDFIT_SOURCE_DIR;
  const fs::path scene_path = root / "data" / "scenes" / (GetParam() + ".json");
  const fs::path golden = root / "data" / "golden" / (GetParam() + ".png");
  const Scene scene = LoadScene(scene_path);
  ExplainLog log;
  const MaterialSet mats = pipeline::LoadMaterials(scene, UsedMaterials(scene, false), {}, &log);
  Renderer renderer;
  const Image display = renderer.ToDisplay(renderer.RenderLinear(scene, mats, &log), scene);
  if (UpdateGolden()) {
    WritePng(golden, display);
    std::printf("updated %s\n", golden.c_str());
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden << " missing: run with BRDFIT_UPDATE_GOLDEN=1";
  const Image want = ReadPng(golden);
  ASSERT_EQ(want.width, display.width);
  ASSERT_EQ(want.height, display.height);
  long over = 0, total = 0;
  int max_levels = 0;
  for (int y = 0; y < want.height; ++y) {
    for (int x = 0; x < want.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const long got = std::lround(std::clamp(display.At(x, y)[c], 0.0f, 1.0f) * 255.0f);
        const long exp = std::lround(want.At(x, y)[c] * 255.0f);
        const int d = static_cast<int>(std::labs(got - exp));
        max_levels = std::max(max_levels, d);
        over += d > 2;
        ++total;
      }
    }
  }
  std::printf("%s: max difference %d levels, %ld of %ld channel values over 2 levels\n",
              GetParam().c_str(), max_levels, over, total);
  EXPECT_LE(over, total / 1000) << "more than 0.1 % of the channel values differ by > 2 levels";
}

INSTANTIATE_TEST_SUITE_P(Scenes, Golden,
                         ::testing::Values("ggx_directional", "ggx_point", "ggx_spot", "urp_steps",
                                           "mesh_torus"));

}  // namespace
}  // namespace brdfit::preview
