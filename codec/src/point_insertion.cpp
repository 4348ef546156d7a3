// Inserting an original vertex into the nearest triangle of the current mesh.
#include "ellicast/codec/decoder.h"

#include "mesh_ops.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ellicast {

using Vec3 = OpenMesh::Vec3d;

namespace {

// Barycentric coordinate under which a point counts as lying on the opposite edge.
constexpr double kOnEdge = 0.1;

uint64_t position_key(const std::array<float, 3>& p) {
    uint32_t b[3];
    std::memcpy(b, p.data(), sizeof b);
    uint64_t h = 1469598103934665603ull;
    for (uint32_t x : b) h = (h ^ x) * 1099511628211ull;
    return h;
}

Vec3 face_normal(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f, OpenMesh::VertexHandle moved,
                 const Vec3& moved_to) {
    Vec3 p[3];
    int n = 0;
    for (auto v : detail::corners(mesh, f)) p[n++] = v == moved ? moved_to : mesh.point(v);
    return OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
}

// Moving v to `to` keeps every face around it within the fold-over bound and non-degenerate.
bool move_is_safe(const DecoderTriMesh& mesh, OpenMesh::VertexHandle v, const Vec3& to, double cos_limit) {
    for (auto f : mesh.vf_range(v)) {
        Vec3 before = face_normal(mesh, f, v, mesh.point(v));
        Vec3 after = face_normal(mesh, f, v, to);
        double lb = before.norm(), la = after.norm();
        if (!(la > 0) || !(lb > 0)) return false;
        if (OpenMesh::dot(before, after) < cos_limit * la * lb) return false;
    }
    return true;
}

}  // namespace

void reindex_faces_around(Reconstruction& r, OpenMesh::VertexHandle v) {
    for (auto f : r.mesh.vf_range(v)) r.face_changed(f);
}

void start_reconstruction(Reconstruction& r, DecoderTriMesh&& base, const Frame& frame, double cell,
                          size_t expected_points, const ReconstructionOptions& options) {
    r.mesh = std::move(base);
    r.mesh.request_vertex_status();
    r.mesh.request_edge_status();
    r.mesh.request_face_status();
    r.options = options;
    r.vertex_points.assign(r.mesh.n_vertices(), {});
    r.by_position.clear();
    // Room for the points the stream declares: each adds a vertex, three edges and two faces (a
    // 1-to-3 or a 2-to-4 split), so that the mesh's arrays seldom move while points arrive. Not more
    // than a few times the base: a declared count is only a claim (a hostile stream's may be 2^32).
    // An eighth more for what the end of a stream inserts again (agreement with the normals, sheets).
    const size_t room = std::min(expected_points, 2 * r.mesh.n_vertices() + 65536) * 9 / 8;
    r.by_position.reserve(room);
    r.vertex_points.reserve(r.mesh.n_vertices() + room);
    r.mesh.reserve(r.mesh.n_vertices() + room, r.mesh.n_edges() + 3 * room, r.mesh.n_faces() + 2 * room);
    r.mc_vertices = r.mesh.n_vertices();
    r.original_vertices = 0;
    Vec3 lo(frame.origin[0], frame.origin[1], frame.origin[2]);
    Vec3 hi = lo + Vec3(frame.scale, frame.scale, frame.scale);
    for (auto v : r.mesh.vertices()) {
        lo.minimize(r.mesh.point(v));
        hi.maximize(r.mesh.point(v));
    }
    // Cells of about twice the final edge length (measured best in bench_decode): the base's area
    // shared by as many faces as the base or the stream's points (2 faces per vertex) will make.
    double area = 0;
    for (auto f : r.mesh.faces()) {
        auto it = r.mesh.cfv_iter(f);
        Vec3 a = r.mesh.point(*it), b = r.mesh.point(*++it), c = r.mesh.point(*++it);
        area += 0.5 * OpenMesh::cross(b - a, c - a).norm();
    }
    // Edge length of an equilateral triangulation of that area with the stream's points.
    r.point_spacing = expected_points > 0 ? std::sqrt(2.0 * area / (std::sqrt(3.0) * double(expected_points))) : 0.0;
    double faces = std::max<double>({1.0, double(r.mesh.n_faces()), 2.0 * double(expected_points)});
    double size = std::clamp(3.0 * std::sqrt(area / faces), 0.25 * cell, 4 * cell);
    if (!(size > 0)) size = cell;
    r.index_lo = lo;
    r.index_hi = hi;
    r.index_cell = size;
    r.rebuild_index();
}

void Reconstruction::rebuild_index() {
    index_built_for = mesh.n_faces();
    faces.reset(index_lo, index_hi, index_cell, std::max<size_t>(4096, 16 * index_built_for));
    faces.build(mesh);
    index_paused = false;
}

