// `brdfit render scene.json -o out.png|out.exr [--explain] [--size WxH] [--compare]`: the GLSL
// preview, headless (EGL surfaceless). Scene format: docs/scenes.md; renderer: docs/preview.md.
#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/command.h"
#include "cli/demo.h"
#include "cli/terminal_text.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/output_policy.h"
#include "pipeline/comparison_scene.h"
#include "pipeline/inputs.h"
#include "pipeline/material_loader.h"
#include "preview/comparison.h"
#include "preview/gl_context.h"
#include "preview/renderer.h"
#include "preview/scene.h"
#include "preview/window.h"

// LeakSanitizer (make test-asan): Mesa/LLVM and HDF5 keep process-lifetime allocations that
// are not ours to free. Suppressed by library name only.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libLLVM\nleak:libgallium\nleak:swrast_dri\nleak:libEGL_mesa\nleak:libglapi\n"
         "leak:libdrm\nleak:dri_\nleak:libhdf5_serial.so\n"
         // --window: X11, GLX and GLFW keep per-process state until exit.
         "leak:libX11\nleak:libGLX\nleak:libglfw\nleak:libxcb\n";
}

namespace brdfit::cli {
namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string scene;
  std::string out;
  std::string size;
  std::string cache;
  bool explain = false;
  bool compare = false;
  bool window = false;
  bool quiet = false;
  int frames = 0;
};

// --explain: one line per entry; names from the scene (materials, objects, lights, files) with
// control characters escaped.
void PrintExplain(const preview::ExplainLog& log) {
  for (const auto& e : log.entries()) {
    fmt::print("explain: {}: {}\n", e.category, TerminalSafe(e.message));
  }
}

void ParseSize(const std::string& s, int* w, int* h) {
  const auto x = s.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t a = 0, b = 0;
    *w = std::stoi(s.substr(0, x), &a);
    *h = std::stoi(s.substr(x + 1), &b);
    if (a != x || b != s.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw InputError("--size '" + s + "': expected WxH, e.g. 512x512");
  }
  if (*w < 1 || *h < 1 || *w > 8192 || *h > 8192) {
    throw InputError("--size '" + s + "': width and height must be in [1, 8192]");
  }
}

// The files a render reads: the scene (or the table) and what its materials and objects name.
std::vector<fs::path> SceneInputs(const std::string& input, bool table_input,
                                  const preview::Scene& scene) {
  std::vector<fs::path> in = table_input ? pipeline::InputFiles({input})
                                         : std::vector<fs::path>{input};
  for (const preview::MaterialSpec& m : scene.materials) {
    for (const fs::path& p : {m.fit_report, m.fit_table, m.table, m.factors}) {
      if (p.empty()) continue;
      for (const fs::path& f : pipeline::InputFiles({p.string()})) in.push_back(f);
    }
  }
  for (const auto& obj : scene.objects) {
    if (!obj.mesh_file.empty()) in.push_back(obj.mesh_file);
  }
  return in;
}

// --window: the interactive preview; with -o the last frame shown is also written.
int RunWindow(const RenderOptions& o, const preview::Scene& scene,
              const preview::MaterialSet& materials, preview::ExplainLog* log) {
  preview::WindowOptions wo;
  wo.compare = o.compare;
  wo.max_frames = o.frames;
  wo.capture_screen = !o.out.empty();
  const preview::WindowResult r = preview::RunPreviewWindow(scene, materials, wo, log);
  if (!o.out.empty() && r.renders > 0) {
    // A PNG holds what the window showed (read back from it); an EXR the linear frame.
    WriteImageByExtension(o.out, r.last_linear,
                          r.last_screen.width > 0 ? r.last_screen : r.last_display);
  }
  if (o.explain) PrintExplain(*log);
  if (!o.out.empty() && r.renders > 0 && !o.quiet) fmt::print("wrote {}\n", o.out);
  return kExitOk;
}

