// Scene files: defaults, Three.js r8x light semantics, strict validation with messages that name
// the file and the problem.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "preview/lights.h"
#include "preview/scene.h"

namespace brdfit::preview {
namespace {

const char* kMinimal = R"({
  "materials": {"m": {"type": "analytic", "model": "lambert+ggx",
                      "params": {"ggx.alpha": 0.3, "lambert.kd_r": 0.8}}},
  "objects": [{"material": "m"}],
  "lights": [{"type": "directional", "direction": [0, 0, 2]},
             {"type": "spot", "position": [0, 0, 5], "target": [0, 0, 0], "angle_deg": 30,
              "penumbra": 0.5, "distance": 10, "decay": 2, "intensity": 3}]
})";

TEST(Scene, ParsesWithDefaults) {
  const Scene s = ParseScene(kMinimal, "mem.json");
  EXPECT_EQ(s.width, 512);
  EXPECT_TRUE(s.punctual_pi);
  ASSERT_EQ(s.materials.size(), 1u);
  const auto& p = s.materials[0].params;
  ASSERT_EQ(p.size(), 7u);
  EXPECT_DOUBLE_EQ(p[0], 0.8);  // lambert.kd_r
  EXPECT_DOUBLE_EQ(p[1], 0.5);  // default
  EXPECT_DOUBLE_EQ(p[6], 0.3);  // ggx.alpha
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_DOUBLE_EQ(s.lights[0].direction.z, 1.0);  // normalized
  EXPECT_NEAR(s.lights[1].angle, kPi / 6, 1e-15);
}

void ExpectError(const std::string& json, const std::string& fragment) {
  try {
    ParseScene(json, "bad.json");
    FAIL() << "expected InputError containing '" << fragment << "'";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

TEST(Scene, RejectsBadInput) {
  ExpectError("{", "invalid JSON");
  ExpectError(R"({"materials": {}, "objects": [{"material": "x"}]})", "unknown material 'x'");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "nope"}},
                  "objects": [{"material": "m"}]})", "unknown model 'nope'");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "ggx",
                  "params": {"alpha": 5}}}, "objects": [{"material": "m"}]})", "outside");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "ggx",
                  "params": {"beta": 5}}}, "objects": [{"material": "m"}]})", "no parameter 'beta'");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "ggx"}},
                  "objects": [{"material": "m", "radius": 1, "colour": 2}]})", "unknown key 'colour'");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "ggx"}},
                  "objects": [{"material": "m"}],
                  "lights": [{"type": "point", "position": [0,0,1], "decay": 2}]})",
              "needs 'distance'");
  ExpectError(R"({"materials": {"m": {"type": "analytic", "model": "ggx"}},
                  "objects": [{"material": "m"}],
                  "lights": [{"type": "area"}]})", "unknown light type 'area'");
}

// Every number of a scene is finite and inside its documented range (docs/scenes.md
// "Ranges"): a camera at 1e308 rendered an all-black image with exit 0. Each key is refused
// just outside its range, and accepted at its edge.
TEST(Scene, EveryNumberIsInItsDocumentedRange) {
  const auto scene = [](const std::string& camera, const std::string& object,
                        const std::string& light, const std::string& extra = "") {
    return R"({"materials": {"m": {"type": "analytic", "model": "ggx"}},
               "camera": {)" +
           camera + R"(},
               "objects": [{"material": "m")" +
           object + R"(}],
               "lights": [{"type": "point")" +
           (light.find("position") == std::string::npos ? R"(, "position": [0, 0, 5])" + light
                                                        : light) +
           "}]" + extra + "}";
  };
  ExpectError(scene(R"("position": [0, 0, 1e308])", "", ""), "'position' must be within 1e+06");
  ExpectError(scene(R"("position": [0, -1e7, 4])", "", ""), "'position' must be within");
  ExpectError(scene(R"("target": [1e300, 0, 0])", "", ""), "'target' must be within");
  ExpectError(scene(R"("near": 1e-300)", "", ""), "'near' must be >= 1e-06");
  ExpectError(scene(R"("far": 1e300)", "", ""), "'far' must be <= 4e+06");
  ExpectError(scene("", R"(, "centre": [0, 1e308, 0])", ""), "'centre' must be within");
  ExpectError(scene("", R"(, "radius": 1e300)", ""), "'radius' must be <= 1e+06");
  ExpectError(scene("", R"(, "radius": 1e-300)", ""), "'radius' must be >= 1e-06");
  ExpectError(scene("", "", R"(, "intensity": 1e300)"), "'intensity' must be <= 1e+06");
  ExpectError(scene("", "", R"(, "color": [1e300, 1, 1])"), "'color' must be <= 1e+06");
  ExpectError(scene("", "", R"(, "position": [0, 0, -1e9])"), "'position' must be within");
  ExpectError(scene("", "", R"(, "distance": 10, "decay": 1e300)"), "'decay' must be <= 1000");
  ExpectError(scene("", "", "", R"(, "display": {"exposure": 1e-300})"), "'exposure' must be >=");
  ExpectError(scene("", "", "", R"(, "image": {"background": [1e300, 0, 0]})"),
              "'background' must be <= 1e+06");
  // A direction is any finite non-zero vector: a huge one is still a direction.
  const Scene huge = ParseScene(
      R"({"materials": {"m": {"type": "analytic", "model": "ggx"}}, "objects": [{"material": "m"}],
          "lights": [{"type": "directional", "direction": [1e154, 1e154, 1e154]}]})",
      "huge.json");
  EXPECT_NEAR(huge.lights[0].direction.z, 1 / std::sqrt(3.0), 1e-15);
  // In range but nothing to see: every object beyond the far plane.
  ExpectError(scene(R"("position": [0, 0, 500], "far": 100)", "", ""),
              "every object lies beyond the camera's 'far'");
  // The edges are accepted.
  const Scene s =
      ParseScene(scene(R"("position": [0, 0, 1e6], "far": 4e6, "near": 1e-6)",
                       R"(, "centre": [0, 0, -1e6], "radius": 1e6)", R"(, "intensity": 1e6)"),
                 "edge.json");
  EXPECT_EQ(s.camera.position.z, 1e6);
  EXPECT_EQ(s.objects[0].radius, 1e6);
}

