// Internal to converters: per-point data between an asset's vertices and a stream's points. A
// sender gives each point the data of the vertex it lies on, or a blend of the corners of the
// triangle it lies on; a receiver gives each vertex it writes the data of the nearest held point
// that has some. Skin weights (format 1.5, spec 21) and morph target displacements (format 1.6,
// spec 22) travel this way.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace ellicast::point_transfer {

// Where a point of the stream lies on the source mesh.
struct Source {
    bool found = false;
    std::array<uint32_t, 3> corners{};  // the nearest triangle's vertices (a point set: one vertex thrice)
    std::array<double, 3> bary{};       // barycentric coordinates of the point in it, clamped to it
    uint32_t nearest = 0;               // the corner nearest to the point
    bool snapped = false;               // the point is that corner (within the quantization step)
};

// One Source per point of `points` (an object's points, quantized in `object`'s frame), on `mesh`.
std::vector<Source> sources(const Mesh& mesh, const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                            const ObjectInfo& object);

// For each vertex of `decoded`, the index into `held` of the position nearest to it (the smaller
// index on a tie). `held` must not be empty.
std::vector<uint32_t> nearest_held(const Mesh& decoded, const std::vector<std::array<float, 3>>& held);

// For each vertex of `decoded`, the record (of `records`, by point index, of object `index` of
// `stream`, whose info has arrived) of the nearest held point that has one; empty when no held
// point has a record.
// A record is the first of its records.stride() elements.
template <class Record>
std::vector<const Record*> nearest_records(const Mesh& decoded, const ReceivedStream& stream, size_t index,
                                           const PagedRecords<Record>& records) {
    const ReceivedObject& object = stream.objects()[index];
    std::vector<std::array<float, 3>> positions;
    std::vector<const Record*> held;
    for (const auto& [i, record] : records) {
        std::optional<QuantizedPoint> p = object.points.find(i);
        if (!p) continue;
        positions.push_back(dequantize_point(*p, *stream.info(), *object.info).position);
        held.push_back(record);
    }
    std::vector<const Record*> out;
    if (held.empty()) return out;
    for (uint32_t n : nearest_held(decoded, positions)) out.push_back(held[n]);
    return out;
}

}  // namespace ellicast::point_transfer
