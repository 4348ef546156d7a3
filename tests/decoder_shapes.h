// Analytic test shapes for the decoder tests: spheres as ellipsoids plus points sampled on them,
// and whole streams made from them through the real format library.
#pragma once

#include "ellicast/codec/decoder.h"
#include "ellicast/format.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace ellicast::test {

inline Ellipsoid sphere_ellipsoid(std::array<float, 3> c, float r) {
    Ellipsoid e;
    e.center = c;
    e.radii = {r, r, r};
    return e;
}

// n points spread evenly over a sphere (Fibonacci lattice), with outward normals.
inline std::vector<SurfacePoint> fibonacci_sphere(size_t n, double radius, std::array<double, 3> c = {0, 0, 0}) {
    std::vector<SurfacePoint> points(n);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (size_t i = 0; i < n; ++i) {
        double y = 1 - 2 * (i + 0.5) / n;
        double r = std::sqrt(1 - y * y);
        double t = golden * i;
        double d[3] = {std::cos(t) * r, y, std::sin(t) * r};
        for (int k = 0; k < 3; ++k) {
            points[i].position[k] = float(c[k] + radius * d[k]);
            points[i].normal[k] = float(d[k]);
        }
    }
    return points;
}

// A latitude/longitude sphere whose points on the meridian u = 0 are sent twice: once with u = 0
// and once with u = 1 (a texture seam, as glTF splits it). Poles are single points.
inline std::vector<SurfacePoint> seamed_uv_sphere(int rings, int segments, double radius) {
    std::vector<SurfacePoint> points;
    auto add = [&](double theta, double phi, float u, float v) {
        SurfacePoint p;
        double d[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
        for (int k = 0; k < 3; ++k) p.position[k] = float(radius * d[k]), p.normal[k] = float(d[k]);
        p.texcoord = {u, v};
        points.push_back(p);
    };
    add(0, 0, 0.5f, 0);
    for (int i = 1; i < rings; ++i) {
        double theta = M_PI * i / rings;
        for (int j = 0; j < segments; ++j) {
            double phi = 2 * M_PI * j / segments;
            add(theta, phi, float(j) / segments, float(i) / rings);
            if (j == 0) add(theta, phi, 1.0f, float(i) / rings);
        }
    }
    add(M_PI, 0, 0.5f, 1);
    return points;
}

inline ObjectInfo object_info(std::array<float, 3> origin, float scale, size_t ellipsoids, size_t points,
                              uint8_t attributes) {
    ObjectInfo info;
    info.frame.origin = origin;
    info.frame.scale = scale;
    info.ellipsoid_count = uint32_t(ellipsoids);
    info.point_count = uint32_t(points);
    info.attributes = attributes;
    return info;
}

// Every packet of a one-object stream carrying `ellipsoids` and `points`.
inline StreamPackets make_stream(const ObjectInfo& object, const std::vector<Ellipsoid>& ellipsoids,
                                 const std::vector<SurfacePoint>& points, StreamInfo& info) {
    info = StreamInfo{};
    info.objects = {object};
    info.objects[0].ellipsoid_count = uint32_t(ellipsoids.size());
    info.objects[0].point_count = uint32_t(points.size());
    ObjectContent content;
    for (const auto& e : ellipsoids) content.ellipsoids.push_back(quantize_ellipsoid(e, object.frame));
    for (const auto& p : points) content.points.push_back(quantize_point(p, info, info.objects[0]));
    StreamPackets packets;
    REQUIRE(packetize_stream(info, {content}, 7, packets) == Error::Ok);
    return packets;
}

// Edges used by other than exactly two triangles (0 for a closed 2-manifold), by position.
inline size_t open_or_nonmanifold_edges(const Mesh& mesh) {
    // Vertices split by attributes share a position: weld by position first.
    std::map<std::array<float, 3>, uint32_t> weld;
    std::vector<uint32_t> id(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        id[i] = weld.emplace(mesh.positions[i], uint32_t(weld.size())).first->second;
    std::map<std::pair<uint32_t, uint32_t>, int> use;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = id[t[k]], b = id[t[(k + 1) % 3]];
            ++use[{std::min(a, b), std::max(a, b)}];
        }
    size_t bad = 0;
    for (const auto& [edge, n] : use) bad += n != 2 ? 1 : 0;
    return bad;
}

inline double signed_volume(const Mesh& mesh) {
    double v = 0;
    for (const auto& t : mesh.triangles) {
        const auto &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        v += (double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
              double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
              double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0])) / 6.0;
    }
    return v;
}

}  // namespace ellicast::test