// Three.js r8x's falloff: colour * intensity * (1 - d / distance)^decay, zero outside the range;
// the spot's smoothstep between cos(angle) and cos(angle (1 - penumbra)).
// A factored material computed from a table takes its form (rank, diffuse value).
TEST(Scene, FactoredMaterialTakesRankAndDiffuse) {
  const Scene s = ParseScene(R"({"materials": {"f": {"type": "factored", "table": "t.binary",
                                 "rank": 3, "diffuse": true}},
                                 "objects": [{"material": "f"}]})",
                             "mem.json");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].factor_rank, 3);
  EXPECT_TRUE(s.materials[0].factor_diffuse);
  const Scene d = ParseScene(R"({"materials": {"f": {"type": "factored", "table": "t.binary"}},
                                 "objects": [{"material": "f"}]})",
                             "mem.json");
  EXPECT_EQ(d.materials[0].factor_rank, 1);
  EXPECT_FALSE(d.materials[0].factor_diffuse);
  const Scene a = ParseScene(R"({"materials": {"f": {"type": "factored", "table": "t.binary",
                                 "form": "auto"}},
                                 "objects": [{"material": "f"}]})",
                             "mem.json");
  EXPECT_TRUE(a.materials[0].factor_auto);
  EXPECT_FALSE(d.materials[0].factor_auto);
  ExpectError(R"({"materials": {"f": {"type": "factored", "table": "t.binary", "form": "best"}},
                  "objects": [{"material": "f"}]})",
              "'form' must be \"auto\"");
  ExpectError(R"({"materials": {"f": {"type": "factored", "table": "t.binary", "form": "auto",
                  "rank": 2}}, "objects": [{"material": "f"}]})",
              "leave them out");
  ExpectError(R"({"materials": {"f": {"type": "factored", "factors": "f.factor.json",
                  "form": "auto"}}, "objects": [{"material": "f"}]})",
              "'factors' is already one");
  ExpectError(R"({"materials": {"f": {"type": "factored", "table": "t.binary", "rank": 5}},
                  "objects": [{"material": "f"}]})",
              "'rank' must be in [1, 4]");
  ExpectError(R"({"materials": {"f": {"type": "factored", "table": "t.binary", "diffuse": 1}},
                  "objects": [{"material": "f"}]})",
              "'diffuse' must be true or false");
}

TEST(Lights, SeedSemantics) {
  Light point;
  point.type = LightType::kPoint;
  point.position = {0, 0, 4};
  point.distance = 8;
  point.decay = 2;
  point.intensity = 2;
  Incident in = IncidentAt(point, {0, 0, 0});
  EXPECT_TRUE(in.visible);
  EXPECT_DOUBLE_EQ(in.colour.x, 2 * 0.25);  // (1 - 4/8)^2
  EXPECT_FALSE(IncidentAt(point, {0, 0, -4.5}).visible);  // d = 8.5 > distance

  Light spot;
  spot.type = LightType::kSpot;
  spot.position = {0, 0, 1};
  spot.target = {0, 0, 0};
  spot.angle = kPi / 4;
  spot.penumbra = 0.5;
  // On the axis: full intensity; just inside the cone edge: smoothstep near 0; outside: none.
  EXPECT_DOUBLE_EQ(IncidentAt(spot, {0, 0, 0}).colour.x, 1.0);
  const double edge = std::tan(kPi / 4 - 1e-3);
  const Incident e = IncidentAt(spot, {edge, 0, 0});
  EXPECT_TRUE(e.visible);
  EXPECT_LT(e.colour.x, 1e-4);
  EXPECT_FALSE(IncidentAt(spot, {1.1, 0, 0}).visible);
  // Halfway in cosine between the two edges: smoothstep(0.5) = 0.5.
  const double c0 = std::cos(kPi / 4), c1 = std::cos(kPi / 8), cm = 0.5 * (c0 + c1);
  EXPECT_NEAR(IncidentAt(spot, {std::tan(std::acos(cm)), 0, 0}).colour.x, 0.5, 1e-12);
}

TEST(Lights, CullingBySphereBounds) {
  Light point;
  point.type = LightType::kPoint;
  point.position = {0, 0, 10};
  point.distance = 5;
  std::string why;
  EXPECT_FALSE(LightReachesSphere(point, {0, 0, 0}, 1.0, &why));
  EXPECT_NE(why.find("out of range"), std::string::npos);
  EXPECT_TRUE(LightReachesSphere(point, {0, 0, 0}, 5.5, &why));
  Light spot;
  spot.type = LightType::kSpot;
  spot.position = {0, 0, 10};
  spot.target = {0, 0, 0};
  spot.angle = 10 * kPi / 180;
  EXPECT_TRUE(LightReachesSphere(spot, {0, 0, 0}, 1.0, &why));
  EXPECT_FALSE(LightReachesSphere(spot, {5, 0, 0}, 1.0, &why));  // 26.6 deg off axis
  EXPECT_NE(why.find("outside the cone"), std::string::npos);
}

}  // namespace
}  // namespace brdfit::preview
