// Mitsuba 3 XML and pbrt-v4 scene text: a unit sphere with the exported material, one distant
// light, a camera; the file header states the provenance (export/provenance.h).
#pragma once

#include <string>

#include "export/provenance.h"
#include "export/targets.h"

namespace brdfit::exports {

// <scene version="3.0.0"> with the material as <bsdf id="brdfit-material">.
std::string MitsubaScene(const MitsubaBlend& b, const Provenance& p);

// pbrt-v4 scene description; the render is written to image_name (an .exr next to the scene).
std::string PbrtScene(const PbrtMix& m, const Provenance& p, const std::string& image_name);

}  // namespace brdfit::exports
