// Generalized winding numbers (Jacobson, Kavan, Sorkine-Hornung 2013) evaluated with a hierarchy
// (Barill et al. 2018, "Fast winding numbers for soups and clouds", first-order dipoles), and a
// voxel grid of them for the encoder's inside test.
#include "encoder_internal.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ellicast::detail {

namespace {

constexpr double kInvFourPi = 0.079577471545947667884;

double dot3(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 sub3(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross3(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// atan2 to about 1e-5 radians (a minimax polynomial after reduction to [0, 1]): the winding
// number sums hundreds of these and is compared with 1/2, and std::atan2 was a third of the time.
double fast_atan2(double y, double x) {
    const double ax = std::abs(x), ay = std::abs(y);
    const double hi = std::max(ax, ay), lo = std::min(ax, ay);
    if (hi == 0) return 0;
    const double t = lo / hi, t2 = t * t;
    double r = t * (0.99997726 + t2 * (-0.33262347 + t2 * (0.19354346 + t2 * (-0.11643287 + t2 * (0.05265332 + t2 * -0.01172120)))));
    if (ay > ax) r = 1.57079632679489662 - r;
    if (x < 0) r = 3.14159265358979324 - r;
    return y < 0 ? -r : r;
}

// Solid angle of triangle (a, b, c) seen from q (Van Oosterom & Strackee 1983), signed.
double solid_angle(const V3& a0, const V3& b0, const V3& c0, const V3& q) {
    V3 a = sub3(a0, q), b = sub3(b0, q), c = sub3(c0, q);
    double la = std::sqrt(dot3(a, a)), lb = std::sqrt(dot3(b, b)), lc = std::sqrt(dot3(c, c));
    double num = dot3(a, cross3(b, c));
    double den = la * lb * lc + dot3(a, b) * lc + dot3(b, c) * la + dot3(c, a) * lb;
    return 2.0 * fast_atan2(num, den);
}

}  // namespace

WindingNumber::WindingNumber(const TriangleTree& tree, double accuracy) : tree_(tree), beta2_(accuracy * accuracy) {
    const auto& nodes = tree.nodes();
    const auto& tris = tree.triangles();
    dipoles_.resize(nodes.size());
    // Children have larger indices than their parent: accumulate bottom-up.
    std::vector<double> area(nodes.size(), 0.0);
    for (size_t k = nodes.size(); k-- > 0;) {
        const auto& node = nodes[k];
        NodeDipole& d = dipoles_[k];
        if (node.is_leaf()) {
            V3 csum{0, 0, 0};
            double asum = 0;
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const auto& t = tris[i];
                V3 nrm = cross3(sub3(t.v[1], t.v[0]), sub3(t.v[2], t.v[0]));
                for (int j = 0; j < 3; ++j) d.normal[j] += 0.5 * nrm[j];
                double a = 0.5 * std::sqrt(dot3(nrm, nrm));
                for (int j = 0; j < 3; ++j) csum[j] += a * (t.v[0][j] + t.v[1][j] + t.v[2][j]) / 3.0;
                asum += a;
            }
            area[k] = asum;
            for (int j = 0; j < 3; ++j)
                d.center[j] = asum > 0 ? csum[j] / asum : 0.5 * (node.bounds.min[j] + node.bounds.max[j]);
        } else {
            const NodeDipole &l = dipoles_[node.first], &r = dipoles_[node.right];
            double al = area[node.first], ar = area[node.right];
            area[k] = al + ar;
            for (int j = 0; j < 3; ++j) {
                d.normal[j] = l.normal[j] + r.normal[j];
                d.center[j] = area[k] > 0 ? (al * l.center[j] + ar * r.center[j]) / area[k]
                                          : 0.5 * (node.bounds.min[j] + node.bounds.max[j]);
            }
        }
        // A ball around the centre holding the node's box.
        double r2 = 0;
        for (int j = 0; j < 3; ++j) {
            double e = std::max(std::abs(node.bounds.max[j] - d.center[j]), std::abs(d.center[j] - node.bounds.min[j]));
            r2 += e * e;
        }
        d.radius2 = r2;
    }
}

double WindingNumber::operator()(const V3& q) const {
    const auto& nodes = tree_.nodes();
    if (nodes.empty()) return 0;
    const auto& tris = tree_.triangles();
    double sum = 0;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        uint32_t k = stack[--top];
        const auto& node = nodes[k];
        const NodeDipole& d = dipoles_[k];
        V3 r = sub3(d.center, q);
        double dist2 = dot3(r, r);
        if (dist2 > beta2_ * d.radius2) {
            sum += dot3(d.normal, r) / (dist2 * std::sqrt(dist2));  // far: one dipole for the node
            continue;
        }
        if (node.is_leaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                sum += solid_angle(tris[i].v[0], tris[i].v[1], tris[i].v[2], q);
            continue;
        }
        if (top + 2 > 128) continue;
        stack[top++] = node.first;
        stack[top++] = node.right;
    }
    return sum * kInvFourPi;
}

double VoxelGrid::sample(const Vec3& p) const {
    double f[3];
    int i0[3];
    for (int k = 0; k < 3; ++k) {
        double u = (p[k] - origin[k]) / h;
        if (!(u >= 0) || u > n[k] - 1) return 0;
        i0[k] = std::min(int(u), n[k] - 2 >= 0 ? n[k] - 2 : 0);
        f[k] = u - i0[k];
    }
    double v = 0;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                int x = std::min(i0[0] + dx, n[0] - 1), y = std::min(i0[1] + dy, n[1] - 1),
                    z = std::min(i0[2] + dz, n[2] - 1);
                double wgt = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
                v += wgt * w[index(x, y, z)];
            }
    return v;
}

