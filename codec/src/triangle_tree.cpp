// Static bounding-volume hierarchy over triangles: median split on the longest axis of the
// centroid bounds, small leaves, depth-first queries visiting the nearer child first.
#include "ellicast/codec/triangle_tree.h"

#include "closest_point.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ellicast {

namespace {

using V3 = std::array<double, 3>;

constexpr uint32_t kLeafSize = 4;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double sq(const V3& a) { return dot(a, a); }

void grow(TriangleTree::Box& box, const V3& p) {
    for (int k = 0; k < 3; ++k) {
        box.min[k] = std::min(box.min[k], p[k]);
        box.max[k] = std::max(box.max[k], p[k]);
    }
}

}  // namespace

V3 closest_point_on_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
    return detail::closest_point_on_triangle(p, a, b, c);
}

double squared_distance_to_box(const V3& p, const TriangleTree::Box& box) {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
        double e = 0;
        if (p[k] < box.min[k]) e = box.min[k] - p[k];
        else if (p[k] > box.max[k]) e = p[k] - box.max[k];
        d += e * e;
    }
    return d;
}

TriangleTree::TriangleTree(std::span<const std::array<float, 3>> positions,
                           std::span<const std::array<uint32_t, 3>> triangles) {
    triangles_.reserve(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) {
        const auto& tri = triangles[t];
        if (tri[0] >= positions.size() || tri[1] >= positions.size() || tri[2] >= positions.size()) continue;
        Triangle out;
        bool finite = true;
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) {
                out.v[c][k] = positions[tri[c]][k];
                finite = finite && std::isfinite(out.v[c][k]);
            }
        if (!finite) continue;
        out.index = static_cast<uint32_t>(t);
        triangles_.push_back(out);
    }
    if (triangles_.empty()) return;

    std::vector<V3> centroids(triangles_.size());
    for (size_t i = 0; i < triangles_.size(); ++i)
        for (int k = 0; k < 3; ++k)
            centroids[i][k] = (triangles_[i].v[0][k] + triangles_[i].v[1][k] + triangles_[i].v[2][k]) / 3.0;
    std::vector<uint32_t> order(triangles_.size());
    std::iota(order.begin(), order.end(), 0u);

    nodes_.reserve(2 * triangles_.size() / kLeafSize + 2);
    struct Task {
        uint32_t node, first, count;
    };
    std::vector<Task> stack;
    nodes_.push_back({});
    stack.push_back({0, 0, static_cast<uint32_t>(order.size())});
    while (!stack.empty()) {
        Task task = stack.back();
        stack.pop_back();
        Box bounds, cbounds;
        for (uint32_t i = task.first; i < task.first + task.count; ++i) {
            for (const V3& v : triangles_[order[i]].v) grow(bounds, v);
            grow(cbounds, centroids[order[i]]);
        }
        nodes_[task.node].bounds = bounds;
        int axis = 0;
        double extent = -1;
        for (int k = 0; k < 3; ++k)
            if (cbounds.max[k] - cbounds.min[k] > extent) {
                extent = cbounds.max[k] - cbounds.min[k];
                axis = k;
            }
        if (task.count <= kLeafSize || !(extent > 0)) {
            nodes_[task.node].first = task.first;
            nodes_[task.node].count = task.count;
            continue;
        }
        uint32_t half = task.count / 2;
        auto begin = order.begin() + task.first;
        std::nth_element(begin, begin + half, begin + task.count, [&](uint32_t a, uint32_t b) {
            if (centroids[a][axis] != centroids[b][axis]) return centroids[a][axis] < centroids[b][axis];
            return a < b;
        });
        uint32_t left = static_cast<uint32_t>(nodes_.size());
        nodes_.push_back({});
        nodes_.push_back({});
        nodes_[task.node].first = left;
        nodes_[task.node].count = 0;
        nodes_[task.node].right = left + 1;
        stack.push_back({left + 1, task.first + half, task.count - half});
        stack.push_back({left, task.first, half});
    }
    std::vector<Triangle> sorted(triangles_.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = triangles_[order[i]];
    triangles_ = std::move(sorted);
}

ClosestPoint TriangleTree::closest_point(const V3& query, double max_distance) const {
    ClosestPoint best;
    if (nodes_.empty()) return best;
    double best_sq = max_distance * max_distance;
    if (std::isnan(best_sq)) return best;
    // Each node with the squared distance of its box, computed once (when its parent is visited).
    struct Entry {
        uint32_t node;
        double d;
    };
    Entry stack[128];
    int top = 0;
    stack[top++] = {0, squared_distance_to_box(query, nodes_[0].bounds)};
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.d > best_sq) continue;
        const Node& node = nodes_[entry.node];
        if (node.is_leaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Triangle& t = triangles_[i];
                V3 p = closest_point_on_triangle(query, t.v[0], t.v[1], t.v[2]);
                double d = sq(sub(p, query));
                if (d <= best_sq && (!best.found || d < best.squared_distance ||
                                     (d == best.squared_distance && t.index < best.triangle))) {
                    best_sq = d;
                    best.point = p;
                    best.triangle = t.index;
                    best.squared_distance = d;
                    best.found = true;
                }
            }
            continue;
        }
        const Entry left{node.first, squared_distance_to_box(query, nodes_[node.first].bounds)};
        const Entry right{node.right, squared_distance_to_box(query, nodes_[node.right].bounds)};
        if (top + 2 > 128) continue;  // cannot happen for median-split trees of < 2^60 triangles
        // The nearer child last, so that it is visited first; a child already farther than the
        // best is not kept.
        const Entry& nearer = left.d <= right.d ? left : right;
        const Entry& farther = left.d <= right.d ? right : left;
        if (farther.d <= best_sq) stack[top++] = farther;
        if (nearer.d <= best_sq) stack[top++] = nearer;
    }
    return best;
}

double TriangleTree::distance(const V3& query) const {
    ClosestPoint c = closest_point(query);
    return c.found ? std::sqrt(c.squared_distance) : std::numeric_limits<double>::infinity();
}

bool TriangleTree::any_within(const V3& query, double radius) const {
    if (nodes_.empty() || !(radius >= 0)) return false;
    double r2 = radius * radius;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (squared_distance_to_box(query, node.bounds) > r2) continue;
        if (node.is_leaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Triangle& t = triangles_[i];
                if (sq(sub(closest_point_on_triangle(query, t.v[0], t.v[1], t.v[2]), query)) <= r2) return true;
            }
            continue;
        }
        if (top + 2 > 128) continue;
        stack[top++] = node.right;
        stack[top++] = node.first;
    }
    return false;
}

}  // namespace ellicast
