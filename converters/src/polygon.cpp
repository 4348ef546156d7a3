// Polygon triangulation without added points: ears clipped in rounds (hierarchical), a y-monotone
// partition when that would take too long (de Berg et al., Computational Geometry, ch. 3), and a
// check of the result that falls back to OpenMesh's fan.
#include "ellicast/converters/polygon.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace ellicast {

namespace {

using Triangle = std::array<uint32_t, 3>;

constexpr double kPi = 3.14159265358979323846;

struct P2 {
    double x, y;
};

double orient(const P2& a, const P2& b, const P2& c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

std::vector<Triangle> fan(size_t n) {
    std::vector<Triangle> out;
    for (uint32_t i = 1; i + 1 < n; ++i) out.push_back({0, i, i + 1});
    return out;
}

// The corners in the plane of the Newell normal, in a frame where the polygon turns
// counter-clockwise (positive area). False for a polygon without area.
bool project(std::span<const std::array<float, 3>> corners, std::vector<P2>& out) {
    const size_t n = corners.size();
    double c[3] = {0, 0, 0};
    for (const auto& p : corners)
        for (int k = 0; k < 3; ++k) c[k] += p[k];
    for (double& v : c) v /= double(n);
    double nrm[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        const auto &p = corners[i], &q = corners[(i + 1) % n];
        double a[3], b[3];
        for (int k = 0; k < 3; ++k) a[k] = p[k] - c[k], b[k] = q[k] - c[k];
        nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(len > 0) || !std::isfinite(len)) return false;
    for (double& v : nrm) v /= len;
    // u: perpendicular to the normal, from the axis the normal is least along; v = normal x u.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(nrm[k]) < std::abs(nrm[axis])) axis = k;
    double e[3] = {0, 0, 0};
    e[axis] = 1;
    double u[3] = {nrm[1] * e[2] - nrm[2] * e[1], nrm[2] * e[0] - nrm[0] * e[2], nrm[0] * e[1] - nrm[1] * e[0]};
    const double ulen = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& v : u) v /= ulen;
    const double v[3] = {nrm[1] * u[2] - nrm[2] * u[1], nrm[2] * u[0] - nrm[0] * u[2], nrm[0] * u[1] - nrm[1] * u[0]};
    out.resize(n);
    for (size_t i = 0; i < n; ++i) {
        double a[3];
        for (int k = 0; k < 3; ++k) a[k] = corners[i][k] - c[k];
        out[i] = {a[0] * u[0] + a[1] * u[1] + a[2] * u[2], a[0] * v[0] + a[1] * v[1] + a[2] * v[2]};
    }
    double area2 = 0;
    for (size_t i = 0; i < n; ++i) area2 += out[i].x * out[(i + 1) % n].y - out[(i + 1) % n].x * out[i].y;
    double extent = 0;
    for (const auto& p : out) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    return area2 > 1e-12 * extent * extent;
}

// The non-convex corners in a k-d tree that can answer "does any of them lie in this triangle"
// and forget corners as they turn convex or are clipped.
class CornerTree {
public:
    CornerTree(const std::vector<P2>& p, std::vector<uint32_t> ids) : p_(p), ids_(std::move(ids)), leaf_(p.size(), -1) {
        alive_.assign(p.size(), 0);
        for (uint32_t i : ids_) alive_[i] = 1;
        if (!ids_.empty()) build(0, uint32_t(ids_.size()), -1);
    }

    void remove(uint32_t id) {
        if (!alive_[id]) return;
        alive_[id] = 0;
        for (int32_t k = leaf_[id]; k >= 0; k = nodes_[k].parent) --nodes_[k].alive;
    }