namespace {

// A grid over `box` with `cells` voxels along its longest side and a one-voxel margin, all zero.
VoxelGrid layout_grid(const TriangleTree::Box& box, int cells) {
    VoxelGrid g;
    double extent = 0;
    for (int k = 0; k < 3; ++k) extent = std::max(extent, box.max[k] - box.min[k]);
    if (!(extent > 0)) extent = 1;
    g.h = extent / cells;
    for (int k = 0; k < 3; ++k) {
        double e = box.max[k] - box.min[k];
        g.n[k] = int(std::ceil(e / g.h - 1e-9)) + 2;
        g.origin[k] = box.min[k] - 0.5 * (g.n[k] * g.h - e) + 0.5 * g.h;
    }
    g.w.assign(g.size(), 0.0f);
    return g;
}

// Side of the (y, z) projection of edge a->b on which q lies, for q nudged by an infinitesimal
// (eps, eps^2) so that it is never on an edge (simulation of simplicity): +1 left, -1 right, 0
// only for an edge that projects to a point. The value is computed from the endpoints in a fixed
// order, so the two triangles sharing an edge get exactly opposite answers: a ray through a shared
// edge or vertex crosses exactly one of them.
int edge_side(const V3& a, const V3& b, double qy, double qz) {
    const bool swap = std::tie(a[1], a[2]) > std::tie(b[1], b[2]);
    const V3& p = swap ? b : a;
    const V3& r = swap ? a : b;
    const double dy = r[1] - p[1], dz = r[2] - p[2];
    const double e = dy * (qz - p[2]) - dz * (qy - p[1]);
    int s = e > 0 ? 1 : e < 0 ? -1 : dz != 0 ? (dz < 0 ? 1 : -1) : dy != 0 ? (dy > 0 ? 1 : -1) : 0;
    return swap ? -s : s;
}

}  // namespace

VoxelGrid build_closed_winding_grid(const TriangleTree& tree, const TriangleTree::Box& box, int cells,
                                    unsigned threads) {
    VoxelGrid g = layout_grid(box, cells);
    const auto& nodes = tree.nodes();
    const auto& tris = tree.triangles();
    if (nodes.empty()) return g;
    // One ray along +x per row of voxels; each crossing adds its orientation (+1 leaving through an
    // outward face) to every voxel before it.
    parallel_for(size_t(g.n[2]), threads, [&](size_t z) {
        std::vector<std::pair<double, int>> hits;
        for (int y = 0; y < g.n[1]; ++y) {
            const double qy = g.origin[1] + y * g.h, qz = g.origin[2] + double(z) * g.h;
            hits.clear();
            uint32_t stack[128];
            int top = 0;
            stack[top++] = 0;
            while (top > 0) {
                const auto& node = nodes[stack[--top]];
                if (qy < node.bounds.min[1] || qy > node.bounds.max[1] || qz < node.bounds.min[2] ||
                    qz > node.bounds.max[2])
                    continue;
                if (node.is_leaf()) {
                    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                        const auto& v = tris[i].v;
                        int s0 = edge_side(v[0], v[1], qy, qz), s1 = edge_side(v[1], v[2], qy, qz),
                            s2 = edge_side(v[2], v[0], qy, qz);
                        if (s0 == 0 || s0 != s1 || s1 != s2) continue;
                        // Where the ray meets the triangle's plane (barycentric from the projection).
                        const double n0 = (v[1][1] - v[0][1]) * (v[2][2] - v[0][2]) - (v[1][2] - v[0][2]) * (v[2][1] - v[0][1]);
                        double x = (v[0][0] + v[1][0] + v[2][0]) / 3.0;
                        if (n0 != 0) {
                            const double wa = ((v[1][1] - qy) * (v[2][2] - qz) - (v[1][2] - qz) * (v[2][1] - qy)) / n0;
                            const double wb = ((v[2][1] - qy) * (v[0][2] - qz) - (v[2][2] - qz) * (v[0][1] - qy)) / n0;
                            x = wa * v[0][0] + wb * v[1][0] + (1 - wa - wb) * v[2][0];
                        }
                        hits.push_back({x, s0});
                    }
                    continue;
                }
                if (top + 2 > 128) continue;
                stack[top++] = node.first;
                stack[top++] = node.right;
            }
            std::sort(hits.begin(), hits.end());
            // Voxels from the far end of the row back: the winding number is the sum of the crossings beyond.
            int w = 0;
            size_t k = hits.size();
            for (int x = g.n[0] - 1; x >= 0; --x) {
                const double qx = g.origin[0] + x * g.h;
                while (k > 0 && hits[k - 1].first > qx) w += hits[--k].second;
                g.w[g.index(x, y, int(z))] = float(w);
            }
        }
    });
    return g;
}

