// Extra surface samples for meshes whose triangles are large compared with what the decoder can
// rebuild from vertices alone (low-poly models, CAD-like boxes, flat polygons).
#pragma once

#include "ellicast/codec/mesh.h"

#include <cstddef>

namespace ellicast::detail {

struct SurfaceSampleOptions {
    double spacing = 0;         // longest edge allowed inside a face (model units); <= 0: no samples
    double crease_spacing = 0;  // longest edge allowed along a crease or a boundary (model units)
    double crease_degrees = 30; // angle between face normals above which a shared edge is a crease
    size_t max_samples = 0;     // the spacings grow until at most this many distinct samples are added
};

// The mesh's vertices followed by points on its surface: each triangle is split at the midpoint of
// its longest edge (relative to that edge's allowed length) until every edge is short enough, and
// every midpoint made becomes a vertex with attributes interpolated from its triangle's corners. A
// midpoint is computed from the two ends alone, so neighbouring triangles make bit-identical
// positions (at a seam, one position with each side's attributes). The triangles are unchanged:
// only positions and attributes grow. `added` receives the number of distinct samples (position
// and attributes) appended; the vertices appended are about twice as many, since each edge's
// midpoints come from both its faces, bit for bit.
Mesh with_surface_samples(const Mesh& mesh, const SurfaceSampleOptions& options, size_t& added);

}  // namespace ellicast::detail