    // Whether a corner other than ia, ib, ic lies in the closed counter-clockwise triangle; adds
    // the nodes and corners visited to `work`.
    bool any_in(uint32_t ia, uint32_t ib, uint32_t ic, uint64_t& work) const {
        if (nodes_.empty()) return false;
        const P2 &a = p_[ia], &b = p_[ib], &c = p_[ic];
        const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
        const double y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
        int32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            ++work;
            if (node.alive == 0 || node.x0 > x1 || node.x1 < x0 || node.y0 > y1 || node.y1 < y0) continue;
            // The box wholly outside one side of the triangle.
            const P2 box[4] = {{node.x0, node.y0}, {node.x1, node.y0}, {node.x0, node.y1}, {node.x1, node.y1}};
            bool outside = false;
            for (const auto& [s, t] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}}) {
                bool all = true;
                for (const P2& q : box) all = all && orient(*s, *t, q) < 0;
                outside = outside || all;
            }
            if (outside) continue;
            if (node.left < 0) {
                for (uint32_t k = node.begin; k < node.end; ++k) {
                    const uint32_t i = ids_[k];
                    ++work;
                    if (!alive_[i] || i == ia || i == ib || i == ic) continue;
                    const P2& q = p_[i];
                    if (orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0) return true;
                }
                continue;
            }
            if (top + 2 > 64) return true;  // cannot happen (depth ~log2 n); answer "blocked"
            stack[top++] = node.left;
            stack[top++] = node.right;
        }
        return false;
    }

private:
    struct Node {
        double x0, y0, x1, y1;
        uint32_t begin, end;
        int32_t left = -1, right = -1, parent = -1;
        uint32_t alive = 0;
    };

    int32_t build(uint32_t begin, uint32_t end, int32_t parent) {
        const int32_t k = int32_t(nodes_.size());
        nodes_.push_back({});
        Node node;
        node.begin = begin;
        node.end = end;
        node.parent = parent;
        node.alive = end - begin;
        node.x0 = node.y0 = INFINITY;
        node.x1 = node.y1 = -INFINITY;
        for (uint32_t i = begin; i < end; ++i) {
            const P2& q = p_[ids_[i]];
            node.x0 = std::min(node.x0, q.x), node.x1 = std::max(node.x1, q.x);
            node.y0 = std::min(node.y0, q.y), node.y1 = std::max(node.y1, q.y);
        }
        if (end - begin <= 8) {
            for (uint32_t i = begin; i < end; ++i) leaf_[ids_[i]] = k;
            nodes_[k] = node;
            return k;
        }
        const bool by_x = node.x1 - node.x0 >= node.y1 - node.y0;
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(ids_.begin() + begin, ids_.begin() + mid, ids_.begin() + end, [&](uint32_t i, uint32_t j) {
            const double a = by_x ? p_[i].x : p_[i].y, b = by_x ? p_[j].x : p_[j].y;
            return a < b || (a == b && i < j);
        });
        nodes_[k] = node;
        const int32_t left = build(begin, mid, k);
        const int32_t right = build(mid, end, k);
        nodes_[k].left = left;
        nodes_[k].right = right;
        return k;
    }

    const std::vector<P2>& p_;
    std::vector<uint32_t> ids_;
    std::vector<int32_t> leaf_;
    std::vector<char> alive_;
    std::vector<Node> nodes_;
};

// Ear clipping in rounds: each round walks the polygon once and clips every ear it meets but the
// corner after one it just clipped, so a convex run loses every other corner per round and its
// triangles double in size from round to round. False when no ear is left (a polygon that is not
// simple) or the work passes `budget`.
bool clip_ears(const std::vector<P2>& p, uint64_t budget, std::vector<Triangle>& out) {
    const uint32_t n = uint32_t(p.size());
    std::vector<uint32_t> prev(n), next(n), reflex;
    std::vector<char> convex(n);
    for (uint32_t i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
        convex[i] = orient(p[prev[i]], p[i], p[next[i]]) > 0;
        if (!convex[i]) reflex.push_back(i);
    }
    CornerTree tree(p, std::move(reflex));
    uint64_t work = 0;
    uint32_t left = n, start = 0;
    while (left > 3) {
        uint32_t v = start, clipped = 0;
        bool skip = false;
        for (uint32_t steps = left; steps > 0 && left > 3; --steps) {
            uint32_t after = next[v];
            ++work;
            if (skip) {
                skip = false;
            } else if (convex[v] && !tree.any_in(prev[v], v, next[v], work)) {
                const uint32_t a = prev[v], c = next[v];
                out.push_back({a, v, c});
                next[a] = c;
                prev[c] = a;
                --left;
                ++clipped;
                if (start == v) start = c;
                for (uint32_t u : {a, c}) {
                    // Clipping an ear only narrows its neighbours' angles: a convex corner that
                    // turns reflex means the polygon overlaps itself.
                    const bool now = orient(p[prev[u]], p[u], p[next[u]]) > 0;
                    if (!now && convex[u]) return false;
                    if (now && !convex[u]) {
                        convex[u] = 1;
                        tree.remove(u);
                    }
                }
                skip = true;
            }
            if (work > budget) return false;
            v = after;
        }
        if (clipped == 0) return false;
    }
    out.push_back({prev[start], start, next[start]});
    return true;
}

