// The closest point of a triangle, shared inside the codec: the encoder's TriangleTree and the
// decoder's FaceGrid both answer their queries with it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace ellicast::detail {

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5:
// Voronoi regions of the triangle), and, when `bary` is given, its barycentric coordinates with
// respect to a, b, c. Degenerate (collinear or point) triangles give the closest point of their
// edges. V is any 3-vector with operator[] and default construction (std::array<double, 3>,
// OpenMesh::Vec3d).
template <class V>
inline V closest_point_on_triangle(const V& p, const V& a, const V& b, const V& c, std::array<double, 3>* bary = nullptr) {
    auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    // The point a + s (b - a) + t (c - a), barycentric (1 - s - t, s, t).
    auto at = [&](double s, double t) {
        if (bary) *bary = {1 - s - t, s, t};
        V out;
        for (int k = 0; k < 3; ++k) out[k] = a[k] + (b[k] - a[k]) * s + (c[k] - a[k]) * t;
        return out;
    };
    auto corner = [&](const V& q, std::array<double, 3> coords) {
        if (bary) *bary = coords;
        return q;
    };
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
        bp[k] = p[k] - b[k];
        cp[k] = p[k] - c[k];
    }
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return corner(a, {1, 0, 0});
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return corner(b, {0, 1, 0});
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double denom = d1 - d3;
        return denom > 0 ? at(d1 / denom, 0) : corner(a, {1, 0, 0});
    }
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return corner(c, {0, 0, 1});
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double denom = d2 - d6;
        return denom > 0 ? at(0, d2 / denom) : corner(a, {1, 0, 0});
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double denom = (d4 - d3) + (d5 - d6);
        if (!(denom > 0)) return corner(b, {0, 1, 0});
        const double w = (d4 - d3) / denom;
        return at(1 - w, w);
    }
    const double sum = va + vb + vc;
    if (!(sum > 0) || !std::isfinite(sum)) {
        // Degenerate (collinear) triangle: the closest point of its three edges.
        double best_d2 = INFINITY, best_s = 0, best_t = 0;
        auto segment = [&](double s0, double t0, double s1, double t1) {
            double q0[3], d[3];
            for (int k = 0; k < 3; ++k) {
                q0[k] = a[k] + ab[k] * s0 + ac[k] * t0;
                d[k] = (a[k] + ab[k] * s1 + ac[k] * t1) - q0[k];
            }
            const double len = dot(d, d);
            double pq[3] = {p[0] - q0[0], p[1] - q0[1], p[2] - q0[2]};
            const double u = len > 0 ? std::clamp(dot(pq, d) / len, 0.0, 1.0) : 0.0;
            double e[3] = {pq[0] - u * d[0], pq[1] - u * d[1], pq[2] - u * d[2]};
            const double d2 = dot(e, e);
            if (d2 < best_d2) best_d2 = d2, best_s = s0 + u * (s1 - s0), best_t = t0 + u * (t1 - t0);
        };
        segment(0, 0, 1, 0);  // a-b
        segment(1, 0, 0, 1);  // b-c
        segment(0, 1, 0, 0);  // c-a
        return at(best_s, best_t);
    }
    return at(vb / sum, vc / sum);
}

}  // namespace ellicast::detail
