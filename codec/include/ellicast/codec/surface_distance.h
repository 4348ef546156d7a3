// Distance between two surfaces, measured the way Metro and MeshLab's Hausdorff filter do: dense
// samples on one surface, the closest point of the other (point to triangle, through a bounding
// volume hierarchy), in both directions.
#pragma once

#include "ellicast/codec/mesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ellicast {

struct SurfaceDistanceOptions {
    size_t samples = 0;                // samples per direction; 0 = 10 per triangle, within [100k, 2M]
    double threshold_percent = 0.5;    // "far" threshold, in % of A's bounding-box diagonal
    uint64_t seed = 1;                 // samples are deterministic for a seed
    unsigned threads = 0;              // 0 = all hardware threads
};

// Distances from samples of one surface to the other surface.
struct DirectedDistance {
    size_t samples = 0;
    double max = 0;         // Hausdorff distance in this direction (samples and vertices)
    double mean = 0;
    double rms = 0;
    double far_fraction = 0;  // fraction of the sampled surface's area farther than the threshold
};

struct SurfaceDistance {
    double diagonal = 0;    // bounding-box diagonal of A (percentages are relative to it)
    double threshold = 0;   // the far threshold, absolute
    DirectedDistance a_to_b, b_to_a;
    double hausdorff() const { return a_to_b.max > b_to_a.max ? a_to_b.max : b_to_a.max; }
    double percent(double value) const { return diagonal > 0 ? 100.0 * value / diagonal : 0; }
};

// Area-uniform random samples on the triangles of `meshes` (point sets contribute nothing):
// each triangle receives a number of samples proportional to its area (the fractional part decided
// by the seeded generator), spread uniformly inside it. Deterministic for a seed.
std::vector<std::array<double, 3>> sample_surface(const std::vector<Mesh>& meshes, size_t count, uint64_t seed);

// Bounding-box diagonal of the vertices of `meshes`.
double bounding_box_diagonal(const std::vector<Mesh>& meshes);

// Measures A against B in both directions. Returns false with `error` when either side has no
// triangle (a point set has no surface to measure against).
bool surface_distance(const std::vector<Mesh>& a, const std::vector<Mesh>& b, const SurfaceDistanceOptions& options,
                      SurfaceDistance& out, std::string& error);

}  // namespace ellicast
