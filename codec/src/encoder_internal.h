// Private interfaces between the encoder's algorithm files (one algorithm per .cpp).
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/codec/triangle_tree.h"
#include "parallel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

namespace ellicast::detail {

using Vec3 = Eigen::Vector3d;
using V3 = std::array<double, 3>;

inline Vec3 to_vec(const V3& a) { return {a[0], a[1], a[2]}; }
inline V3 to_arr(const Vec3& a) { return {a.x(), a.y(), a.z()}; }

// A deterministic random stream (std::mt19937 is specified exactly; distributions are not).
class Random {
public:
    explicit Random(uint32_t seed) : engine_(seed) {}
    double uniform() { return (engine_() >> 5) * (1.0 / 134217728.0); }  // [0, 1) with 27 bits
    uint32_t below(uint32_t n) { return uint32_t(uniform() * n); }

private:
    std::mt19937 engine_;
};

// ---------------------------------------------------------------------------------------------
// winding_number.cpp

// Generalized winding number of a triangle soup (Jacobson et al. 2013), evaluated fast with the
// tree's hierarchy and a dipole far-field approximation (Barill et al. 2018). About 1 inside a
// closed outward-oriented surface, 0 outside, in between near holes.
class WindingNumber {
public:
    explicit WindingNumber(const TriangleTree& tree, double accuracy = 2.0);
    double operator()(const V3& q) const;

private:
    struct NodeDipole {
        V3 center{};      // area-weighted centroid
        V3 normal{};      // sum of area-weighted normals
        double radius2 = 0;  // squared radius of a ball around center holding the node
    };
    const TriangleTree& tree_;
    double beta2_;
    std::vector<NodeDipole> dipoles_;
};

// Winding numbers at the centres of a regular voxel grid.
struct VoxelGrid {
    int n[3] = {0, 0, 0};
    V3 origin{};       // centre of voxel (0,0,0)
    double h = 1;      // voxel edge
    std::vector<float> w;  // winding number per voxel, x fastest

