// Internal to converters: skin weights between an asset's vertices and a stream's points (format
// 1.5, spec 21): the influence record of every point a sender sends, and the weights of every vertex
// a receiver writes.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/asset.h"
#include "ellicast/format.h"

#include <vector>

namespace ellicast::skin_weights {

// One record per point of `points` (an object's points in stream order, quantized in `object`'s
// frame): a point at an original vertex (within the quantization step) takes that vertex's
// weights; any other point (a surface sample) the blend of the corners of the triangle nearest to
// it by barycentric weights, its four largest kept (spec 21.4). A point whose weights all round to
// 0 gets the record of the nearest vertex with a weight.
std::vector<Influences> point_records(const Mesh& mesh, const VertexWeights& weights,
                                      const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                                      const ObjectInfo& object);

// The weights of every vertex of `decoded` (object `index` of `stream` as a receiver shows it):
// those of the held point with a record nearest to the vertex (spec 21.3). Empty when the stream
// holds no record of the object.
VertexWeights vertex_weights(const Mesh& decoded, const ReceivedStream& stream, size_t index);

// The weights of one record: joints, and the weights divided by 255 (unused slots 0).
void record_weights(const Influences& record, std::array<uint16_t, 4>& joints, std::array<float, 4>& weights);

// Whether every weight is a multiple of 1/255 in [0, 1] (as a stream's are, spec 21.2), so that
// normalized bytes hold them exactly; and those bytes.
bool in_255ths(const std::vector<std::array<float, 4>>& weights);
std::vector<std::array<uint8_t, 4>> as_bytes(const std::vector<std::array<float, 4>>& weights);

}  // namespace ellicast::skin_weights
