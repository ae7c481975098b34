// Render time of the GLSL preview, headless (EGL surfaceless, Mesa llvmpipe): a 512x512 sphere
// per material kind and light set, a 4,096-triangle mesh, and the 512x512 four-panel comparison. Programs and textures
// are cached by the renderer, so the timed loop measures drawing + readback (+ the display
// pass), not shader compilation; the first render (with compilation) is reported separately.
#include <benchmark/benchmark.h>

#include <memory>

#include "core/synth.h"
#include "models/registry.h"
#include "preview/comparison.h"
#include "preview/gl_context.h"
#include "preview/renderer.h"

namespace brdfit::preview {
namespace {

HeadlessGlContext& Context() {
  static HeadlessGlContext ctx;
  return ctx;
}

std::shared_ptr<const Table> MerlSizedTable() {
  static std::shared_ptr<const Table> t = [] {
    const ModelInfo* m = FindModel("lambert+ggx");
    std::vector<double> p = m->DefaultParams();
    p.back() = 0.2;
    return std::make_shared<const Table>(SynthesizeTable(
        Grid::Merl(), [&](const Geometry& g, double rgb[3]) { m->eval(p.data(), g, rgb); }, {}));
  }();
  return t;
}

Scene BenchScene(int lights) {
  Scene s;
  s.width = s.height = 512;
  for (int i = 0; i < lights; ++i) {
    Light l;
    l.name = std::to_string(i);  // (not "l" + to_string: GCC 12 -Wrestrict false positive)
    l.name.insert(0, 1, 'l');
    l.type = i % 3 == 0 ? LightType::kDirectional : i % 3 == 1 ? LightType::kPoint : LightType::kSpot;
    l.direction = Normalize(Vec3{1.0 - i, 1, 1});
    l.position = {2.0 - i, 2, 3};
    l.angle = 0.5;
    l.penumbra = 0.3;
    s.lights.push_back(l);
  }
  Object o;
  o.material = "m";
  s.objects = {o};
  return s;
}

MaterialSet Analytic(const std::string& model) {
  ResolvedMaterial m;
  m.name = "m";
  m.model = model;
  m.params = FindModel(model)->DefaultParams();
  return {{"m", m}};
}

void RenderSphere(benchmark::State& state, MaterialSet mats, int lights) {
  Context();
  Renderer renderer;
  const Scene scene = BenchScene(lights);
  renderer.RenderLinear(scene, mats, nullptr);  // compile outside the timed loop
  for (auto _ : state) {
    Image img = renderer.ToDisplay(renderer.RenderLinear(scene, mats, nullptr), scene);
    benchmark::DoNotOptimize(img.rgba.data());
  }
}

void BM_Sphere512_LambertGgx_1Light(benchmark::State& s) { RenderSphere(s, Analytic("lambert+ggx"), 1); }
void BM_Sphere512_LambertGgx_3Lights(benchmark::State& s) { RenderSphere(s, Analytic("lambert+ggx"), 3); }
void BM_Sphere512_Ue4_3Lights(benchmark::State& s) { RenderSphere(s, Analytic("ue4"), 3); }
void BM_Sphere512_Measured_3Lights(benchmark::State& s) {
  ResolvedMaterial m;
  m.name = "m";
  m.kind = MaterialKind::kMeasured;
  m.table = MerlSizedTable();
  RenderSphere(s, {{"m", m}}, 3);
}

// The torus of data/scenes/torus.obj (4,096 triangles) as the scene's object, 3 lights: the
// mesh path (vertex buffers cached, Three.js-style vertex stage) against the analytic sphere.
void BM_Mesh512_Torus_LambertGgx_3Lights(benchmark::State& state) {
  Context();
  Renderer renderer;
  Scene scene = BenchScene(3);
  Object& o = scene.objects[0];
  o.shape = ObjectShape::kMesh;
  o.mesh_file = std::string(BRDFIT_SOURCE_DIR) + "/data/scenes/torus.obj";
  o.mesh = std::make_shared<const Mesh>(PlaceMesh(LoadObj(o.mesh_file), o.centre, 1.0, true));
  const MaterialSet mats = Analytic("lambert+ggx");
  renderer.RenderLinear(scene, mats, nullptr);  // compile and upload outside the timed loop
  for (auto _ : state) {
    Image img = renderer.ToDisplay(renderer.RenderLinear(scene, mats, nullptr), scene);
    benchmark::DoNotOptimize(img.rgba.data());
  }
}

// First render of a fresh renderer: shader generation + compilation + draw + readback.
void BM_Sphere512_FirstRender_WithCompile(benchmark::State& state) {
  Context();
  const Scene scene = BenchScene(3);
  const MaterialSet mats = Analytic("lambert+ggx");
  for (auto _ : state) {
    Renderer renderer;
    Image img = renderer.RenderLinear(scene, mats, nullptr);
    benchmark::DoNotOptimize(img.rgba.data());
  }
}

// The 512x512 comparison (measured | fit | error; the factored panel needs fit/ and is
// covered by tests): three panel renders, the error map and the labels.
void BM_Comparison512(benchmark::State& state) {
  Context();
  Renderer renderer;
  Scene scene = BenchScene(2);
  scene.has_comparison = true;
  scene.comparison.measured = "meas";
  scene.comparison.fitted = {"fit"};
  ResolvedMaterial meas;
  meas.name = "meas";
  meas.kind = MaterialKind::kMeasured;
  meas.table = MerlSizedTable();
  MaterialSet mats = Analytic("lambert+ggx");
  mats["fit"] = mats["m"];
  mats["meas"] = meas;
  for (auto _ : state) {
    Image img = RenderComparison(renderer, scene, mats, 512, 512, nullptr, nullptr);
    benchmark::DoNotOptimize(img.rgba.data());
  }
}

BENCHMARK(BM_Sphere512_LambertGgx_1Light)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_Sphere512_LambertGgx_3Lights)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_Sphere512_Ue4_3Lights)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_Sphere512_Measured_3Lights)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_Mesh512_Torus_LambertGgx_3Lights)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_Sphere512_FirstRender_WithCompile)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Comparison512)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
}  // namespace brdfit::preview

BENCHMARK_MAIN();