void Reconstruction::refresh_index() {
    if (index_paused || (faces.cell_size() > index_cell * 1.001 && mesh.n_faces() > 4 * index_built_for))
        rebuild_index();
}

Insertion insert_point(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                       OpenMesh::VertexHandle& vertex) {
    DecoderTriMesh& mesh = r.mesh;
    const Vec3 p(position[0], position[1], position[2]);
    const uint64_t key = position_key(position);
    bool merged = false;
    for (int32_t node = r.by_position.first(key); node != PositionIndex::kEnd; node = r.by_position.next(node)) {
        // Every vertex at this position takes the point: a seam's vertex, or both sides of a sheet.
        const auto v = r.by_position.vertex(node);
        if (!mesh.status(v).deleted() && mesh.point(v) == p) {
            r.vertex_points[v.idx()].push_back(point_index);
            if (!merged) ++r.seam_merges, vertex = v;
            merged = true;
        }
    }
    if (merged) return Insertion::SeamDuplicate;

    r.refresh_index();
    Vec3 closest;
    std::array<double, 3> bary;
    OpenMesh::FaceHandle f = r.faces.nearest(mesh, p, closest, bary);
    if (!f.is_valid()) return Insertion::NoMesh;
    return insert_into_face(r, point_index, position, f, bary, vertex);
}

Insertion insert_into_face(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                           OpenMesh::FaceHandle f, const std::array<double, 3>& bary,
                           OpenMesh::VertexHandle& vertex) {
    DecoderTriMesh& mesh = r.mesh;
    const Vec3 p(position[0], position[1], position[2]);
    const uint64_t key = position_key(position);
    OpenMesh::VertexHandle fv[3];
    OpenMesh::HalfedgeHandle opposite[3];  // halfedge of f opposite corner i
    {
        // Same corner order as FaceGrid::nearest's barycentric coordinates.
        int n = 0;
        for (auto v : detail::corners(mesh, f)) fv[n++] = v;
        for (auto h : mesh.fh_range(f)) {
            auto a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
            for (int i = 0; i < 3; ++i)
                if (fv[i] != a && fv[i] != b) opposite[i] = h;
        }
    }
    const double cos_limit = std::cos(r.options.foldover_degrees * M_PI / 180.0);

    int small = 0, smallest = 0, largest = 0;
    for (int i = 0; i < 3; ++i) {
        if (bary[i] < kOnEdge) ++small;
        if (bary[i] < bary[smallest]) smallest = i;
        if (bary[i] > bary[largest]) largest = i;
    }

    // On a marching-cubes vertex: that vertex becomes the original one.
    if (small == 2 && !r.is_original(fv[largest]) && move_is_safe(mesh, fv[largest], p, cos_limit)) {
        vertex = fv[largest];
        mesh.set_point(vertex, p);
        r.vertex_points[vertex.idx()].push_back(point_index);
        --r.mc_vertices;
        ++r.original_vertices;
        ++r.vertex_moves;
        r.by_position.add(key, vertex);
        reindex_faces_around(r, vertex);
        return Insertion::VertexMoved;
    }

    // A vertex of the faces to split already stands at p (the other side of a sheet folded onto
    // this one): the point joins it rather than making a zero-area face.
    {
        OpenMesh::VertexHandle at;
        for (int i = 0; i < 3; ++i)
            if (mesh.point(fv[i]) == p) at = fv[i];
        if (small >= 1) {
            auto o = mesh.opposite_halfedge_handle(opposite[smallest]);
            if (!mesh.is_boundary(o)) {
                auto x = mesh.to_vertex_handle(mesh.next_halfedge_handle(o));
                if (mesh.point(x) == p) at = x;
            }
        }
        if (at.is_valid()) {
            if (!r.is_original(at)) --r.mc_vertices, ++r.original_vertices;
            r.vertex_points[at.idx()].push_back(point_index);
            r.by_position.add(key, at);
            ++r.seam_merges;
            vertex = at;
            return Insertion::SeamDuplicate;
        }
    }
    vertex = mesh.add_vertex(p);
    r.vertex_points.resize(mesh.n_vertices());
    r.vertex_points[vertex.idx()].push_back(point_index);
    ++r.original_vertices;
    r.by_position.add(key, vertex);
    Insertion kind;
    if (small >= 1) {
        OpenMesh::EdgeHandle e = mesh.edge_handle(opposite[smallest]);
        mesh.split(e, vertex);
        ++r.edge_splits;
        kind = Insertion::EdgeSplit;
    } else {
        mesh.split(f, vertex);
        ++r.face_splits;
        kind = Insertion::FaceSplit;
    }
    reindex_faces_around(r, vertex);
    return kind;
}

}  // namespace ellicast
