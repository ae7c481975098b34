// Mesh objects: the OBJ reader (triangulation, normals, validation with the file named), the
// placement, and the GPU path against the CPU reference (ray/triangle hits, interpolated
// normals) within the parity tolerance of the analytic sphere, 1e-3 relative per pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "preview/mesh.h"
#include "preview/reference_render.h"
#include "preview/renderer.h"
#include "tests/preview/gl_test_env.h"
#include "tests/preview/mesh_test_util.h"
#include "tests/preview/reference_compare.h"
#include "tests/scratch_dir.h"

namespace brdfit::preview {
namespace {

using testing::CompareToReference;
using testing::CubeObj;
using testing::ReferenceComparison;
using testing::UvSphereObj;

std::string ErrorOf(const std::string& obj_text) {
  try {
    ParseObj(obj_text, "shape.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshObj, CubeQuadsBecomeTrianglesWithAngleWeightedCornerNormals) {
  const Mesh m = ParseObj(CubeObj(), "cube.obj");
  EXPECT_EQ(m.NumTriangles(), 12u);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_TRUE(m.computed_normals);
  EXPECT_EQ(m.dropped_triangles, 0u);
  // Each corner sees three faces at 90 degrees whatever the triangulation: the normal is the
  // corner's diagonal.
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3 want = Normalize(m.positions[v]);
    EXPECT_NEAR(Dot(m.normals[v], want), 1.0, 1e-12) << "vertex " << v;
  }
  EXPECT_NEAR(m.bound_radius, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(Length(m.bound_centre), 0.0, 1e-12);
  // Counter-clockwise from outside: every face normal points away from the centre.
  for (std::size_t t = 0; t < m.NumTriangles(); ++t) {
    const Vec3& a = m.positions[m.indices[3 * t]];
    const Vec3 n =
        Cross(m.positions[m.indices[3 * t + 1]] - a, m.positions[m.indices[3 * t + 2]] - a);
    EXPECT_GT(Dot(n, a), 0.0) << "triangle " << t;
  }
}

TEST(MeshObj, FileNormalsAreKeptAndPoleTrianglesDropped) {
  const Mesh m = ParseObj(UvSphereObj(8, 12, 2.0, true), "uv.obj");
  EXPECT_FALSE(m.computed_normals);
  // Quads touching a pole have two coincident corners: depending on the diagonal the reader
  // splits them along, one of their triangles may have no area. Every other one is kept.
  EXPECT_GE(m.dropped_triangles, 12u);
  EXPECT_LE(m.dropped_triangles, 2u * 12u);
  EXPECT_EQ(m.NumTriangles() + m.dropped_triangles, 2u * 8u * 12u);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(Dot(m.normals[v], 0.5 * m.positions[v]), 1.0, 1e-12);
  }
}

TEST(MeshObj, PlacementMovesTheBoundingSphere) {
  const Mesh m = ParseObj(CubeObj(), "cube.obj");
  const Mesh fitted = PlaceMesh(m, {1, 2, 3}, 0.5, true);
  EXPECT_NEAR(fitted.bound_radius, 0.5, 1e-12);
  EXPECT_NEAR(Length(fitted.bound_centre - Vec3{1, 2, 3}), 0.0, 1e-12);
  const Mesh raw = PlaceMesh(m, {0, 1, 0}, 2.0, false);  // scale 2, then move
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(Length(raw.positions[v] - (Vec3{0, 1, 0} + 2.0 * m.positions[v])), 0.0, 1e-12);
  }
  for (std::size_t v = 0; v < m.normals.size(); ++v) {
    EXPECT_NEAR(Dot(raw.normals[v], m.normals[v]), 1.0, 1e-12);
  }
}

TEST(MeshObj, BadFilesAreNamedWithTheProblem) {
  EXPECT_NE(ErrorOf("").find("shape.obj: no triangle with a non-zero area"), std::string::npos)
      << ErrorOf("");
  EXPECT_NE(ErrorOf("v 0 0 0\nv 1 0 0\n").find("no triangle"), std::string::npos);
  EXPECT_NE(ErrorOf("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").find("no triangle"),
            std::string::npos);  // collinear
  const std::string out_of_range = ErrorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_NE(out_of_range.find("shape.obj"), std::string::npos) << out_of_range;
  EXPECT_FALSE(out_of_range.empty());
  const std::string bad_normal = ErrorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//7\n");
  EXPECT_FALSE(bad_normal.empty());
  const std::string huge = ErrorOf("v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_FALSE(huge.empty()) << "an overflowing coordinate must not become a vertex";
  // Finite but so large that squared distances overflow (fuzz/regressions/mesh).
  const std::string large = ErrorOf("v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(large.find("beyond 1e100"), std::string::npos) << large;
  // Lines tinyobjloader read leniently are refused with their line number.
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const auto& [obj, problem] : std::vector<std::pair<std::string, std::string>>{
           {"v a b c\n" + tri + "f 2 3 4\n", "line 1: 'v' value 'a' is not a finite number"},
           {tri + "f 1 2 99999999999999999999\n", "line 4: face corner '99999999999999999999'"},
           {tri + "f 1 2 0\n", "line 4: face corner '0'"},
           {tri + "f 1 2 3x\n", "line 4: face corner '3x'"},
           {tri + "vn nan 0 1\nf 1//1 2//1 3//1\n", "line 4: 'vn' value 'nan'"},
           {tri + "vn 0 0 0\nf 1//1 2//1 3//1\n", "line 4: 'vn 0 0 0' is not a direction"},
           {tri + "vn 0 1\n", "line 4: 'vn' takes 3 to 3 numbers, not 2"},
           {tri + "f 1 2\n", "line 4: a face needs at least 3 corners"},
           {"v inf 0 0\n" + tri, "line 1: 'v' value 'inf' is not a finite number"}}) {
    const std::string err = ErrorOf(obj);
    EXPECT_NE(err.find("shape.obj: " + problem), std::string::npos) << obj << "\n -> " << err;
  }
  // Valid forms still read: v/t/n corners, negative indices, CRLF lines, comments.
  const std::string ok =
      "# c\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\n"
      "f 1/1/1 2/1/1 -1/1/1\r\n";
  EXPECT_EQ(ParseObj(ok, "ok.obj").indices.size(), 3u);
  // Placement that overflows is refused too.
  EXPECT_THROW(PlaceMesh(ParseObj(CubeObj(), "cube.obj"), {0, 0, 0}, 1e300, false), InputError);
  try {
    LoadObj("/nonexistent/brdfit/mesh.obj");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/brdfit/mesh.obj"), std::string::npos);
  }
}

// ---- GPU against the CPU reference ------------------------------------------------------------

Scene MeshScene(const std::string& obj_text, bool normalize, MaterialSet* mats) {
  Scene s;
  s.camera.position = {0.5, 1.2, 4.0};
  s.width = s.height = 96;
  Light key;
  key.name = "key";
  key.direction = Normalize(Vec3{0.6, 0.5, 1.0});
  Light lamp;
  lamp.name = "lamp";
  lamp.type = LightType::kPoint;
  lamp.position = {-2, 1, 2};
  lamp.colour = {0.4, 0.5, 0.6};
  s.lights = {key, lamp};
  Object o;
  o.name = "mesh";
  o.shape = ObjectShape::kMesh;
  o.material = "m";
  o.mesh_normalize = normalize;
  o.mesh = std::make_shared<const Mesh>(
      PlaceMesh(ParseObj(obj_text, "mem.obj"), o.centre, 1.0, normalize));
  s.objects = {o};
  ResolvedMaterial m;
  m.name = "m";
  m.model = "lambert+ggx";
  m.params = {0.3, 0.2, 0.1, 0.8, 0.7, 0.6, 0.15};
  (*mats)["m"] = m;
  return s;
}

TEST(MeshRender, GpuMatchesCpuReferenceOnSmoothAndFlatMeshes) {
  BRDFIT_REQUIRE_GL();
  Renderer renderer;
  struct Case {
    const char* name;
    std::string obj;
  } cases[] = {{"uv sphere, file normals", UvSphereObj(24, 48, 1.0, true)},
               {"uv sphere, computed normals", UvSphereObj(16, 32, 1.0, false)},
               {"cube, corner normals", CubeObj()}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MaterialSet mats;
    const Scene scene = MeshScene(c.obj, true, &mats);
    ExplainLog log;
    const Image gpu = renderer.RenderLinear(scene, mats, &log);
    ReferenceExtras ex;
    const Image cpu = RenderReference(scene, mats, scene.width, scene.height, &ex);
    const ReferenceComparison r = CompareToReference(gpu, cpu, ex, 1e-6, true);
    std::printf("mesh parity %-28s max relative error %.3g over %ld pixels\n", c.name, r.max_rel,
                r.compared);
    EXPECT_GT(r.compared, 96 * 96 / 8);
    EXPECT_LE(r.max_rel, 1e-3);
    // Coverage: the same pixels are drawn (alpha) except along the silhouette.
    long differ = 0;
    for (int i = 0; i < gpu.width * gpu.height; ++i)
      differ += (gpu.rgba[4 * i + 3] > 0.5f) != (cpu.rgba[4 * i + 3] > 0.5f);
    EXPECT_LT(differ, 40) << "coverage differs on " << differ << " pixels";
  }
}

// A finely tessellated sphere mesh looks like the analytic sphere it approximates: the
// placement (bounding sphere -> centre, radius) and the normals' orientation are right.
TEST(MeshRender, TessellatedSphereLooksLikeTheAnalyticSphere) {
  BRDFIT_REQUIRE_GL();
  Renderer renderer;
  MaterialSet mats;
  Scene scene = MeshScene(UvSphereObj(48, 96, 7.0, true), true, &mats);  // normalized to r = 1
  const Image mesh = renderer.RenderLinear(scene, mats, nullptr);
  scene.objects[0].shape = ObjectShape::kSphere;
  scene.objects[0].mesh.reset();
  const Image sphere = renderer.RenderLinear(scene, mats, nullptr);
  ReferenceExtras ex;
  RenderReference(scene, mats, scene.width, scene.height, &ex);
  const ReferenceComparison r = CompareToReference(mesh, sphere, ex, 1e-6, true);
  std::printf("tessellated vs analytic sphere: max relative difference %.3g over %ld pixels\n",
              r.max_rel, r.compared);
  EXPECT_GT(r.compared, 96 * 96 / 4);
  EXPECT_LT(r.max_rel, 0.05);  // flat facets at 48 x 96 shift hit points by < 0.2 % of r
}

TEST(MeshRender, LightsOutOfReachOfTheBoundingSphereAreCulled) {
  BRDFIT_REQUIRE_GL();
  Renderer renderer;
  MaterialSet mats;
  Scene scene = MeshScene(CubeObj(), true, &mats);
  scene.lights[1].position = {0, 0, 10};
  scene.lights[1].distance = 5;  // reaches 5 units: the mesh's bounding sphere ends at z = 1
  ExplainLog log;
  renderer.RenderLinear(scene, mats, &log);
  const std::string text = log.Format();
  EXPECT_NE(text.find("skip: light 'lamp' for object 'mesh'"), std::string::npos) << text;
  EXPECT_NE(text.find("mesh"), std::string::npos);
  // The second frame reuses the vertex buffers.
  ExplainLog again;
  renderer.RenderLinear(scene, mats, &again);
  EXPECT_EQ(again.Format().find("vertex buffers"), std::string::npos) << again.Format();
}

TEST(MeshScene, LoadSceneLoadsEachFileOnceAndPlacesEveryObject) {
  const ScratchDir dir;
  {
    std::ofstream(dir / "cube.obj") << CubeObj();
    std::ofstream(dir / "scene.json") << R"({
      "materials": {"m": {"type": "analytic", "model": "lambert"}},
      "objects": [
        {"name": "a", "shape": "mesh", "file": "cube.obj", "material": "m"},
        {"name": "b", "shape": "mesh", "file": "cube.obj", "centre": [3, 0, 0], "radius": 0.5,
         "material": "m"},
        {"name": "c", "shape": "mesh", "file": "cube.obj", "normalize": false, "radius": 2,
         "material": "m"}]})";
  }
  ExplainLog log;
  const Scene s = LoadScene(dir / "scene.json", &log);
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_NEAR(s.objects[0].BoundRadius(), 1.0, 1e-12);
  EXPECT_NEAR(s.objects[1].BoundRadius(), 0.5, 1e-12);
  EXPECT_NEAR(Length(s.objects[1].BoundCentre() - Vec3{3, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(s.objects[2].BoundRadius(), 2 * std::sqrt(3.0), 1e-12);
  const std::string text = log.Format();
  EXPECT_EQ(text.find("load: mesh"), text.rfind("load: mesh")) << text;  // loaded once
  EXPECT_NE(text.find("12 triangles, 8 vertices, normals computed"), std::string::npos) << text;

  std::ofstream(dir / "scene.json") << R"({"materials": {"m": {"type": "analytic",
      "model": "lambert"}}, "objects": [{"shape": "mesh", "material": "m"}]})";
  try {
    LoadScene(dir / "scene.json");
    FAIL() << "a mesh without a file must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs 'file'"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "scene.json") << R"({"materials": {"m": {"type": "analytic",
      "model": "lambert"}}, "objects": [{"shape": "mesh", "file": "missing.obj",
      "material": "m"}]})";
  try {
    LoadScene(dir / "scene.json");
    FAIL() << "a missing mesh file must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.obj"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfit::preview