// The monotone pieces' triangles, by the stack algorithm, for one piece given counter-clockwise.
void triangulate_monotone(const std::vector<P2>& p, const std::vector<uint32_t>& rank, const std::vector<uint32_t>& face,
                          std::vector<Triangle>& out) {
    const size_t m = face.size();
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (orient(p[a], p[b], p[c]) < 0) std::swap(b, c);
        out.push_back({a, b, c});
    };
    if (m == 3) {
        emit(face[0], face[1], face[2]);
        return;
    }
    std::vector<uint32_t> sorted(m);
    for (size_t k = 0; k < m; ++k) sorted[k] = uint32_t(k);
    std::sort(sorted.begin(), sorted.end(), [&](uint32_t i, uint32_t j) { return rank[face[i]] < rank[face[j]]; });
    // Chains: from the top forward (counter-clockwise) to the bottom is the left chain.
    std::vector<char> chain(m, 2);
    const uint32_t top = sorted.front(), bottom = sorted.back();
    chain[top] = chain[bottom] = 0;
    for (size_t k = (top + 1) % m; k != bottom; k = (k + 1) % m) chain[k] = 1;
    std::vector<uint32_t> stack = {sorted[0], sorted[1]};
    for (size_t j = 2; j + 1 < m; ++j) {
        const uint32_t u = sorted[j];
        if (chain[u] != chain[stack.back()]) {
            for (size_t s = 0; s + 1 < stack.size(); ++s) emit(face[u], face[stack[s]], face[stack[s + 1]]);
            stack = {sorted[j - 1], u};
        } else {
            uint32_t last = stack.back();
            stack.pop_back();
            while (!stack.empty()) {
                const uint32_t t = stack.back();
                const double o = orient(p[face[t]], p[face[u]], p[face[last]]);
                if (!(chain[u] == 1 ? o < 0 : o > 0)) break;
                emit(face[u], face[last], face[t]);
                last = t;
                stack.pop_back();
            }
            stack.push_back(last);
            stack.push_back(u);
        }
    }
    for (size_t s = 0; s + 1 < stack.size(); ++s) emit(face[bottom], face[stack[s]], face[stack[s + 1]]);
}

