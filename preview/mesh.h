// Placing a mesh (io/obj_mesh.h) in a preview scene by the object's centre and radius.
#pragma once

#include "io/obj_mesh.h"
#include "models/geometry.h"

namespace brdfit::preview {

// The mesh in world space. normalize: its bounding sphere becomes (centre, radius). Otherwise
// the file's coordinates are kept, scaled by `radius` and moved by `centre`. Throws
// InputError when the placed coordinates overflow.
Mesh PlaceMesh(const Mesh& mesh, const Vec3& centre, double radius, bool normalize);

}  // namespace brdfit::preview
