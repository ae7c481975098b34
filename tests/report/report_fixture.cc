#include "tests/report/report_fixture.h"

#include <cmath>

#include "core/model_params.h"
#include "core/synth.h"
#include "io/image_io.h"
#include "models/registry.h"
#include "pipeline/rendered_views.h"
#include "report/report_slices.h"

namespace brdfit::testing {

namespace fs = std::filesystem;
using report::Entry;

namespace {

Entry Fit(const std::string& model, const std::string& budget, double log_rmse, double ms,
          const std::vector<double>& params) {
  const ModelInfo* m = FindModel(model);
  Entry e;
  e.kind = Entry::Kind::kFit;
  e.name = model;
  e.loss = "log";
  e.budget = budget;
  e.status = "converged";
  e.param_names = m->param_names;
  e.params = params;
  e.at_bound.assign(params.size(), false);
  e.iterations = 12;
  e.metrics = Scored(log_rmse, 1.5 * log_rmse, 3 * log_rmse, 1000);
  e.times_ms = {{"prepare", 0.1 * ms}, {"init", 0.2 * ms}, {"solve", 0.7 * ms}};
  e.time_ms = ms;
  return e;
}

}  // namespace

report::Report MakeFixtureReport(const fs::path& dir) {
  report::Report r;
  r.title = "fixture report <with> \"markup\" & ampersands";
  r.metric_definition = "log_rmse etc. (fixture)";
  const ModelInfo* m = FindModel("lambert+ggx");
  const Grid grid{24, 24, 48, ThetaHMapping::kSqrt};
  const char* names[2] = {"plastic", "metal & co"};
  const double alphas[2] = {0.1, 0.3};
  for (int k = 0; k < 2; ++k) {
    const std::vector<double> truth =
        ResolveModelParams(*m, {"kd_r=0.4", "kd_g=0.2", "kd_b=0.1", "ks_r=0.05", "ks_g=0.05",
                                "ks_b=0.05", "alpha=" + std::to_string(alphas[k])});
    std::vector<double> off = truth;
    off.back() *= 1.6;  // alpha is the last parameter of lambert+ggx
    const Table table = SynthesizeTable(
        grid, [&](const Geometry& g, double rgb[3]) { m->eval(truth.data(), g, rgb); }, {});
    report::Material mat;
    mat.name = names[k];
    mat.source = std::string(names[k]) + ".h5";
    mat.entries.push_back(Fit("lambert+ggx", "full", 0.002 + k * 0.001, 900, truth));
    mat.entries.push_back(Fit("lambert+ggx", "stride:8", 0.004, 120, truth));
    mat.entries.push_back(Fit("lambert+ggx", "stride:32", 0.03, 40, off));
    Entry failed = Fit("lambert+beckmann", "full", 0, 50, FindModel("lambert+beckmann")->DefaultParams());
    failed.status = "failed";
    failed.message = "no samples";
    failed.metrics.ok = false;
    mat.entries.push_back(failed);
    Entry factor;
    factor.kind = Entry::Kind::kFactor;
    factor.name = "factor:mccool";
    factor.loss = "log (linear)";
    factor.budget = "res 32";
    factor.status = "converged";
    factor.metrics = Scored(0.02, 0.03, 0.2, 1000);
    factor.time_ms = 60;
    mat.entries.push_back(factor);
    mat.slices = report::ComputeThetaHSlices(
        table, report::DefaultSliceThetaD(), 90,
        {{"lambert+ggx", "fitted", report::ModelPredictor("lambert+ggx", truth)},
         {"lambert+ggx (stride:32)", "fitted", report::ModelPredictor("lambert+ggx", off)},
         {"factor:mccool", "factored", [&, off](const HalfDiffAngles& a) {
            std::array<double, 3> rgb{};
            m->eval(off.data(), MakeGeometry(a), rgb.data());
            for (double& v : rgb) v *= 1.1;
            return rgb;
          }}});
    // Renders of the best fit beside the first material; the second says why it has none.
    if (k == 0) {
      mat.views = pipeline::RenderMaterialViews(table, mat, {}, pipeline::DefaultViewLights());
    } else {
      mat.views.missing = "No renders: the fixture draws them for the first material only.";
    }
    r.materials.push_back(std::move(mat));
    for (const char* budget : {"full", "stride:4", "stride:16"}) {
      for (const char* model : {"lambert+ggx", "lambert+beckmann"}) {
        report::BenchPoint b;
        b.material = names[k];
        b.model = model;
        b.loss = "log";
        b.budget = budget;
        b.status = "converged";
        const double scale = std::string(budget) == "full" ? 1 : std::string(budget) == "stride:4" ? 0.3 : 0.1;
        b.time_ms = 1000 * scale * (model[8] == 'g' ? 1 : 2);
        b.metrics = Scored(0.01 / std::sqrt(scale) * (model[8] == 'g' ? 1 : 1.5), 0.02, 0.1, 1000);
        r.bench.push_back(b);
      }
    }
  }
  // A 64 x 48 gradient as the render.
  Image img(64, 48);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      float* p = img.At(x, y);
      p[0] = x / 63.0f;
      p[1] = y / 47.0f;
      p[2] = 0.5f;
      p[3] = 1;
    }
  }
  const fs::path png = dir / "render.png";
  WritePng(png, img);
  r.renders.push_back({"gradient render", png.string()});
  return r;
}

}  // namespace brdfit::testing