// A y-monotone partition by a plane sweep (de Berg et al., 3.2), its pieces traced as faces of
// the polygon plus diagonals, each triangulated by the stack algorithm. O(n log n). False when the
// sweep finds the polygon is not simple.
bool monotone(const std::vector<P2>& p, const std::vector<uint32_t>& order, const std::vector<uint32_t>& rank,
              std::vector<Triangle>& out) {
    const uint32_t n = uint32_t(p.size());
    auto nx = [n](uint32_t i) { return i + 1 == n ? 0 : i + 1; };
    auto pv = [n](uint32_t i) { return i == 0 ? n - 1 : i - 1; };
    struct Sweep {
        double x = 0, y = 0;
    } sweep;
    constexpr uint32_t kProbe = UINT32_MAX;
    // Edge e (corner e to the next) at the sweep line; kProbe is the sweep point itself.
    auto x_at = [&](uint32_t e) {
        if (e == kProbe) return sweep.x;
        const P2 &a = p[e], &b = p[nx(e)];
        if (a.y == b.y) return std::clamp(sweep.x, std::min(a.x, b.x), std::max(a.x, b.x));
        return a.x + (sweep.y - a.y) / (b.y - a.y) * (b.x - a.x);
    };
    auto less = [&](uint32_t l, uint32_t r) {
        const double xl = x_at(l), xr = x_at(r);
        return xl != xr ? xl < xr : l < r;
    };
    std::set<uint32_t, decltype(less)> status(less);
    std::vector<std::set<uint32_t, decltype(less)>::iterator> where(n, status.end());
    std::vector<uint32_t> helper(n, 0);
    std::vector<char> merge(n, 0);
    std::vector<std::pair<uint32_t, uint32_t>> diagonals;
    auto diagonal = [&](uint32_t a, uint32_t b) {
        if (a != b && nx(a) != b && nx(b) != a) diagonals.push_back({std::min(a, b), std::max(a, b)});
    };
    auto insert = [&](uint32_t e) {
        auto [it, fresh] = status.insert(e);
        where[e] = it;
        helper[e] = e;
        return fresh;
    };
    // Ends edge e (which must be in the status), with the diagonal to its helper if that merges.
    auto finish = [&](uint32_t e, uint32_t v) {
        if (where[e] == status.end()) return false;
        if (merge[helper[e]]) diagonal(v, helper[e]);
        status.erase(where[e]);
        where[e] = status.end();
        return true;
    };
    auto left_of = [&](uint32_t& e) {
        auto it = status.lower_bound(kProbe);
        if (it == status.begin()) return false;
        e = *--it;
        return true;
    };
    for (uint32_t v : order) {
        sweep = {p[v].x, p[v].y};
        const uint32_t a = pv(v), c = nx(v);
        const bool a_below = rank[a] > rank[v], c_below = rank[c] > rank[v];
        const double o = orient(p[a], p[v], p[c]);
        uint32_t j = 0;
        if (a_below && c_below) {
            if (o == 0) return false;
            if (o < 0) {  // split
                if (!left_of(j)) return false;
                diagonal(v, helper[j]);
                helper[j] = v;
            }
            if (!insert(v)) return false;  // start or split
        } else if (!a_below && !c_below) {
            if (o == 0) return false;
            if (!finish(a, v)) return false;
            if (o < 0) {  // merge
                merge[v] = 1;
                if (!left_of(j)) return false;
                if (merge[helper[j]]) diagonal(v, helper[j]);
                helper[j] = v;
            }
        } else if (!a_below) {  // regular, the interior to the right
            if (!finish(a, v) || !insert(v)) return false;
        } else {  // regular, the interior to the left
            if (!left_of(j)) return false;
            if (merge[helper[j]]) diagonal(v, helper[j]);
            helper[j] = v;
        }
    }

    // The pieces: faces of the polygon's edges and the diagonals, each corner's neighbours in
    // counter-clockwise order; from half-edge u->w the face goes on to w's neighbour just
    // clockwise of u.
    std::sort(diagonals.begin(), diagonals.end());
    diagonals.erase(std::unique(diagonals.begin(), diagonals.end()), diagonals.end());
    std::vector<uint32_t> first(n + 1, 0);
    for (uint32_t i = 0; i < n; ++i) first[i + 1] = 2;
    for (const auto& [a, b] : diagonals) ++first[a + 1], ++first[b + 1];
    for (uint32_t i = 0; i < n; ++i) first[i + 1] += first[i];
    std::vector<uint32_t> around(first[n]), fill(first.begin(), first.end() - 1);
    for (uint32_t i = 0; i < n; ++i) around[fill[i]++] = pv(i), around[fill[i]++] = nx(i);
    for (const auto& [a, b] : diagonals) around[fill[a]++] = b, around[fill[b]++] = a;
    for (uint32_t i = 0; i < n; ++i)
        std::sort(around.begin() + first[i], around.begin() + first[i + 1], [&](uint32_t s, uint32_t t) {
            const double as = std::atan2(p[s].y - p[i].y, p[s].x - p[i].x), at = std::atan2(p[t].y - p[i].y, p[t].x - p[i].x);
            return as < at || (as == at && s < t);
        });
    std::vector<char> used(around.size(), 0);
    auto slot = [&](uint32_t at, uint32_t to) -> int64_t {
        for (uint32_t k = first[at]; k < first[at + 1]; ++k)
            if (around[k] == to) return k;
        return -1;
    };
    std::vector<uint32_t> face;
    for (uint32_t s = 0; s < n; ++s)
        for (uint32_t k = first[s]; k < first[s + 1]; ++k) {
            if (used[k] || around[k] == pv(s)) continue;  // done, or the outside of an edge
            face.clear();
            uint32_t from = s, h = k;
            for (size_t steps = 0;; ++steps) {
                if (steps > around.size() || used[h]) return false;
                used[h] = 1;
                face.push_back(from);
                const uint32_t to = around[h];
                const int64_t back = slot(to, from);
                if (back < 0) return false;
                const uint32_t deg = first[to + 1] - first[to];
                const uint32_t next = first[to] + (uint32_t(back) - first[to] + deg - 1) % deg;
                if (around[next] == pv(to)) return false;  // would leave the polygon
                from = to;
                h = next;
                if (h == k) break;
            }
            if (face.size() < 3) return false;
            triangulate_monotone(p, rank, face, out);
        }
    return true;
}

