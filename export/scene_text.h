// Mitsuba 3 XML and pbrt-v4 scene text: a unit sphere with the exported material, one distant
// light, a camera; the file header states the provenance (export/provenance.h).
#pragma once

#include <string>
#include <vector>

#include "export/provenance.h"
#include "export/targets.h"

namespace brdfit::exports {

// <scene version="3.0.0"> with the material as <bsdf id="brdfit-material">.
std::string MitsubaScene(const MitsubaBlend& b, const Provenance& p);

// pbrt-v4 scene description; the render is written to image_name (an .exr next to the scene).
std::string PbrtScene(const PbrtMix& m, const Provenance& p, const std::string& image_name);

// Whether a pbrt-v4 string holds `s` as it is (printable ASCII but '"' and '\\'); the scenes
// write any other character as '_'.
bool PbrtStringHolds(const std::string& s);

// The same scenes with the material an RGL .bsdf file (named relative to the scene), read by
// Mitsuba's and pbrt-v4's `measured` material (pbrt-v4 reads spectral files only); `header`:
// the lines of the file's header comment. pbrt's string cannot hold '"', '\\' or control
// characters (they become '_'): the caller makes sure the name has none.
std::string MitsubaMeasuredScene(const std::string& bsdf_name,
                                 const std::vector<std::string>& header);
std::string PbrtMeasuredScene(const std::string& bsdf_name, const std::vector<std::string>& header,
                              const std::string& image_name);

}  // namespace brdfit::exports
