// Internal to converters: morph target displacements between an asset's vertices and a stream's
// points (format 1.6, spec 22).
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/asset.h"
#include "ellicast/format.h"

#include <vector>

namespace ellicast::morph_targets {

// The displacement records of every point of `points` (an object's points, quantized in `object`'s
// frame), one after the other: a point at an original vertex (within the quantization step) takes
// that vertex's displacements, any other point (a surface sample) the blend of the corners of the
// triangle nearest to it by barycentric weights (spec 22.5).
std::vector<float> point_values(const Mesh& mesh, const VertexMorph& morph, const std::vector<QuantizedPoint>& points,
                                const StreamInfo& info, const ObjectInfo& object);

// The displacements of every vertex of `decoded` (object `index` of `stream` as a receiver shows
// it): those of the held point with a record nearest to the vertex (spec 22.3). Empty when the
// stream holds no record of the object.
VertexMorph vertex_morph(const Mesh& decoded, const ReceivedStream& stream, size_t index);

}  // namespace ellicast::morph_targets