VoxelGrid build_winding_grid(const TriangleTree& tree, const WindingNumber& winding, const TriangleTree::Box& box,
                             int cells, unsigned threads, const std::function<void(double)>& progress) {
    VoxelGrid g = layout_grid(box, cells);
    auto center = [&](int x, int y, int z) -> V3 {
        return {g.origin[0] + x * g.h, g.origin[1] + y * g.h, g.origin[2] + z * g.h};
    };

    // Lattice of block corners: every B-th voxel along each axis, and the last one.
    constexpr int B = 4;
    std::vector<int> lattice[3];
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < g.n[k] - 1; i += B) lattice[k].push_back(i);
        lattice[k].push_back(g.n[k] - 1);
    }
    const size_t lx = lattice[0].size(), ly = lattice[1].size(), lz = lattice[2].size();
    std::vector<float> corner(lx * ly * lz);
    parallel_for(lz, threads, [&](size_t iz) {
        for (size_t iy = 0; iy < ly; ++iy)
            for (size_t ix = 0; ix < lx; ++ix)
                corner[(iz * ly + iy) * lx + ix] =
                    float(winding(center(lattice[0][ix], lattice[1][iy], lattice[2][iz])));
    });
    if (progress) progress(0.2);

    // Each block owns voxels [L_i, L_{i+1}) (the last block also its far end).
    parallel_for(lz - 1, threads, [&](size_t bz) {
        for (size_t by = 0; by + 1 < ly; ++by)
            for (size_t bx = 0; bx + 1 < lx; ++bx) {
                float c[8];
                bool any_in = false, any_out = false;
                for (int j = 0; j < 8; ++j) {
                    c[j] = corner[((bz + (j >> 2 & 1)) * ly + by + (j >> 1 & 1)) * lx + bx + (j & 1)];
                    (c[j] > 0.5f ? any_in : any_out) = true;
                }
                int lo[3] = {lattice[0][bx], lattice[1][by], lattice[2][bz]};
                int hi[3] = {lattice[0][bx + 1], lattice[1][by + 1], lattice[2][bz + 1]};
                int end[3];
                for (int k = 0; k < 3; ++k) end[k] = hi[k] + (hi[k] == g.n[k] - 1 ? 1 : 0);
                bool uniform = !(any_in && any_out);
                if (uniform) {
                    V3 mid = center(lo[0], lo[1], lo[2]);
                    double half2 = 0;
                    for (int k = 0; k < 3; ++k) {
                        double e = 0.5 * (hi[k] - lo[k]) * g.h;
                        mid[k] += e;
                        half2 += e * e;
                    }
                    uniform = !tree.any_within(mid, std::sqrt(half2) + g.h);
                }
                for (int z = lo[2]; z < end[2]; ++z)
                    for (int y = lo[1]; y < end[1]; ++y)
                        for (int x = lo[0]; x < end[0]; ++x) {
                            float v;
                            if (uniform) {
                                double fx = hi[0] > lo[0] ? double(x - lo[0]) / (hi[0] - lo[0]) : 0;
                                double fy = hi[1] > lo[1] ? double(y - lo[1]) / (hi[1] - lo[1]) : 0;
                                double fz = hi[2] > lo[2] ? double(z - lo[2]) / (hi[2] - lo[2]) : 0;
                                double s = 0;
                                for (int j = 0; j < 8; ++j)
                                    s += c[j] * ((j & 1) ? fx : 1 - fx) * ((j >> 1 & 1) ? fy : 1 - fy) *
                                         ((j >> 2 & 1) ? fz : 1 - fz);
                                v = float(s);
                            } else {
                                v = float(winding(center(x, y, z)));
                            }
                            g.w[g.index(x, y, z)] = v;
                        }
            }
    });
    if (progress) progress(1.0);
    return g;
}

}  // namespace ellicast::detail
