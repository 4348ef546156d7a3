// Procedural shapes shared by the tests and the benchmarks (header only, codec's Mesh type).
#pragma once

#include "ellicast/codec/mesh.h"

#include <array>
#include <cmath>
#include <cstdint>

namespace ellicast::samples {

// A closed latitude/longitude ellipsoid with `rings` rings of 2 * rings vertices between its poles
// (on the z axis), outward faces, no attributes.
inline Mesh uv_ellipsoid(int rings, std::array<double, 3> center, std::array<double, 3> radii) {
    Mesh m;
    const int n = rings;
    auto at = [&](double x, double y, double z) {
        return std::array<float, 3>{float(center[0] + radii[0] * x), float(center[1] + radii[1] * y),
                                    float(center[2] + radii[2] * z)};
    };
    m.positions.push_back(at(0, 0, 1));
    for (int i = 1; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            double th = M_PI * i / n, ph = M_PI * j / n;
            m.positions.push_back(at(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    m.positions.push_back(at(0, 0, -1));
    auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * 2 * n + (j % (2 * n))); };
    for (int j = 0; j < 2 * n; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i < n - 1; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
    const uint32_t south = uint32_t(m.positions.size() - 1);
    for (int j = 0; j < 2 * n; ++j) m.triangles.push_back({ring(n - 1, j + 1), ring(n - 1, j), south});
    return m;
}

// An axis-aligned box centred on the origin as glTF has it: four vertices per face, each with that
// face's normal (24 vertices, 12 triangles), faces counter-clockwise seen from outside; normals
// point inwards when `inward` (an asset whose normals disagree with its winding).
inline Mesh box(std::array<float, 3> size, bool inward = false) {
    Mesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const float s = side ? 1.0f : -1.0f;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const uint32_t first = uint32_t(m.positions.size());
            for (int k = 0; k < 4; ++k) {
                std::array<float, 3> p{};
                p[axis] = s * size[axis] / 2;
                p[u] = ((k == 1 || k == 2) ? 1 : -1) * size[u] / 2;
                p[v] = (k >= 2 ? 1 : -1) * size[v] / 2;
                m.positions.push_back(p);
                std::array<float, 3> n{};
                n[axis] = inward ? -s : s;
                m.normals.push_back(n);
            }
            if (side) {
                m.triangles.push_back({first, first + 1, first + 2});
                m.triangles.push_back({first, first + 2, first + 3});
            } else {
                m.triangles.push_back({first, first + 2, first + 1});
                m.triangles.push_back({first, first + 3, first + 2});
            }
        }
    return m;
}

}  // namespace ellicast::samples
