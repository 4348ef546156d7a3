// Tangents for normal-mapped output (glTF TANGENT: xyz a unit vector perpendicular to the normal,
// w = +1 or -1 the handedness of the bitangent cross(normal, tangent) * w).
//
// A reconstruction is a new triangulation, so tangents the source asset carried (or a baker
// computed) cannot be reused: they are built on the mesh as written, the way glTF asks a client to
// (MikkTSpace's construction, without its splitting of vertices, which welded output does not
// need): per triangle, the directions of increasing u and of the image's "up" (decreasing glTF v,
// whose origin is the image's top left) from the texture coordinates; per corner, those projected
// onto the plane of the corner's normal and weighted by the corner's angle; per vertex, the sum
// normalized, and w from the sign of the summed handedness.
#include "tangents.h"

#include <algorithm>
#include <cmath>

namespace ellicast::gltf_write {

namespace {

using V = std::array<double, 3>;
V sub(const V& a, const V& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(const V& a, const V& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
V scaled(const V& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
V of(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }
double norm(const V& a) { return std::sqrt(dot(a, a)); }

// `t` without its component along unit `n`, normalized; zero when nothing is left.
V tangential(const V& t, const V& n) {
    const V p = sub(t, scaled(n, dot(n, t)));
    const double len = norm(p);
    return len > 1e-20 && std::isfinite(len) ? scaled(p, 1.0 / len) : V{0, 0, 0};
}

// Any unit vector perpendicular to unit `n`.
V perpendicular(const V& n) {
    const V axis = std::abs(n[0]) < 0.9 ? V{1, 0, 0} : V{0, 1, 0};
    return tangential(axis, n);
}

}  // namespace

std::vector<std::array<float, 4>> mesh_tangents(const Mesh& mesh) {
    const size_t n = mesh.positions.size();
    std::vector<std::array<float, 4>> out(n, {1, 0, 0, 1});
    if (!mesh.has_normals() || !mesh.has_texcoords()) return out;
    std::vector<V> normal(n), sum(n, V{0, 0, 0});
    std::vector<double> handed(n, 0);
    for (size_t i = 0; i < n; ++i) {
        const V v = of(mesh.normals[i]);
        const double len = norm(v);
        normal[i] = len > 0 && std::isfinite(len) ? scaled(v, 1.0 / len) : V{0, 0, 1};
    }
    for (const auto& t : mesh.triangles) {
        if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
        const V p[3] = {of(mesh.positions[t[0]]), of(mesh.positions[t[1]]), of(mesh.positions[t[2]])};
        // (u, up) with up = -v: the image's axes.
        const double u[3] = {mesh.texcoords[t[0]][0], mesh.texcoords[t[1]][0], mesh.texcoords[t[2]][0]};
        const double w[3] = {-double(mesh.texcoords[t[0]][1]), -double(mesh.texcoords[t[1]][1]), -double(mesh.texcoords[t[2]][1])};
        const V e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]);
        const double du1 = u[1] - u[0], dw1 = w[1] - w[0], du2 = u[2] - u[0], dw2 = w[2] - w[0];
        const double det = du1 * dw2 - du2 * dw1;
        if (!(std::abs(det) > 1e-30) || !std::isfinite(det)) continue;  // no texture mapping to follow
        const V tu = scaled(sub(scaled(e1, dw2), scaled(e2, dw1)), 1.0 / det);  // dP/du
        const V tw = scaled(sub(scaled(e2, du1), scaled(e1, du2)), 1.0 / det);  // dP/dup
        for (int c = 0; c < 3; ++c) {
            const V a = sub(p[(c + 1) % 3], p[c]), b = sub(p[(c + 2) % 3], p[c]);
            const double la = norm(a), lb = norm(b);
            if (!(la > 0) || !(lb > 0)) continue;
            const double angle = std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
            const uint32_t v = t[c];
            const V dir = tangential(tu, normal[v]);
            for (int k = 0; k < 3; ++k) sum[v][k] += angle * dir[k];
            handed[v] += angle * (dot(cross(normal[v], dir), tw) < 0 ? -1.0 : 1.0);
        }
    }
    for (size_t i = 0; i < n; ++i) {
        V t = tangential(sum[i], normal[i]);
        if (norm(t) == 0) t = perpendicular(normal[i]);
        out[i] = {float(t[0]), float(t[1]), float(t[2]), handed[i] < 0 ? -1.0f : 1.0f};
    }
    return out;
}

}  // namespace ellicast::gltf_write