// Whether `tris` triangulate the polygon: n - 2 triangles whose directed edges are the polygon's
// edges once each plus inner edges in both directions, none inverted, filling every corner's inner
// angle exactly (a surface that winds twice over part of the plane overfills some corner).
bool is_triangulation(const std::vector<P2>& p, const std::vector<Triangle>& tris) {
    const size_t n = p.size();
    if (tris.size() != n - 2) return false;
    double extent = 0;
    for (const auto& q : p) extent = std::max({extent, std::abs(q.x), std::abs(q.y)});
    const double tolerance = 1e-12 * extent * extent;
    std::vector<uint64_t> edges;
    edges.reserve(3 * tris.size());
    std::vector<double> filled(n, 0.0);
    for (const auto& t : tris) {
        for (int k = 0; k < 3; ++k)
            if (t[k] >= n || t[k] == t[(k + 1) % 3]) return false;
        if (orient(p[t[0]], p[t[1]], p[t[2]]) < -tolerance) return false;
        for (int k = 0; k < 3; ++k) {
            const P2 &a = p[t[k]], &b = p[t[(k + 1) % 3]], &c = p[t[(k + 2) % 3]];
            const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
            filled[t[k]] += std::atan2(ux * wy - uy * wx, ux * wx + uy * wy);
            edges.push_back(uint64_t(t[k]) << 32 | t[(k + 1) % 3]);
        }
    }
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    size_t boundary = 0;
    for (uint64_t e : edges) {
        const uint32_t a = uint32_t(e >> 32), b = uint32_t(e);
        if (b == (a + 1) % n) ++boundary;
        else if (a == (b + 1) % n || !std::binary_search(edges.begin(), edges.end(), uint64_t(b) << 32 | a))
            return false;
    }
    if (boundary != n) return false;
    for (size_t i = 0; i < n; ++i) {
        const P2 &a = p[(i + n - 1) % n], &b = p[i], &c = p[(i + 1) % n];
        const double ux = c.x - b.x, uy = c.y - b.y, wx = a.x - b.x, wy = a.y - b.y;
        double inner = std::atan2(ux * wy - uy * wx, ux * wx + uy * wy);
        if (inner < 0) inner += 2 * kPi;
        if (std::abs(filled[i] - inner) > 1e-6) return false;
    }
    return true;
}

}  // namespace

PolygonTriangulation triangulate_polygon(std::span<const std::array<float, 3>> corners) {
    PolygonTriangulation result;
    const size_t n = corners.size();
    if (n < 3 || n >= UINT32_MAX) return result;
    result.triangles = fan(n);
    std::vector<P2> p;
    if (!project(corners, p)) return result;
    if (n == 3) {
        result.simple = true;
        return result;
    }
    // Two corners at one point: the polygon touches itself (the sweep also needs distinct points).
    std::vector<uint32_t> order(n), rank(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t i, uint32_t j) {
        return p[i].y > p[j].y || (p[i].y == p[j].y && (p[i].x < p[j].x || (p[i].x == p[j].x && i < j)));
    });
    for (uint32_t k = 0; k < n; ++k) {
        rank[order[k]] = k;
        if (k > 0 && p[order[k]].x == p[order[k - 1]].x && p[order[k]].y == p[order[k - 1]].y) return result;
    }
    // A small polygon that its fan triangulates (a convex one, or a quad concave at its third
    // corner) keeps the fan, the triangles OpenMesh made before.
    if (n <= 32 && is_triangulation(p, result.triangles)) {
        result.simple = true;
        return result;
    }
    std::vector<Triangle> tris;
    tris.reserve(n - 2);
    uint64_t log2n = 1;
    while ((uint64_t(1) << log2n) < n) ++log2n;
    if (!clip_ears(p, 6 * uint64_t(n) * (log2n + 4), tris) || !is_triangulation(p, tris)) {
        tris.clear();
        if (!monotone(p, order, rank, tris) || !is_triangulation(p, tris)) return result;
    }
    result.triangles = std::move(tris);
    result.simple = true;
    return result;
}

}  // namespace ellicast
