// A reconstruction of a partial stream no larger than the object it stands for.
//
// Where few points have arrived, most of a reconstruction is the marching-cubes base at the
// decoder's grid: a 12-triangle cube came back as 60,000 triangles, the 2CylinderEngine's 1.8 MB at
// one cycle of 50% loss as a 73 MB glTF. This pass collapses the vertices that are not received
// points (the base's filler) by the quadric error until the mesh has at most `max_faces`
// triangles; every received point stays where it is, with its attributes.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <cstddef>
#include <vector>

namespace ellicast::detail {

// Returns the number of triangles removed (0 when the mesh already fits, or when it cannot be
// simplified safely: a triangle OpenMesh cannot take as a manifold face leaves it unchanged).
size_t simplify_filler(Mesh& mesh, const std::vector<SurfacePoint>& received, size_t max_faces);

}  // namespace ellicast::detail
