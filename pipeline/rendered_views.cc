#include "pipeline/rendered_views.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/image.h"
#include "core/luminance.h"
#include "fit/rendered_error.h"
#include "io/image_io.h"
#include "models/registry.h"
#include "pipeline/factor_export.h"
#include "report/rendered_colors.h"

namespace brdfit::pipeline {
namespace {

using report::Srgb;
using State = RenderedImage::State;

void Put(Image* img, std::size_t i, const Srgb& c) {
  float* p = &img->rgba[4 * i];
  for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(c[k]);
  p[3] = 1;
}

// A tone-mapped sphere: the sRGB PSNR's mapping (fit/rendered_error.h RenderedToneMap).
std::string SpherePng(const RenderedImage& r, const std::vector<double>& radiance,
                      double exposure) {
  Image img(r.resolution, r.resolution);
  for (std::size_t i = 0; i < r.state.size(); ++i) {
    switch (r.state[i]) {
      case State::kOff: Put(&img, i, report::kViewBackground); break;
      case State::kUnlit: Put(&img, i, report::kViewUnlit); break;
      case State::kMasked: Put(&img, i, report::kViewMasked); break;
      case State::kBelowFloor:
      case State::kCompared:
        Put(&img, i,
            {RenderedToneMap(radiance[3 * i], exposure), RenderedToneMap(radiance[3 * i + 1], exposure),
             RenderedToneMap(radiance[3 * i + 2], exposure)});
        break;
    }
  }
  return EncodePng(img);
}

// The relative luminance error map (fit/rendered_error.h RenderedImage::rel_error) with an
// absolute luminance floor: the metric's floor in its own image of the same light
// (RenderedErrorOptions::luminance_floor times that image's peak Y_m). A picture at another
// resolution samples a narrow peak higher, and its own relative floor would hide pixels the
// metric compares.
std::string ErrorPng(const RenderedImage& r, double floor_y) {
  Image img(r.resolution, r.resolution);
  for (std::size_t i = 0; i < r.state.size(); ++i) {
    switch (r.state[i]) {
      case State::kOff: Put(&img, i, report::kViewBackground); break;
      case State::kUnlit: Put(&img, i, report::kViewUnlit); break;
      case State::kMasked: Put(&img, i, report::kViewMasked); break;
      case State::kBelowFloor:
      case State::kCompared: {
        const double ym = Rec709Luminance(&r.measured[3 * i]);
        if (!(ym > floor_y)) {
          Put(&img, i, report::kViewBelowFloor);
          break;
        }
        const double ya = Rec709Luminance(&r.approx[3 * i]);
        Put(&img, i, report::ErrorColor((ya - ym) / ym));
        break;
      }
    }
  }
  return EncodePng(img);
}

// The peak measured luminance of a light's image over its lit, unmasked pixels.
double PeakMeasuredLuminance(const RenderedImage& r) {
  double peak = 0;
  for (std::size_t i = 0; i < r.state.size(); ++i) {
    if (r.state[i] == State::kCompared || r.state[i] == State::kBelowFloor) {
      peak = std::max(peak, Rec709Luminance(&r.measured[3 * i]));
    }
  }
  return peak;
}

}  // namespace

std::vector<double> DefaultViewLights() {
  return {45, 110, 152};
}

void CheckViewLights(const std::vector<double>& light_deg) {
  const std::vector<double> all = RenderedErrorOptions{}.light_angles_deg;
  std::string names;
  for (const double a : all) names += (names.empty() ? "" : ", ") + fmt::format("{}", a);
  if (light_deg.empty()) throw InputError("--render-lights needs at least one light");
  for (const double a : light_deg) {
    if (std::find(all.begin(), all.end(), a) == all.end()) {
      throw InputError(fmt::format(
          "--render-lights {}: not a light of the rendered-image metric ({} degrees)", a, names));
    }
  }
}

report::MaterialViews RenderMaterialViews(const Table& table, const report::Material& m,
                                          const std::vector<report::FactorRef>& factors,
                                          const std::vector<double>& light_deg) {
  CheckViewLights(light_deg);
  report::MaterialViews v;
  const report::BestPick best = report::PickBest(m.entries);
  if (best.index < 0) {
    v.missing = "No renders: no usable fit or factorization.";
    return v;
  }
  const report::Entry& e = m.entries[static_cast<std::size_t>(best.index)];
  v.entry_key = e.Key();
  BrdfFunction approx;
  std::shared_ptr<FactoredBrdf> factored;
  if (e.kind == report::Entry::Kind::kFit) {
    const ModelInfo* model = FindModel(e.Model());  // a numbered duplicate: its model
    if (!model || e.params.size() != model->param_names.size()) {
      v.missing = fmt::format("No renders: {} cannot be evaluated (unknown model or {} parameters).",
                              e.name, e.params.size());
      return v;
    }
    approx = ModelBrdf(*model, e.params);
  } else {
    const auto f = std::find_if(factors.begin(), factors.end(), [&](const report::FactorRef& r) {
      return r.material == m.name && r.label == e.name;
    });
    if (f == factors.end()) {
      v.missing = "No renders: the factorization's sidecar is not at hand.";
      return v;
    }
    factored = std::make_shared<FactoredBrdf>(LoadFactoredBrdf(f->sidecar));
    approx = [factored](const Vec3& wi, const Vec3& wo) { return factored->Eval(wi, wo); };
  }
  const RenderedErrorOptions options;  // the metric's scene, as every fit's stored metric
  const RenderedImages images = RenderImages(PrepareRenderedReference(table, options), approx);
  if (!images.metric.ok) {
    v.missing = "No renders: the rendered-image metric failed: " + images.metric.problem;
    return v;
  }
  // The pictures: the same scene and tone mapping (the metric's exposure, which pools every
  // light of the metric's images) at kViewResolution, for the shown lights only, so that a
  // highlight spans more than a few pixels. Their numbers are the metric's own images'.
  v.resolution = kViewResolution;
  v.metric_resolution = images.metric.resolution;
  v.exposure = images.metric.exposure;
  RenderedErrorOptions display = options;
  display.resolution = kViewResolution;
  display.light_angles_deg = light_deg;
  display.environment.samples = 0;
  const RenderedImages shown = RenderImages(PrepareRenderedReference(table, display), approx);
  if (shown.lights.size() != light_deg.size()) {
    v.missing = "No renders: the approximation is not finite at the renders' resolution.";
    return v;
  }
  for (std::size_t j = 0; j < light_deg.size(); ++j) {
    const double a = light_deg[j];
    const auto k = static_cast<std::size_t>(
        std::find(options.light_angles_deg.begin(), options.light_angles_deg.end(), a) -
        options.light_angles_deg.begin());
    const RenderedImage& img = shown.lights[j];
    report::RenderedView view;
    view.light_deg = a;
    view.measured_png = SpherePng(img, img.measured, v.exposure);
    view.approx_png = SpherePng(img, img.approx, v.exposure);
    view.error_png =
        ErrorPng(img, options.luminance_floor * PeakMeasuredLuminance(images.lights[k]));
    view.psnr_db = images.metric.lights[k].psnr_db;
    view.median_rel_error = images.metric.lights[k].median_rel_error;
    v.lights.push_back(std::move(view));
  }
  return v;
}

}  // namespace brdfit::pipeline
