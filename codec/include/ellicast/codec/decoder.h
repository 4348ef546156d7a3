// The decoder: rebuilds a surface from whatever ellipsoids and surface points of an object arrived,
// as spec/format.md section 13 (Reconstruction, informative) describes; an object whose every point
// and whole exact layer arrived comes back as its original triangles instead (section 19.4), with
// the surface normals of section 24.3 where its points left them to the surface.
//
// Pipeline (Bischoff & Kobbelt 2002), one algorithm per source file:
//   rasterize.cpp        ellipsoids -> a grid of clamped signed distances (sign = inside/outside)
//   marching_cubes.cpp   grid -> closed, consistently oriented OpenMesh triangle mesh (the base)
//   face_grid.cpp        a uniform grid of faces: nearest triangle while the mesh changes
//   point_insertion.cpp  each point goes into its nearest triangle (1-to-3 or edge split)
//   edge_flip.cpp        local flips after each insertion (min angle where flat, smoothness where curved)
//   mc_collapse.cpp      marching-cubes vertices collapse into original vertices once enough arrived
//   normal_repair.cpp    at the end, faces are made to agree with the received normals (creases, corners)
//   decoder.cpp          a whole object / stream, attribute transfer, snapshots, progress, timings
//
// Everything here is deterministic: the same ellipsoids and points (in any order, with duplicate
// ellipsoids) give the same mesh, bit for bit. Points are inserted in the order of the received list
// (index order) on an object with normals, otherwise in the bit-reversed order of their place in it.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace ellicast {

// The decoder's mutable mesh (double precision: insertion and flips compare small angles).
struct DecoderMeshTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
};
using DecoderTriMesh = OpenMesh::TriMesh_ArrayKernelT<DecoderMeshTraits>;

// Whether collapsing halfedge h keeps the mesh manifold, by the link condition checked directly:
// the vertices next to both ends are exactly the apexes of the edge's faces and no other face holds
// both ends. OpenMesh's is_collapse_ok alone lets through collapses that leave faces with a repeated
// vertex (found by fuzz_decode: a later insertion into such a face read past an edge array).
bool collapse_link_ok(DecoderTriMesh& mesh, OpenMesh::HalfedgeHandle h);

// ---------------------------------------------------------------------------------------------
// Rasterization (rasterize.cpp)

inline constexpr int kDefaultGridResolution = 96;  // cells along the frame's edge when nothing else is asked
inline constexpr int kMinGridResolution = 4;
inline constexpr int kMaxGridResolution = 1024;
inline constexpr size_t kMaxGridNodes = size_t(48) << 20;  // ~200 MB of floats: refuse larger grids
inline constexpr size_t kBaseGridNodesInAll = size_t(1) << 24;  // the base allowance, over all objects

// A grid of nodes over the part of an object's frame that its ellipsoids cover (plus one cell).
// value > 0 inside the union of ellipsoids, <= 0 outside. Each value is the largest, over the
// ellipsoids whose bounding box holds the node, of the signed distance to that ellipsoid measured
// along the ray from its centre (exact for spheres), clamped below at -cell.
struct EllipsoidGrid {
    std::array<double, 3> origin{};  // position of node (0,0,0)
    double cell = 1;                 // node spacing
    std::array<int, 3> nodes{};      // node counts along x, y, z
    std::vector<float> value;        // x fastest, then y, then z

    size_t index(int i, int j, int k) const { return (size_t(k) * nodes[1] + j) * nodes[0] + i; }
    bool empty() const { return value.empty(); }
};

// Rasterizes `ellipsoids` with node spacing frame.scale / resolution. Only nodes inside each
// ellipsoid's bounding box (grown by one cell) are visited. The result does not depend on the order
// of the ellipsoids nor on duplicates. Degenerate ellipsoids (a radius <= 0 or a non-finite value)
// are skipped and counted in `skipped`. Returns false with `error` set when the grid would exceed
// kMaxGridNodes or the resolution is out of [kMinGridResolution, kMaxGridResolution]; an empty grid
// (no usable ellipsoid) is not an error. With `threads` > 1 the grid's slabs along z are drawn side
// by side (each node takes the largest value of the ellipsoids over it, so the result is the same).
bool rasterize_ellipsoids(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution,
                          EllipsoidGrid& out, std::string& error, size_t* skipped = nullptr, unsigned threads = 1);

