// A static bounding-volume hierarchy over the triangles of a mesh: closest point and unsigned
// distance queries. Built once, then read-only: queries may run from several threads at once.
//
// Used by the encoder (ellipsoid growth, inside tests) and by the decoder's point-to-surface
// distance metric.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace ellicast {

// The answer to a closest-point query.
struct ClosestPoint {
    std::array<double, 3> point{};  // the closest point on the surface
    uint32_t triangle = 0;          // index of its triangle in the input triangle list
    double squared_distance = std::numeric_limits<double>::infinity();
    bool found = false;             // false: no triangle within the query's max distance (or no triangles)
};

class TriangleTree {
public:
    // An axis-aligned box.
    struct Box {
        std::array<double, 3> min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::infinity()};
        std::array<double, 3> max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                  -std::numeric_limits<double>::infinity()};
    };

    // A node of the hierarchy. A leaf covers the triangles [first, first + count) of leaf order
    // (see triangles()); an inner node has count == 0 and children `first` and `right`.
    struct Node {
        Box bounds;
        uint32_t first = 0;  // leaf: first triangle (in leaf order); inner: index of the left child
        uint32_t count = 0;  // leaf: triangle count (> 0); inner: 0
        uint32_t right = 0;  // inner: index of the right child
        bool is_leaf() const { return count > 0; }
    };

    // One triangle in leaf order: its three corners and its index in the input list.
    struct Triangle {
        std::array<std::array<double, 3>, 3> v;
        uint32_t index = 0;
    };

    TriangleTree() = default;

    // Builds the hierarchy. Triangles whose indices point outside `positions` are ignored; so are
    // triangles with a non-finite corner. Degenerate (zero-area) triangles are kept: they are still
    // points or segments of the surface. Deterministic: the same input gives the same tree.
    TriangleTree(std::span<const std::array<float, 3>> positions, std::span<const std::array<uint32_t, 3>> triangles);

    // The closest point of the surface to `query`, searching only within `max_distance` of it
    // (found == false when nothing is that close, or the tree is empty).
    ClosestPoint closest_point(const std::array<double, 3>& query,
                               double max_distance = std::numeric_limits<double>::infinity()) const;

    // Unsigned distance from `query` to the surface (infinity for an empty tree).
    double distance(const std::array<double, 3>& query) const;

    // True when some triangle comes within `radius` of `query` (cheaper than closest_point).
    bool any_within(const std::array<double, 3>& query, double radius) const;

    bool empty() const { return nodes_.empty(); }
    size_t triangle_count() const { return triangles_.size(); }
    // The root is nodes()[0] (when not empty).
    const std::vector<Node>& nodes() const { return nodes_; }
    // The triangles in leaf order.
    const std::vector<Triangle>& triangles() const { return triangles_; }
    // Bounds of the whole surface.
    Box bounds() const { return nodes_.empty() ? Box{} : nodes_[0].bounds; }

private:
    std::vector<Node> nodes_;
    std::vector<Triangle> triangles_;
};

// The point of triangle (a, b, c) closest to p (works for degenerate triangles too).
std::array<double, 3> closest_point_on_triangle(const std::array<double, 3>& p, const std::array<double, 3>& a,
                                                const std::array<double, 3>& b, const std::array<double, 3>& c);

// Squared distance from p to the box (0 inside).
double squared_distance_to_box(const std::array<double, 3>& p, const TriangleTree::Box& box);

}  // namespace ellicast
