// Skin weights between an asset's vertices and a stream's points (format 1.5, spec 21).
#include "skin_weights.h"

#include "point_transfer.h"

#include <algorithm>
#include <cmath>

namespace ellicast::skin_weights {

namespace {

Influences vertex_record(const VertexWeights& w, size_t v) {
    return quantize_influences(w.joints[v], w.weights[v]);
}

}  // namespace

void record_weights(const Influences& record, std::array<uint16_t, 4>& joints, std::array<float, 4>& weights) {
    joints = {0, 0, 0, 0};
    weights = {0, 0, 0, 0};
    for (size_t i = 0; i < record.count && i < 4; ++i) {
        joints[i] = record.joints[i];
        weights[i] = float(record.weights[i]) / 255.0f;
    }
}

std::vector<Influences> point_records(const Mesh& mesh, const VertexWeights& weights,
                                      const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                                      const ObjectInfo& object) {
    std::vector<Influences> out(points.size());
    if (weights.joints.size() != mesh.positions.size() || mesh.positions.empty()) return {};
    // The nearest vertex with a record, for points whose blend rounds to nothing.
    std::vector<Influences> vertex(mesh.positions.size());
    for (size_t v = 0; v < vertex.size(); ++v) vertex[v] = vertex_record(weights, v);
    const std::vector<point_transfer::Source> where = point_transfer::sources(mesh, points, info, object);
    for (size_t i = 0; i < points.size(); ++i) {
        const point_transfer::Source& s = where[i];
        if (!s.found) continue;
        Influences r;
        if (s.snapped) {
            r = vertex[s.nearest];
        } else {
            std::array<uint16_t, 12> joints{};
            std::array<float, 12> blend{};
            for (size_t k = 0; k < 3; ++k)
                for (size_t j = 0; j < 4; ++j) {
                    joints[4 * k + j] = weights.joints[s.corners[k]][j];
                    blend[4 * k + j] = float(s.bary[k] * weights.weights[s.corners[k]][j]);
                }
            r = quantize_influences(joints, blend);
            if (r.count == 0) r = vertex[s.nearest];
        }
        if (r.count == 0) {
            // No corner has a weight above 0: a record must have one; the first joint of the
            // nearest corner with all of it.
            r.count = 1;
            r.joints[0] = weights.joints[s.nearest][0];
            r.weights[0] = 255;
        }
        out[i] = r;
    }
    return out;
}

VertexWeights vertex_weights(const Mesh& decoded, const ReceivedStream& stream, size_t index) {
    VertexWeights out;
    if (index >= stream.objects().size() || !stream.info()) return out;
    const ReceivedObject& object = stream.objects()[index];
    if (!object.info || object.weights.empty() || decoded.positions.empty()) return out;
    const std::vector<const Influences*> per_vertex = point_transfer::nearest_records(decoded, stream, index, object.weights);
    if (per_vertex.empty()) return out;
    out.joints.resize(decoded.positions.size());
    out.weights.resize(decoded.positions.size());
    for (size_t v = 0; v < decoded.positions.size(); ++v) record_weights(*per_vertex[v], out.joints[v], out.weights[v]);
    return out;
}

bool in_255ths(const std::vector<std::array<float, 4>>& weights) {
    return std::all_of(weights.begin(), weights.end(), [](const std::array<float, 4>& v) {
        return std::all_of(v.begin(), v.end(), [](float x) {
            return x >= 0 && x <= 1 && std::abs(x * 255.0 - std::round(x * 255.0)) < 1e-3;
        });
    });
}

std::vector<std::array<uint8_t, 4>> as_bytes(const std::vector<std::array<float, 4>>& weights) {
    std::vector<std::array<uint8_t, 4>> out(weights.size());
    for (size_t i = 0; i < weights.size(); ++i)
        for (size_t k = 0; k < 4; ++k) out[i][k] = uint8_t(std::lround(std::clamp(weights[i][k], 0.0f, 1.0f) * 255.0));
    return out;
}

}  // namespace ellicast::skin_weights