// The node count of the grid rasterize_ellipsoids would build (0 when no ellipsoid is usable,
// SIZE_MAX when it would overflow), without building it.
size_t ellipsoid_grid_nodes(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution);
// What rasterize_ellipsoids would visit at `resolution`: the nodes of every usable ellipsoid's
// bounding box (with the margin it draws), summed; an upper bound of its work.
double ellipsoid_raster_work(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution);

// ---------------------------------------------------------------------------------------------
// Marching cubes (marching_cubes.cpp)

// Extracts the zero level set of `grid` as a closed 2-manifold triangle mesh whose faces are
// oriented outwards (away from the inside). Vertices lie on grid edges. Deterministic. Face
// ambiguities are resolved by separating the inside corners, identically from both cells, so the
// mesh has no cracks. The returned mesh has vertex, edge and face status attributes requested.
DecoderTriMesh marching_cubes(const EllipsoidGrid& grid);

// ---------------------------------------------------------------------------------------------
// Nearest triangle while the mesh changes (face_grid.cpp)

// A uniform grid of cells, each listing the faces whose bounding box overlaps it. Faces are
// (re)registered after every change; stale entries are skipped by a per-face version and dropped
// from a cell whenever it would grow, so cells stay small and queries fast as the mesh is refined.
class FaceGrid {
public:
    // Covers [lo, hi] (points outside are clamped to the border cells) with cells of edge `cell`,
    // coarsened until there are at most `max_cells` cells (and never more than 4M).
    void reset(const OpenMesh::Vec3d& lo, const OpenMesh::Vec3d& hi, double cell, size_t max_cells = size_t(4) << 20);
    // Registers every live face of `mesh`.
    void build(const DecoderTriMesh& mesh);
    // (Re)registers face `f` at its current position; call after any change to its vertices.
    void update(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f);
    // Forgets face `f` (call when it is deleted).
    void remove(OpenMesh::FaceHandle f);
    // The live face nearest to p (invalid handle when the mesh has no face), its closest point and
    // the barycentric coordinates of that point. With `accept`, only faces it accepts count; with
    // `max_distance`, only faces closer than that (else an invalid handle, without a wider search).
    OpenMesh::FaceHandle nearest(const DecoderTriMesh& mesh, const OpenMesh::Vec3d& p, OpenMesh::Vec3d& closest,
                                 std::array<double, 3>& bary,
                                 const std::function<bool(OpenMesh::FaceHandle)>& accept = {},
                                 double max_distance = std::numeric_limits<double>::max()) const;
    size_t live_faces() const { return live_; }
    size_t cell_count() const { return cells_.size(); }
    double cell_size() const { return cell_; }

private:
    struct Entry {
        uint32_t face;
        uint32_t version;
    };
    size_t cell_of(int i, int j, int k) const { return (size_t(k) * dims_[1] + j) * dims_[0] + i; }
    void cell_range(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f, std::array<int, 3>& lo,
                    std::array<int, 3>& hi) const;
    void add_entries(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f);

