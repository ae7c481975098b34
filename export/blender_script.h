// The Blender 3.4 Python script of `brdfit export --format blender`: it builds the exported
// materials and brdfit's preview scene (a unit sphere, the camera at (0, 0, 4) with a 30 degree
// vertical field of view, one sun from (1, 1, 1) of irradiance 3, a black world, Cycles on the
// CPU, the Standard view transform) and renders it when asked (docs/exports.md, "Blender").
#pragma once

#include <string>

#include "export/provenance.h"
#include "export/targets.h"

namespace brdfit::exports {

// Run as `blender -b --factory-startup --python-exit-code 1 -P SCRIPT -- [--material
// exact|principled] [--render OUT.png] [--size N] [--samples N] [--seed N] [--threads N]
// [--save OUT.blend]`; without arguments it builds the scene (in the UI: `blender -P SCRIPT`).
std::string BlenderScript(const BlenderMaterial& m, const Provenance& p);

}  // namespace brdfit::exports
