// Orientation repair before the inside test: every connected part made to agree with itself across
// its manifold edges, then turned so that it faces outward (or inward where it bounds a cavity).
//
// The encoder's inside test counts a point as inside where the winding number of the surface is
// about +1, which holds only for outward-facing triangles. An exported model whose faces all point
// inward (a common fault) has winding number -1 inside, so no seed grows and the object got no
// interior ellipsoid at all; a model with some parts or faces reversed loses those parts.
//
// 1. Parts: triangles joined across edges (by welded position) that exactly two triangles share.
//    Within a part, each triangle is turned to traverse every such edge opposite to its neighbour
//    (breadth-first from the part's first triangle); a part that cannot agree (a Moebius strip)
//    keeps what the search gave it and is counted.
// 2. Which way a part faces: a closed part (no boundary or non-manifold edge) faces outward when
//    its signed volume is positive, unless it lies inside an odd number of other closed parts, where
//    it bounds a cavity and faces inward. Nesting is counted by ray crossings against the other
//    closed parts whose bounding box holds the point, with a bound on the work. An open part is
//    turned by its signed volume only when that is clear (more than half of its unsigned volume
//    about its centre); otherwise, and for a flat part (a volume under 1e-5 of its area times its
//    size: a label's quad, whose volume is rounding noise), it keeps the orientation most of its
//    triangles had.
// Degenerate triangles (two corners at one position) are left as they are.
#include "encoder_internal.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace ellicast::detail {