    OpenMesh::Vec3d lo_{0, 0, 0};
    double cell_ = 1;
    std::array<int, 3> dims_{1, 1, 1};
    std::vector<std::vector<Entry>> cells_;
    std::vector<uint32_t> version_;    // per face; even = not registered, odd = registered
    mutable std::vector<uint32_t> seen_;  // per face: query stamp
    mutable uint32_t stamp_ = 0;
    size_t live_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The vertices put at each exact position, in the order they were put there (seam detection): an
// open-addressing table of 64-bit position keys, each the head of a list in one shared pool (no
// allocation per point, unlike a map of vectors).
class PositionIndex {
public:
    static constexpr int32_t kEnd = -1;
    void clear() {
        slots_.clear();
        pool_.clear();
        used_ = 0;
    }
    void reserve(size_t positions) {
        pool_.reserve(positions);
        size_t want = 16;
        while (want < 2 * positions) want *= 2;
        if (want > slots_.size()) rehash(want);
    }
    // The first node of the list at `key` (kEnd when none); walk it with vertex() and next().
    int32_t first(uint64_t key) const {
        if (slots_.empty()) return kEnd;
        for (size_t i = slot_of(key);; i = (i + 1) & (slots_.size() - 1)) {
            const Slot& s = slots_[i];
            if (s.head == kEnd) return kEnd;
            if (s.key == key) return s.head;
        }
    }
    OpenMesh::VertexHandle vertex(int32_t node) const { return OpenMesh::VertexHandle(pool_[size_t(node)].vertex); }
    int32_t next(int32_t node) const { return pool_[size_t(node)].next; }
    // Appends v to the list at `key`.
    void add(uint64_t key, OpenMesh::VertexHandle v) {
        if (2 * (used_ + 1) > slots_.size()) rehash(std::max<size_t>(16, 2 * slots_.size()));
        const int32_t node = int32_t(pool_.size());
        pool_.push_back({v.idx(), kEnd});
        for (size_t i = slot_of(key);; i = (i + 1) & (slots_.size() - 1)) {
            Slot& s = slots_[i];
            if (s.head == kEnd) {
                s = {key, node, node};
                ++used_;
                return;
            }
            if (s.key == key) {
                pool_[size_t(s.tail)].next = node;
                s.tail = node;
                return;
            }
        }
    }

private:
    struct Slot {
        uint64_t key = 0;
        int32_t head = kEnd, tail = kEnd;
    };
    struct Node {
        int vertex;
        int32_t next;
    };
    size_t slot_of(uint64_t key) const { return size_t((key * 0x9E3779B97F4A7C15ull) >> 17) & (slots_.size() - 1); }
    void rehash(size_t size) {
        std::vector<Slot> old = std::move(slots_);
        slots_.assign(size, Slot{});
        for (const Slot& s : old) {
            if (s.head == kEnd) continue;
            size_t i = slot_of(s.key);
            while (slots_[i].head != kEnd) i = (i + 1) & (slots_.size() - 1);
            slots_[i] = s;
        }
    }
    std::vector<Slot> slots_;
    std::vector<Node> pool_;
    size_t used_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The progressive reconstruction shared by insertion, flips and collapses

struct ReconstructionOptions {
    double flat_angle_degrees = 20;    // dihedral angle under which a region counts as flat
    double foldover_degrees = 80;      // a flip/collapse may not turn a face normal further than this
    // A marching-cubes vertex goes once an original neighbour is closer than this many times the
    // spacing the complete stream's points will have (or once it has collapse_min_originals
    // original neighbours making up collapse_min_fraction of its neighbours).
    double collapse_spacing_factor = 1.0;
    int collapse_min_originals = 3;
    double collapse_min_fraction = 0.5;
    int max_flips_per_insertion = 64;
};

struct Reconstruction {
    DecoderTriMesh mesh;                          // with vertex/edge/face status
    FaceGrid faces;                               // nearest-face index over `mesh`
    std::vector<std::vector<uint32_t>> vertex_points;  // per vertex: indices of the points at it ({} = MC vertex)
    PositionIndex by_position;                    // seam detection: the vertices put at each position
    size_t mc_vertices = 0;                       // marching-cubes vertices still in the mesh
    double point_spacing = 0;                     // expected edge length once every point arrived (0: unknown)
    double spacing_scale = 1;                     // > 1 at the end of an incomplete stream: its real spacing
    size_t original_vertices = 0;
    ReconstructionOptions options;
    // The received points when they carry normals (else null), and per point whether it lies on a
    // sheet (points_on_sheets; may be null): agree_with_received_normals reads them.
    const std::vector<SurfacePoint>* normals = nullptr;
    const std::vector<char>* sheet_points = nullptr;

