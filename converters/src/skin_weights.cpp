// Skin weights between an asset's vertices and a stream's points (format 1.5, spec 21).
#include "skin_weights.h"

#include "ellicast/codec/triangle_tree.h"

#include <algorithm>
#include <cmath>

namespace ellicast::skin_weights {

namespace {

Influences vertex_record(const VertexWeights& w, size_t v) {
    return quantize_influences(w.joints[v], w.weights[v]);
}

// Barycentric coordinates of `p` (on or near the triangle) in triangle (a, b, c), clamped to it.
std::array<double, 3> barycentric(const std::array<double, 3>& p, const std::array<float, 3>& a,
                                  const std::array<float, 3>& b, const std::array<float, 3>& c) {
    double v0[3], v1[3], v2[3];
    for (int k = 0; k < 3; ++k) v0[k] = double(b[k]) - a[k], v1[k] = double(c[k]) - a[k], v2[k] = p[k] - a[k];
    auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
    const double den = d00 * d11 - d01 * d01;
    if (!(std::abs(den) > 0)) return {1, 0, 0};
    double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    v = std::clamp(v, 0.0, 1.0);
    w = std::clamp(w, 0.0, 1.0 - v);
    return {1 - v - w, v, w};
}

double squared_distance(const std::array<double, 3>& p, const std::array<float, 3>& q) {
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (p[k] - q[k]) * (p[k] - q[k]);
    return d;
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
    // Triangles to search: the mesh's, or each vertex as a degenerate triangle for a point set.
    std::vector<std::array<uint32_t, 3>> triangles = mesh.triangles;
    if (mesh.is_point_set || triangles.empty()) {
        triangles.clear();
        for (uint32_t v = 0; v < mesh.positions.size(); ++v) triangles.push_back({v, v, v});
    }
    const TriangleTree tree(mesh.positions, triangles);
    // A vertex "is" the point when within the quantization step's diagonal.
    const double step = double(object.frame.scale) / double((uint32_t(1) << info.position_bits) - 1);
    const double snap = 3 * step * step;
    // The nearest vertex with a record, for points whose blend rounds to nothing.
    std::vector<Influences> vertex(mesh.positions.size());
    for (size_t v = 0; v < vertex.size(); ++v) vertex[v] = vertex_record(weights, v);
    for (size_t i = 0; i < points.size(); ++i) {
        const SurfacePoint sp = dequantize_point(points[i], info, object);
        const std::array<double, 3> p = {sp.position[0], sp.position[1], sp.position[2]};
        const ClosestPoint c = tree.closest_point(p);
        if (!c.found) continue;
        const auto& t = triangles[c.triangle];
        size_t nearest = 0;
        double best = squared_distance(p, mesh.positions[t[0]]);
        for (size_t k = 1; k < 3; ++k)
            if (double d = squared_distance(p, mesh.positions[t[k]]); d < best) best = d, nearest = k;
        Influences r;
        if (best <= snap) {
            r = vertex[t[nearest]];
        } else {
            const auto bary = barycentric(c.point, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
            std::array<uint16_t, 12> joints{};
            std::array<float, 12> blend{};
            for (size_t k = 0; k < 3; ++k)
                for (size_t s = 0; s < 4; ++s) {
                    joints[4 * k + s] = weights.joints[t[k]][s];
                    blend[4 * k + s] = float(bary[k] * weights.weights[t[k]][s]);
                }
            r = quantize_influences(joints, blend);
            if (r.count == 0) r = vertex[t[nearest]];
        }
        if (r.count == 0) {
            // No corner has a weight above 0: a record must have one; the first joint of the
            // nearest corner with all of it.
            r.count = 1;
            r.joints[0] = weights.joints[t[nearest]][0];
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
    // The held points with a record, as degenerate triangles (the tree finds the nearest).
    std::vector<std::array<float, 3>> positions;
    std::vector<const Influences*> records;
    for (const auto& [i, record] : object.weights) {
        auto p = object.points.find(i);
        if (p == object.points.end()) continue;
        positions.push_back(dequantize_point(p->second, *stream.info(), *object.info).position);
        records.push_back(&record);
    }
    if (positions.empty()) return out;
    std::vector<std::array<uint32_t, 3>> triangles(positions.size());
    for (uint32_t k = 0; k < triangles.size(); ++k) triangles[k] = {k, k, k};
    const TriangleTree tree(positions, triangles);
    out.joints.resize(decoded.positions.size());
    out.weights.resize(decoded.positions.size());
    for (size_t v = 0; v < decoded.positions.size(); ++v) {
        const auto& q = decoded.positions[v];
        const ClosestPoint c = tree.closest_point({q[0], q[1], q[2]});
        const Influences& r = *records[c.found ? c.triangle : 0];
        record_weights(r, out.joints[v], out.weights[v]);
    }
    return out;
}

}  // namespace ellicast::skin_weights
