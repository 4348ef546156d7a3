// Triangulating one polygonal face (an OBJ, PLY or OFF face of more than three corners) without
// adding points: the triangles cover exactly the polygon, keep its orientation, and are spatially
// local (a large convex part is split in halving rounds, so that a point lies near only a few long
// triangles), which the encoder's winding numbers need to stay fast.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace ellicast {

struct PolygonTriangulation {
    // Triangles as indices into the corners given, each in the polygon's own orientation. Always
    // corners.size() - 2 of them for 3 or more corners (none for fewer).
    std::vector<std::array<uint32_t, 3>> triangles;
    // False when the polygon is not simple in its best-fit plane (self-crossing, self-touching,
    // repeated points, zero area) or could not be triangulated: `triangles` is then the fan from the
    // first corner, as OpenMesh's reader makes it, which may cover area outside the polygon.
    bool simple = false;
};

// Triangulates the polygon whose corners, in order, are `corners` (finite coordinates), projected on
// the plane of their Newell normal. A polygon of at most 32 corners that the fan from its first corner
// triangulates (any convex one) keeps that fan, the triangles OpenMesh made before. Any other simple
// polygon, concave too, is triangulated by clipping ears in rounds (each round clips at most every
// other corner, so a convex run is split hierarchically) or, when that would take more than
// O(n log n) work, by a y-monotone partition. The result is checked (n - 2 triangles, each edge of
// the polygon used once and every inner edge twice in opposite directions, none inverted, at every
// corner the triangles fill exactly its inner angle) and replaced by the fan when the check fails.
// O(n log n) time, O(n) memory, deterministic.
PolygonTriangulation triangulate_polygon(std::span<const std::array<float, 3>> corners);

}  // namespace ellicast
