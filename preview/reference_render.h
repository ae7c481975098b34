// CPU reference renderer in double precision: the same scene (spheres and meshes, Three.js lights,
// analytic or measured materials) evaluated with the C++ models and Table::LookupTrilinear.
// It is the oracle of the GPU path (GLSL <-> C++ parity) and of the light semantics. It shares
// no code with the shaders: rays, sphere and triangle hits, frames and lights are computed
// independently, in world space.
#pragma once

#include "core/image.h"
#include "preview/material.h"
#include "preview/scene.h"

namespace brdfit::preview {

// Linear radiance per pixel centre; alpha 1 where an object is hit. `edge` (optional) receives
// per pixel the smallest n.v and 1 if the pixel is within one pixel of a silhouette, for tests
// that exclude silhouettes. Factored materials use their CPU evaluator (and, like the GPU
// path, ignore spot lights).
struct ReferenceExtras {
  std::vector<double> cos_view;    // n . v at the pixel centre, 0 where nothing is hit
  std::vector<unsigned char> hit;  // 1 where the pixel-centre ray hits an object
};
Image RenderReference(const Scene& scene, const MaterialSet& materials, int width, int height,
                      ReferenceExtras* extras = nullptr);

}  // namespace brdfit::preview
