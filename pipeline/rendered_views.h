// The images of `brdfit report` beside each material: its best approximation (report::PickBest)
// rendered in the scene of the rendered-image metric (fit/rendered_error.h, docs/accuracy.md)
// against its table — measured sphere, approximation's sphere and relative luminance error map
// per light, as PNGs (tone mapping of the sRGB PSNR, colours of report/rendered_colors.h).
#pragma once

#include <vector>

#include "core/table.h"
#include "report/report_model.h"

namespace brdfit::pipeline {

// The side of the pictures, pixels: three times the metric's images (RenderedErrorOptions), so
// that a highlight a few of the metric's pixels wide is seen as a shape.
inline constexpr int kViewResolution = 192;

// The lights shown by default (degrees from the view direction; among the metric's lights).
std::vector<double> DefaultViewLights();

// Throws InputError if a light is not one of the metric's default lights (the images are those
// of the metric, whose tone mapping pools every light).
void CheckViewLights(const std::vector<double>& light_deg);

// The images of m's best approximation against `table` (m's measured table). Fits are
// evaluated through their registered model, factorizations through their sidecar (`factors`).
// What cannot be drawn gives MaterialViews::missing (the reason), never an exception, except
// InputError for an unreadable sidecar.
report::MaterialViews RenderMaterialViews(const Table& table, const report::Material& m,
                                          const std::vector<report::FactorRef>& factors,
                                          const std::vector<double>& light_deg);

}  // namespace brdfit::pipeline