namespace {

struct EdgeUse {
    uint64_t key;   // welded endpoints, smaller first
    uint32_t face;
    bool forward;   // the face traverses the edge from the smaller to the larger endpoint
};

struct Part {
    std::vector<uint32_t> faces;
    bool closed = true;
    V3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
};

// Parity of the crossings of the ray from `o` along a fixed, generic direction with triangle abc.
bool ray_crosses(const V3& o, const V3& a, const V3& b, const V3& c) {
    static const V3 d = {0.5773502691896257, 0.5773502691896258 * 1.0000117, 0.5773502691896256 * 0.9999871};
    const V3 e1 = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2 = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const V3 p = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (std::abs(det) < 1e-300) return false;
    const double inv = 1.0 / det;
    const V3 s = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (u < 0 || u > 1) return false;
    const V3 q = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    const double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (v < 0 || u + v > 1) return false;
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv > 0;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> orient_outward(const Mesh& mesh, const std::vector<uint32_t>& weld,
                                                     OrientationReport& report) {
    const auto& tris = mesh.triangles;
    const size_t n = tris.size();
    report = {};
    auto corner = [&](uint32_t f, int k) { return weld[tris[f][k]]; };
    auto degenerate = [&](uint32_t f) {
        return corner(f, 0) == corner(f, 1) || corner(f, 1) == corner(f, 2) || corner(f, 2) == corner(f, 0);
    };

    std::vector<EdgeUse> uses;
    uses.reserve(3 * n);
    for (uint32_t f = 0; f < n; ++f) {
        if (degenerate(f)) continue;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = corner(f, e), b = corner(f, (e + 1) % 3);
            uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), f, a < b});
        }
    }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return x.key != y.key ? x.key < y.key : x.face < y.face;
    });

    // Manifold links (two faces on an edge) as an adjacency list; `flip` on a link means the two
    // faces traverse the edge the same way, so one of them must turn to agree with the other.
    struct Link {
        uint32_t other;
        bool flip;
    };
    std::vector<uint32_t> link_start(n + 1, 0);
    std::vector<char> on_open_edge(n, 0);
    std::vector<std::array<uint32_t, 2>> pairs;
    std::vector<char> pair_flip;
    for (size_t i = 0; i < uses.size();) {
        size_t j = i;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        if (j - i == 2 && uses[i].face != uses[i + 1].face) {
            pairs.push_back({uses[i].face, uses[i + 1].face});
            pair_flip.push_back(uses[i].forward == uses[i + 1].forward);
            ++link_start[uses[i].face + 1];
            ++link_start[uses[i + 1].face + 1];
        } else {
            for (size_t k = i; k < j; ++k) on_open_edge[uses[k].face] = 1;
        }
        i = j;
    }
    for (size_t f = 0; f < n; ++f) link_start[f + 1] += link_start[f];
    std::vector<Link> links(link_start[n]);
    {
        std::vector<uint32_t> fill(link_start.begin(), link_start.end() - 1);
        for (size_t p = 0; p < pairs.size(); ++p) {
            links[fill[pairs[p][0]]++] = {pairs[p][1], bool(pair_flip[p])};
            links[fill[pairs[p][1]]++] = {pairs[p][0], bool(pair_flip[p])};
        }
    }

    // 1. Agreement within each part.
    constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> part_of(n, kNone);
    std::vector<char> turn(n, 0);
    std::vector<Part> parts;
    std::deque<uint32_t> queue;
    for (uint32_t s = 0; s < n; ++s) {
        if (part_of[s] != kNone || degenerate(s)) continue;
        const uint32_t id = uint32_t(parts.size());
        parts.emplace_back();
        Part& part = parts.back();
        bool conflict = false;
        part_of[s] = id;
        queue.push_back(s);
        while (!queue.empty()) {
            const uint32_t f = queue.front();
            queue.pop_front();
            part.faces.push_back(f);
            if (on_open_edge[f]) part.closed = false;
            for (uint32_t l = link_start[f]; l < link_start[f + 1]; ++l) {
                const uint32_t g = links[l].other;
                const char want = char(turn[f] ^ char(links[l].flip));
                if (part_of[g] == kNone) {
                    part_of[g] = id;
                    turn[g] = want;
                    queue.push_back(g);
                } else if (turn[g] != want) {
                    conflict = true;
                }
            }
        }
        if (conflict) {
            ++report.non_orientable_parts;
            part.closed = false;
        }
    }

    auto position = [&](uint32_t f, int k) -> V3 {
        const auto& p = mesh.positions[tris[f][k]];
        return {p[0], p[1], p[2]};
    };
    // The corners of face f as it would be written with `turned` applied.
    auto corners = [&](uint32_t f, bool turned, V3& a, V3& b, V3& c) {
        a = position(f, 0);
        b = position(f, turned ? 2 : 1);
        c = position(f, turned ? 1 : 2);
    };

    // 2. Which way each part faces.
    std::vector<double> volume(parts.size(), 0), unsigned_volume(parts.size(), 0), area(parts.size(), 0);
    for (size_t id = 0; id < parts.size(); ++id) {
        Part& part = parts[id];
        for (uint32_t f : part.faces)
            for (int k = 0; k < 3; ++k) {
                const V3 p = position(f, k);
                for (int d = 0; d < 3; ++d) part.lo[d] = std::min(part.lo[d], p[d]), part.hi[d] = std::max(part.hi[d], p[d]);
            }
        const V3 o = {0.5 * (part.lo[0] + part.hi[0]), 0.5 * (part.lo[1] + part.hi[1]), 0.5 * (part.lo[2] + part.hi[2])};
        for (uint32_t f : part.faces) {
            V3 a, b, c;
            corners(f, turn[f], a, b, c);
            for (int d = 0; d < 3; ++d) a[d] -= o[d], b[d] -= o[d], c[d] -= o[d];
            const double v = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
            volume[id] += v;
            unsigned_volume[id] += std::abs(v);
            const V3 u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            area[id] += 0.5 * std::sqrt(std::pow(u[1] * w[2] - u[2] * w[1], 2) + std::pow(u[2] * w[0] - u[0] * w[2], 2) +
                                        std::pow(u[0] * w[1] - u[1] * w[0], 2));
        }
    }

    // Nesting depth of each closed part among the other closed parts (bounded work: past the bound,
    // the remaining parts count as not nested).
    std::vector<uint32_t> depth(parts.size(), 0);
    {
        std::vector<uint32_t> closed;
        for (uint32_t id = 0; id < parts.size(); ++id)
            if (parts[id].closed && parts.size() > 1) closed.push_back(id);
        uint64_t budget = 200'000'000;  // triangle tests
        for (uint32_t i : closed) {
            const uint32_t f0 = parts[i].faces.front();
            const V3 a = position(f0, 0), b = position(f0, 1), c = position(f0, 2);
            const V3 q = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
            for (uint32_t j : closed) {
                if (j == i) continue;
                const Part& other = parts[j];
                bool inside_box = true;
                for (int d = 0; d < 3; ++d) inside_box &= q[d] >= other.lo[d] && q[d] <= other.hi[d];
                if (!inside_box) continue;
                if (budget < other.faces.size()) {
                    report.nesting_unchecked = true;
                    continue;
                }
                budget -= other.faces.size();
                bool odd = false;
                for (uint32_t g : other.faces) odd ^= ray_crosses(q, position(g, 0), position(g, 1), position(g, 2));
                depth[i] += odd;
            }
        }
    }

    std::vector<std::array<uint32_t, 3>> out = tris;
    for (size_t id = 0; id < parts.size(); ++id) {
        const Part& part = parts[id];
        bool reverse;
        // A flat part (a label, a card's face: its volume about its centre is rounding noise next to
        // its area times its size) has no inside: it keeps the orientation it came with.
        const double size = std::sqrt(std::pow(part.hi[0] - part.lo[0], 2) + std::pow(part.hi[1] - part.lo[1], 2) +
                                      std::pow(part.hi[2] - part.lo[2], 2));
        const bool flat = unsigned_volume[id] <= 1e-5 * area[id] * size;
        const bool clear = !flat && std::abs(volume[id]) > (part.closed ? 1e-9 : 0.5) * unsigned_volume[id];
        if (clear) {
            const bool want_positive = depth[id] % 2 == 0;
            reverse = (volume[id] > 0) != want_positive;
        } else {
            // No clear side: keep the orientation most of the part's triangles came with.
            size_t turned = 0;
            for (uint32_t f : part.faces) turned += turn[f];
            reverse = 2 * turned > part.faces.size();
        }
        ++report.parts;
        size_t changed = 0;
        for (uint32_t f : part.faces) {
            const bool t = bool(turn[f]) != reverse;
            if (t) {
                std::swap(out[f][1], out[f][2]);
                ++changed;
            }
        }
        if (changed == part.faces.size()) ++report.reversed_parts;
        else if (changed > 0) ++report.mended_parts;
        report.turned_faces += changed;
        if (depth[id] % 2 == 1) ++report.cavities;
    }
    return out;
}

}  // namespace ellicast::detail