    size_t index(int x, int y, int z) const { return (size_t(z) * n[1] + y) * n[0] + x; }
    size_t size() const { return size_t(n[0]) * n[1] * n[2]; }
    bool inside(size_t i) const { return w[i] > 0.5f; }
    // Trilinear interpolation of the winding number (0 outside the grid).
    double sample(const Vec3& p) const;
};

// Lays a grid over `box` with `cells` voxels along its longest side (plus a one-voxel margin)
// and evaluates the winding number at every voxel centre; blocks far from the surface whose
// corners agree are filled without evaluating every voxel.
VoxelGrid build_winding_grid(const TriangleTree& tree, const WindingNumber& winding, const TriangleTree::Box& box,
                             int cells, unsigned threads, const std::function<void(double)>& progress);

// The same grid for a surface without boundary (every edge matched by an edge in the opposite
// direction): exact integer winding numbers from signed ray crossings, one ray per row of voxels,
// far cheaper than evaluating the winding number at each voxel.
VoxelGrid build_closed_winding_grid(const TriangleTree& tree, const TriangleTree::Box& box, int cells,
                                    unsigned threads);

// ---------------------------------------------------------------------------------------------
// ellipsoid_growth.cpp

struct Candidate {
    Vec3 center = Vec3::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // column i: direction of semi-axis i
    Vec3 radii = Vec3::Zero();
    double volume() const { return 4.18879020478639 * radii.x() * radii.y() * radii.z(); }
};

// Balls around the nodes and triangles of a TriangleTree, for tests against an ellipsoid: per node
// (index order) the centre of its box and half its diagonal, per triangle (leaf order) its centroid
// and the distance to its farthest corner.
struct TreeBalls {
    std::vector<std::array<double, 4>> nodes, triangles;
    // Per triangle (leaf order): the unit normal n of its plane, the offset n . a of its first corner
    // and how far its other corners lie off that plane as computed (the slab holding it), or all
    // zero for a triangle without a normal.
    std::vector<std::array<double, 5>> planes;
    // Per node: the triangles below it, [first, end) in leaf order (a node's triangles are a run).
    std::vector<std::array<uint32_t, 2>> spans;
    // Per node: a slab holding its triangles, across their mean normal: the unit direction n and
    // the least and greatest n . x over their corners (all zero where the normals cancel).
    std::vector<std::array<double, 5>> slabs;
};

struct GrowthContext {
    const TriangleTree& tree;
    const VoxelGrid& grid;
    const WindingNumber& winding;
    bool closed = false;    // no boundary edges: the exact surface test alone proves insideness
    double min_radius = 0;  // smaller spheres are not worth a candidate
    // Per tree node: area, area-weighted centroid sum and second moments (for local PCA).
    std::vector<std::array<double, 10>> node_moments;
    // Per triangle (leaf order): its area (its centroid is its ball's centre, balls.triangles).
    std::vector<double> areas;
    // Balls around the tree's nodes and triangles (see clear_of_surface).
    TreeBalls balls;
};

// Fills ctx.node_moments from the tree.
void prepare_growth(GrowthContext& ctx);

// The triangles (in leaf order) that stopped the last few tries of one growth. A stretch tries each
// axis and end in turn, and each is usually stopped by the triangle that stopped it the time before:
// tested first, they settle most failing tries without a search. They only speed the answer up.
struct Blockers {
    static constexpr uint32_t kSize = 8;
    std::array<uint32_t, kSize> triangles{};
    uint32_t count = 0, next = 0;
    void add(uint32_t t) {
        triangles[next] = t;
        next = (next + 1) % kSize;
        count = std::min(count + 1, kSize);
    }
};

// True when the solid ellipsoid meets no triangle (exact, in double precision: no triangle for which
// ellipsoid_meets_triangle holds, whatever the tree's grouping and the shortcuts). `blockers`, when
// given, are tested first, and the triangle found in the way joins them. `balls`, when given, are
// the tree's (tree_balls): a triangle whose ball clearly misses the ellipsoid is not tested, and a
// node's ball is not computed again at every visit (the answer is the same, found sooner).
bool clear_of_surface(const TriangleTree& tree, const Candidate& e, Blockers* blockers = nullptr,
                      const TreeBalls* balls = nullptr);

// The test clear_of_surface applies to each triangle: the solid ellipsoid meets the triangle.
bool ellipsoid_meets_triangle(const Candidate& e, const TriangleTree::Triangle& t);

// The balls of every node and triangle of the tree.
TreeBalls tree_balls(const TriangleTree& tree);

// True when the ellipsoid is inside the model: clear of the surface, centre inside, and (for an
// open surface) not leaking out through a hole (checked on the winding grid).
bool ellipsoid_inside(const GrowthContext& ctx, const Candidate& e, Blockers* blockers = nullptr);

// Grows a candidate from surface point `p` with unit inward normal `n`: a sphere tangent at p
// grown until it touches the surface elsewhere, then stretched axis by axis (moving its centre
// when that helps) while it stays inside. False when no sphere of min_radius fits.
bool grow_ellipsoid(const GrowthContext& ctx, const Vec3& p, const Vec3& n, Candidate& out);

// Grows a flat candidate from surface point `p` with unit inward normal `n`: a ball of radius
// `thickness` tangent at p (smaller if that does not fit), stretched only along the surface (its
// axes those of the local surface turned by `turn` radians about n), so that it hugs the surface
// and fills the thin layer under it that large ellipsoids leave.
bool grow_flat(const GrowthContext& ctx, const Vec3& p, const Vec3& n, double thickness, double turn,
               Candidate& out);

// ---------------------------------------------------------------------------------------------
// ellipsoid_selection.cpp

// The voxels of a grid whose centres are inside an ellipsoid, as runs along x: (row, x0, x1).
struct Span {
    uint32_t row;  // y + z * ny
    uint16_t x0, x1;  // [x0, x1)
};
std::vector<Span> rasterize(const VoxelGrid& grid, const Candidate& e, double inflate = 0);

// Voxel bitset over a grid, one row of words per (y, z).
class VoxelBits {
public:
    VoxelBits(const VoxelGrid& grid, bool value);
    void set(size_t x, size_t row, bool v);
    bool get(size_t x, size_t row) const;
    size_t count(const std::vector<Span>& spans) const;  // set bits under the spans
    void clear(const std::vector<Span>& spans);
    void fill(const std::vector<Span>& spans);
    size_t count_all() const;

private:
    size_t words_per_row_;
    std::vector<uint64_t> bits_;
};

struct SelectionResult {
    std::vector<uint32_t> volume;   // candidate indices chosen for volume, in order
    std::vector<uint32_t> surface;  // candidate indices chosen for surface coverage
    double coverage = 0;            // covered fraction of interior voxels by the chosen ones (measuring grid)
};

// What select_ellipsoids works out per candidate, kept between calls over the same grids, surface
// samples and `near` whose candidate list only grows (an encoder's rounds): each candidate's runs
// of voxels on the working and the measuring grid, and the surface samples near it.
struct SelectionCache {
    std::vector<std::vector<Span>> spans;          // on the working grid
    std::vector<std::vector<Span>> fine_spans;     // on the measuring grid, where fine_done
    std::vector<char> fine_done;
    // The interior voxels under each candidate's runs (its first gain, the same in every call).
    std::vector<size_t> interior_under;  // of the first interior_under.size() candidates
    std::vector<std::vector<uint32_t>> near_samples;  // of the first near_samples.size() candidates
};

// Greedy: the largest candidate first, then the one with the largest gain of covered interior
// voxels, until `coverage` or `max_volume`; then, until `max_count` in all, the candidate covering
// the most surface samples still farther than `near` from every chosen ellipsoid. Gains are
// counted on `grid`; the coverage (when to stop, and the result's) on `measure` when given (a
// finer grid over the same model: a truer measure than the working grid's voxel centres). With a
// `cache`, what an earlier call worked out for the same candidates is not worked out again. Its
// candidates' runs and near samples are found with `threads` threads (the result does not depend on it).
SelectionResult select_ellipsoids(const VoxelGrid& grid, const VoxelGrid* measure,
                                  const std::vector<Candidate>& candidates, const std::vector<Vec3>& surface_samples,
                                  double near, double coverage, uint32_t max_volume, uint32_t max_count,
                                  const std::function<void(double)>& progress, SelectionCache* cache = nullptr,
                                  unsigned threads = 2);

// ---------------------------------------------------------------------------------------------
// sheet_ellipsoids.cpp

// Flat ellipsoids straddling sheet-like surface: the samples listed in `sheet` (indices into
// `samples`, with unit `normals` and the connected `part` of the mesh each lies on), clustered
// within 4h (more when `max_count` discs cannot cover them all) among samples of one part, one disc
// about h thick per cluster, at most `max_count`, in the order of `sheet`.
std::vector<Candidate> sheet_ellipsoids(const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                                        const std::vector<uint32_t>& part, const std::vector<uint32_t>& sheet,
                                        double h, size_t max_count);

// Points inside the triangles of `tree` with an edge longer than 2h, on a lattice about h apart
// (corners left out: the vertices are samples already), with the triangle's unit normal and input
// index: surface that vertex samples miss on a low-poly sheet. Only triangles whose input index is
// marked in `allowed` (all when it is empty). At most about `max_count` (the lattice widens).
void face_samples(const TriangleTree& tree, const std::vector<char>& allowed, double h, size_t max_count,
                  std::vector<Vec3>& points, std::vector<Vec3>& normals, std::vector<uint32_t>& triangles);

// The connected parts of `mesh` (triangles joined through vertices welded by `weld`): the part of
// each vertex and of each triangle (a part is named by one of its vertices), and per part name
// whether it has a boundary (an edge of one triangle). A closed part has an inside and no sheet,
// however open the rest of the mesh is.
struct MeshParts {
    std::vector<uint32_t> of_vertex, of_triangle;
    std::vector<char> open;
};
MeshParts mesh_parts(const Mesh& mesh, const std::vector<uint32_t>& weld);

// ---------------------------------------------------------------------------------------------
// orientation.cpp

struct OrientationReport {
    size_t parts = 0;                 // parts joined across manifold edges
    size_t reversed_parts = 0;        // parts whose every triangle was turned (they faced the wrong way)
    size_t mended_parts = 0;          // parts of which only some triangles were turned (they disagreed)
    size_t turned_faces = 0;          // triangles turned in all
    size_t non_orientable_parts = 0;  // parts that cannot agree with themselves (left as found)
    size_t cavities = 0;              // closed parts inside an odd number of others (facing inward)
    bool nesting_unchecked = false;   // the bound on ray tests was reached: some nesting not counted
};

// The mesh's triangles, each part turned to agree with itself and to face outward (a cavity's
// wall inward); triangles already right keep their corner order. `weld` maps each vertex to the
// first vertex at its position.
std::vector<std::array<uint32_t, 3>> orient_outward(const Mesh& mesh, const std::vector<uint32_t>& weld,
                                                     OrientationReport& report);

// ---------------------------------------------------------------------------------------------
// point_order.cpp

// An order of `positions` (distinct points) in which every prefix, and every run of consecutive
// points, is spread evenly: coarse-to-fine levels of a voxel hierarchy, shuffled within a level.
std::vector<uint32_t> spread_order(const std::vector<std::array<uint32_t, 3>>& positions, int bits, uint32_t seed);

}  // namespace ellicast::detail
