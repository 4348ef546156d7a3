// Per-point data between an asset's vertices and a stream's points (skin weights, morph targets).
#include "point_transfer.h"

#include "ellicast/codec/triangle_tree.h"

#include <algorithm>
#include <cmath>

namespace ellicast::point_transfer {

namespace {

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

std::vector<Source> sources(const Mesh& mesh, const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                            const ObjectInfo& object) {
    std::vector<Source> out(points.size());
    if (mesh.positions.empty()) return out;
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
    for (size_t i = 0; i < points.size(); ++i) {
        const SurfacePoint sp = dequantize_point(points[i], info, object);
        const std::array<double, 3> p = {sp.position[0], sp.position[1], sp.position[2]};
        const ClosestPoint c = tree.closest_point(p);
        if (!c.found) continue;
        Source& s = out[i];
        s.found = true;
        s.corners = triangles[c.triangle];
        size_t nearest = 0;
        double best = squared_distance(p, mesh.positions[s.corners[0]]);
        for (size_t k = 1; k < 3; ++k)
            if (double d = squared_distance(p, mesh.positions[s.corners[k]]); d < best) best = d, nearest = k;
        s.nearest = s.corners[nearest];
        s.snapped = best <= snap;
        s.bary = barycentric(c.point, mesh.positions[s.corners[0]], mesh.positions[s.corners[1]],
                             mesh.positions[s.corners[2]]);
    }
    return out;
}

std::vector<uint32_t> nearest_held(const Mesh& decoded, const std::vector<std::array<float, 3>>& held) {
    std::vector<uint32_t> out(decoded.positions.size(), 0);
    if (held.empty()) return out;
    // The held positions as degenerate triangles: the tree finds the nearest.
    std::vector<std::array<uint32_t, 3>> triangles(held.size());
    for (uint32_t k = 0; k < triangles.size(); ++k) triangles[k] = {k, k, k};
    const TriangleTree tree(held, triangles);
    for (size_t v = 0; v < decoded.positions.size(); ++v) {
        const auto& q = decoded.positions[v];
        const ClosestPoint c = tree.closest_point({q[0], q[1], q[2]});
        out[v] = c.found ? c.triangle : 0;
    }
    return out;
}

}  // namespace ellicast::point_transfer