int RunRender(RenderOptions o) {
  using Clock = std::chrono::steady_clock;
  if (o.out.empty() && !o.window) {
    throw InputError("an output image is needed: -o out.png (or --window)");
  }
  preview::ExplainLog log;
  const bool table_input = pipeline::IsTableInput(o.scene);
  preview::Scene scene =
      table_input
          ? preview::ParseScene(pipeline::ComparisonScene(o.scene, false).dump(), "comparison.json")
          : preview::LoadScene(o.scene, &log);
  if (table_input) {
    log.Add("note", "input " + o.scene +
                        " is a table: its comparison scene (measured | "
                        "lambert+ggx fit | factored)");
    o.compare = true;
  }
  if (!o.size.empty()) ParseSize(o.size, &scene.width, &scene.height);
  CheckOutputs(SceneInputs(o.scene, table_input, scene), {{o.out, "-o"}});
  if (o.compare && !scene.has_comparison) {
    throw InputError(o.scene, "--compare needs a 'comparison' section (docs/scenes.md)");
  }
  pipeline::LoadOptions lo;
  lo.cache_dir = o.cache;
  const auto t0 = Clock::now();
  const preview::MaterialSet materials =
      pipeline::LoadMaterials(scene, preview::UsedMaterials(scene, o.compare), lo, &log);
  const auto t1 = Clock::now();
  if (o.window) return RunWindow(o, scene, materials, &log);
  preview::HeadlessGlContext context;
  log.Add("note", "OpenGL: " + context.Description());
  preview::Renderer renderer;
  Image linear, display;
  if (o.compare) {
    preview::ComparisonStats stats;
    display = preview::RenderComparison(renderer, scene, materials, scene.width, scene.height, &log,
                                        &stats);
    linear = display;  // an EXR of a comparison holds its display values
  } else {
    linear = renderer.RenderLinear(scene, materials, &log);
    display = renderer.ToDisplay(linear, scene);
  }
  const auto t2 = Clock::now();
  WriteImageByExtension(o.out, linear, display);
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  log.Add("note", fmt::format("materials {:.1f} ms, render {:.1f} ms ({}x{})", ms(t0, t1),
                              ms(t1, t2), scene.width, scene.height));
  if (o.explain) PrintExplain(log);
  if (!o.quiet) fmt::print("wrote {}\n", o.out);
  return kExitOk;
}

Registrar reg{
    "render", "Render a scene with the GLSL preview (headless, or in a window)", [](CLI::App& sub) {
      auto opts = std::make_shared<RenderOptions>();
      sub.add_option("scene", opts->scene,
                     "scene file (docs/scenes.md), or a table (.binary, .h5, nbrdf:NAME): its "
                     "comparison with a lambert+ggx fit and a factorization")
          ->required();
      sub.add_option("-o,--out", opts->out,
                     "output image: .png (display) or .exr (linear); required without --window");
      sub.add_flag("--explain", opts->explain,
                   "print what was loaded, computed, reused and skipped");
      sub.add_option("--size", opts->size, "image size WxH (overrides the scene)");
      sub.add_option("--cache", opts->cache,
                     "cache folder for computed fits and factorizations "
                     "(default $BRDFIT_CACHE_DIR or ~/.cache/brdfit)");
      sub.add_flag("--window", opts->window,
                   "show the preview in a window (needs a display): left-drag orbits, the wheel "
                   "zooms, R resets, Esc closes; with -o the last frame shown is written");
      sub.add_option("--frames", opts->frames,
                     "with --window: close after N frames (scripts, tests)")
          ->check(CLI::Range(0, std::numeric_limits<int>::max()));  // not a 300-digit bound
      sub.add_flag("--compare", opts->compare,
                   "measured | fitted | factored | error panels (scene 'comparison')");
      sub.add_flag("-q,--quiet", opts->quiet, "no 'wrote' line (--explain still prints)");
      sub.footer(
          "Exit codes: 0 written, 2 bad scene or input (also a fit the scene needs that fails).\n"
          "Examples:\n  brdfit render data/scenes/ggx_directional.json -o ggx.png\n"
          "  brdfit render scene.json -o cmp.png --compare --size 512x512 --explain\n"
          "  brdfit render nbrdf:gold-metallic-paint -o gold.png\n"
          "  brdfit render data/scenes/ggx_spot.json --window");
      return [opts] { return RunRender(*opts); };
    }};

// Demo step 40: a comparison of the first demo table against a fit and a factorization.
int DemoRender(DemoContext& ctx) {
  if (ctx.tables.empty()) {
    fmt::print("render: no demo table to compare (the synth step wrote none)\n");
    return kExitOk;
  }
  const nlohmann::json s = pipeline::ComparisonScene(ctx.tables.front().string(), ctx.quick);
  const auto scene_path = ctx.out_dir / "compare_scene.json";
  {
    std::ofstream out(scene_path);
    out << s.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  }
  RenderOptions o;
  o.scene = scene_path.string();
  o.out = (ctx.out_dir / "compare.png").string();
  o.cache = (ctx.out_dir / "cache").string();
  o.compare = true;
  o.size = ctx.quick ? "256x256" : "512x512";
  const int code = RunRender(o);
  ctx.outputs.push_back(scene_path);
  ctx.outputs.push_back(o.out);
  return code;
}

DemoStepRegistrar demo_step{40, "render comparison", DemoRender};

}  // namespace
}  // namespace brdfit::cli