    // Counters
    size_t face_splits = 0, edge_splits = 0, vertex_moves = 0, seam_merges = 0, flips = 0, collapses = 0,
           rejected_collapses = 0;

    // True while `faces` is not kept up to date (collapse_all_mc_vertices: no insertion follows it,
    // and re-indexing the large faces of a sparse stream's last collapses would cost more than the
    // collapses); insert_point rebuilds the index first when it is set.
    bool index_paused = false;

    // The face index covers [index_lo, index_hi] with cells of about index_cell, but never more cells
    // than 16 per face the mesh has when it is built (at least 4,096): its memory and the empty cells a
    // search walks follow what the stream carried, not the object's frame or the count it declares.
    // It is built again, finer, each time the mesh has grown fourfold.
    OpenMesh::Vec3d index_lo{0, 0, 0}, index_hi{0, 0, 0};
    double index_cell = 1;
    size_t index_built_for = 0;  // faces the mesh had when the index was last laid out
    void rebuild_index();
    // Rebuilds the index when it is paused, or coarser than wanted and the mesh has grown fourfold.
    void refresh_index();

    bool is_original(OpenMesh::VertexHandle v) const { return !vertex_points[v.idx()].empty(); }
    // Keep the face index in step with a changed or deleted face.
    void face_changed(OpenMesh::FaceHandle f) {
        if (!index_paused) faces.update(mesh, f);
    }
    void face_removed(OpenMesh::FaceHandle f) {
        if (!index_paused) faces.remove(f);
    }
};

// Takes ownership of a base mesh (from marching_cubes with node spacing `cell`): builds the face
// index over `frame` (grown to cover the mesh), its cells sized for the triangles that
// `expected_points` insertions will leave, and marks every vertex as a marching-cubes vertex.
void start_reconstruction(Reconstruction& r, DecoderTriMesh&& base, const Frame& frame, double cell,
                          size_t expected_points, const ReconstructionOptions& options);

// Re-registers every face around v in r.faces (after v moved or its faces changed).
void reindex_faces_around(Reconstruction& r, OpenMesh::VertexHandle v);

// ---------------------------------------------------------------------------------------------
// Point insertion (point_insertion.cpp)

enum class Insertion : uint8_t {
    FaceSplit,     // the point fell inside its nearest triangle: 1-to-3 split
    EdgeSplit,     // it fell on (near) an edge: the edge was split (2-to-4, or 1-to-2 on a border)
    VertexMoved,   // it fell on a marching-cubes vertex, which became this original vertex
    SeamDuplicate, // an original vertex already had this exact position: one more attribute set
    NoMesh,        // the mesh has no face
};

// Inserts SurfacePoint number `point_index` at `position` into its nearest triangle and returns
// what happened; `vertex` receives the vertex that now carries the point. Does not flip.
Insertion insert_point(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                       OpenMesh::VertexHandle& vertex);

// Inserts the point into face f at barycentric coordinates `bary` (those of FaceGrid::nearest: an
// edge split near an edge, the marching-cubes corner moved onto it, else a 1-to-3 split).
Insertion insert_into_face(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                           OpenMesh::FaceHandle f, const std::array<double, 3>& bary,
                           OpenMesh::VertexHandle& vertex);

// ---------------------------------------------------------------------------------------------
// Sheets (sheet_sides.cpp)

// For each point, whether it lies on a sheet: in the middle of one of the flat ellipsoids (thinner
// than two grid cells, twice as wide as thick both ways) that an encoder lays across surface
// with no inside, where no ellipsoid kept inside a surface could hold a point of it. The base there
// is a thin closed shell, both of whose sides stand for the same surface.
std::vector<char> points_on_sheets(const std::vector<Ellipsoid>& ellipsoids, double cell,
                                   const std::vector<SurfacePoint>& points);

// A sheet point already inserted at `first` goes into the shell's other side as well: into the
// nearest face behind `first` (facing the other way, within `reach`), as a second vertex at the
// same position. Returns false (and leaves the mesh alone) when there is no such face.
bool insert_on_other_side(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                          OpenMesh::VertexHandle first, double reach, OpenMesh::VertexHandle& vertex);

// The end of a complete stream: the marching-cubes vertices that remain on the shell of a flat
// ellipsoid (where the thin base wraps round a sheet's edge, beyond its last points) go with their
// faces; the sheet's other side still covers what such a face covered inside it. The mesh may
// become open, as the sheet is. A vertex whose removal would leave an original vertex without a
// face moves onto its nearest original neighbour instead. Returns the number of vertices removed.
size_t remove_sheet_leftovers(Reconstruction& r, const std::vector<Ellipsoid>& ellipsoids, double cell);

// ---------------------------------------------------------------------------------------------
// Edge flips (edge_flip.cpp)

// Flips edges around vertex v until no flip improves: where the two faces of an edge are nearly
// flat (dihedral under options.flat_angle_degrees) towards a larger minimum angle; where curved,
// towards a smaller total angle between neighbouring normals over the quad's five edges (so edges
// follow creases), never turning a face by more than options.foldover_degrees. Returns the number
// of flips.
size_t flip_edges_around(Reconstruction& r, OpenMesh::VertexHandle v);

// ---------------------------------------------------------------------------------------------
// Agreement with the received normals (normal_repair.cpp)

// For the end of a complete stream whose points carry normals (r.normals; does nothing without):
// puts right the faces that disagree with the normals their corners received (more than 30
// degrees from all of them), which nearest-triangle insertion leaves where the base is rounded off
// (faces across a crease, corners turned inside out, folds). First flips that halve a pair's
// disagreement; then faces with an edge longer than 8 point spacings (the walls of a tunnel the
// ellipsoids left through the object) are cut out and their rims filled; then, for a few rounds
// while it keeps converging, the vertices of disagreeing faces are collapsed away and inserted
// again into the nearest face that agrees with their normals (not when more than a fifth of the
// faces disagree: the mesh is then wrong throughout, not locally, and that does not converge).
// Normals are read the way most of the mesh's faces face (an open surface's may face into the
// volume), both ways for sheet points; a vertex whose normals its neighbours do not fit (normals
// smoothed across a crease) has no say. Returns the number of vertices inserted again.
size_t agree_with_received_normals(Reconstruction& r);

// ---------------------------------------------------------------------------------------------
// Collapse of marching-cubes vertices (mc_collapse.cpp)

// Looks at the marching-cubes vertices next to v and collapses each into its nearest original
// neighbour once enough originals arrived around it (an original neighbour within
// options.collapse_spacing_factor * point_spacing, or options.collapse_min_* original neighbours),
// when the collapse is topologically legal and turns no face by more than options.foldover_degrees;
// then the marching-cubes neighbours of the vertex collapsed into, in turn. Returns the number of
// collapses.
size_t collapse_mc_vertices_near(Reconstruction& r, OpenMesh::VertexHandle v);

// Tries every remaining marching-cubes vertex. With `force`, any original neighbour is enough and
// vertices with none collapse into a marching-cubes neighbour, pass after pass, so that a fully
// received stream ends with original vertices only; a vertex no collapse can remove gets a link edge
// flipped towards it first (only topologically impossible collapses stay). When the marching-cubes
// vertices outnumber the originals 4 to 1, the forced stages skip the flips after each collapse and
// one flip pass follows, so that a sparse stream's end costs about as much as its base.
// Meant for the end of a stream: it leaves r.faces out of date (r.index_paused) and a later
// insert_point rebuilds it.
size_t collapse_all_mc_vertices(Reconstruction& r, bool force);

// ---------------------------------------------------------------------------------------------
// Whole objects and streams (decoder.cpp)

// Stage timings in seconds.
struct DecodeTimings {
    double rasterize = 0;
    double marching_cubes = 0;
    double insertion = 0;  // insertions with their flips and collapses
    double cleanup = 0;    // final collapse pass
    double output = 0;     // building the output mesh (attribute transfer)
    double total() const { return rasterize + marching_cubes + insertion + cleanup + output; }
};

struct DecodeOptions {
    int grid_resolution = 0;     // cells along the frame edge; 0 = the stream's grid_hint, else default
    // Work bound (spec 13): unless grid_resolution is given, an object's grid has at most
    // base_grid_nodes + grid_nodes_per_element * (ellipsoids + points received) nodes, the
    // resolution lowered until it fits, so that a stream's cost follows what it carries (ten
    // one-ellipsoid objects once took 5 s, 381 MB and a 62 MB .glb at the stream's grid hint).
    // decode_stream shares kBaseGridNodesInAll out over the objects for base_grid_nodes.
    size_t base_grid_nodes = size_t(1) << 18;
    size_t grid_nodes_per_element = 2048;
    // The same for the rasterizer's work (ellipsoid_raster_work): ellipsoids that each cover much of
    // the object cost their volume each (100,000 of them in 2.2 MB took over 120 s). Honest bases
    // visit a few million nodes (the bunny 13.8 million at its grid hint of 98, fandisk 8.4); the
    // resolution is lowered until the work is at most base_raster_work + raster_work_per_element *
    // (ellipsoids + points received).
    double base_raster_work = double(1u << 26);
    double raster_work_per_element = 1024;
    // The size of a partial reconstruction: an object whose points have not all arrived is written
    // with at most max(min_faces, faces_per_point * point_count) triangles (point_count from its
    // stream info; a closed mesh has about 2 a point), the base's filler simplified by the quadric
    // error and every received point kept. A 12-triangle cube came back as 60,000 triangles, the
    // 2CylinderEngine's 1.8 MB after one cycle at 50% loss as a 73 MB glTF. 0: no limit.
    double faces_per_point = 4;
    size_t min_faces = 5000;
    size_t snapshot_every = 0;   // > 0: call `snapshot` for the base and after every N inserted points
    // The exact layer (format 1.3, spec 19): an object whose every point and whole connectivity
    // arrived is written as its original triangles. false: always the reconstruction. Not used with
    // snapshot_every > 0: snapshots follow the reconstruction as points arrive.
    bool exact = true;
    // Objects reconstructed side by side (results do not depend on it; 1 with snapshots).
    unsigned threads = 2;
    ReconstructionOptions reconstruction;
    // Progress of the current stage: (stage name, fraction 0..1). May be empty.
    std::function<void(const std::string& stage, double fraction)> progress;
    // A snapshot of object `object` after `points` points (0 = the base). May be empty.
    std::function<void(size_t object, size_t points, const Mesh& mesh)> snapshot;
    // When given, no point is inserted past this moment: the object is finished with the points
    // inserted so far (a note says how many), so that a receiver's deadline bounds its last decode.
    std::optional<std::chrono::steady_clock::time_point> deadline;
    // A region of interest (decode --region): a point for which this returns false (object index,
    // dequantized position in the object's frame) is held, not inserted; an object's exact layer,
    // when whole, is still used. Empty: every point is inserted.
    std::function<bool(size_t object, const std::array<float, 3>& position)> insert_if;
};

struct ObjectDecodeReport {
    size_t ellipsoids = 0;           // received
    size_t skipped_ellipsoids = 0;   // degenerate ones
    size_t points = 0;               // received
    size_t base_vertices = 0, base_faces = 0;
    size_t vertices_out = 0, faces_out = 0;
    size_t mc_vertices_left = 0;     // marching-cubes vertices still in the output
    size_t simplified_faces = 0;     // triangles of the base's filler simplified away (DecodeOptions::faces_per_point)
    size_t face_splits = 0, edge_splits = 0, vertex_moves = 0, seam_merges = 0, flips = 0, collapses = 0;
    size_t sheet_points = 0;   // points also inserted into the other side of a sheet's thin base
    bool complete = false;           // every declared point arrived
    bool has_surface = false;        // false: output is a point set (no ellipsoids, or a PointSet object)
    int grid_resolution = 0;         // the resolution of the grid the base was built on (0: none)
    bool exact = false;              // written as its original triangles (the exact layer, spec 19)
    bool has_connectivity = false;   // the stream carries its exact layer (some of it arrived)
    uint64_t connectivity_bytes = 0, connectivity_size = 0;  // bytes of it received, of its coded size
    std::vector<std::string> notes;  // what the user should know ("no ellipsoids: points only", ...)
    DecodeTimings timings;
};

// Format 1.14 (spec 30): the further texture-coordinate sets of the points given to the decoder,
// [set - 1][k] for the k-th point; NaN where the point's record of that set has not arrived.
using PointTexcoordSets = std::vector<std::vector<std::array<float, 2>>>;

// Reconstructs one object from the ellipsoids and points that arrived (points in stream order,
// as ReceivedStream::points gives them; `point_count` is the object's declared count and tells
// whether the stream is complete). Returns false with `error` only when nothing can be built
// (e.g. the grid would be too large); a missing base gives a point set and a note. `sets`, when
// given, are the points' further texture-coordinate sets: the output then has them too, each vertex
// its point's (NaN where that record has not arrived; decode_stream fills those in, spec 30.2).
bool decode_object(const ObjectInfo& info, const std::vector<Ellipsoid>& ellipsoids,
                   const std::vector<SurfacePoint>& points, int grid_hint, const DecodeOptions& options,
                   size_t object_index, Mesh& out, ObjectDecodeReport& report, std::string& error,
                   const PointTexcoordSets* sets = nullptr);

struct StreamDecodeReport {
    std::vector<ObjectDecodeReport> objects;  // one per object of the table (empty for absent ones)
    size_t objects_without_info = 0;          // object table entries that never arrived
    size_t objects_failed = 0;                // objects that could not be built (why: their notes)
    DecodeTimings timings;                    // summed over objects
};

// The base allowance of grid nodes per object when decoding `stream` object by object:
// kBaseGridNodesInAll shared by the objects that have ellipsoids (at least 4096, at most
// options.base_grid_nodes). decode_stream applies it itself.
size_t shared_base_grid_nodes(const ReceivedStream& stream, const DecodeOptions& options);

// Surface normals (format 1.8, spec 24.4): every vertex whose normal is (0, 0, 0) (a point whose
// normal was left to the surface) gets the angle-weighted sum of spec 24.3 over the triangles that
// use it, normalized; (0, 0, 1) where that is undefined.
void fill_surface_normals(Mesh& mesh);

// Object `object`'s exact mesh (spec 19.4): its original triangles over the points they use, each
// corner with the point's dequantized attributes (surface normals filled in). False, with `why`, while its points or its
// connectivity are not all there or the connectivity is unusable.
bool exact_mesh(const ReceivedStream& stream, size_t object, Mesh& out, std::string& why, bool& unusable);

// Reconstructs every object of a received stream whose info arrived. Fails with a clear `error`
// when no STREAM_INFO arrived at all. Objects with no geometry at all are left out of `meshes`;
// `mesh_objects`, when given, receives the object index of each mesh.
bool decode_stream(const ReceivedStream& stream, const DecodeOptions& options, std::vector<Mesh>& meshes,
                   StreamDecodeReport& report, std::string& error, std::vector<size_t>* mesh_objects = nullptr);

// The output mesh of a reconstruction in its current state, with attributes: seams are split by
// attribute set (each face corner takes the set closest to the face's other corners), and
// marching-cubes vertices take the attributes of their nearest original vertex.
Mesh extract_mesh(const Reconstruction& r, const ObjectInfo& info, const std::vector<SurfacePoint>& points,
                  const PointTexcoordSets* sets = nullptr);

}  // namespace ellicast
