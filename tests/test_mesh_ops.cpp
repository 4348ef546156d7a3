// The decoder's own mesh operations against OpenMesh's, which they replace in the insertion's inner
// loops and must match exactly (a reconstruction is fixed byte for byte by them): collapse_link_ok
// against TriConnectivity::is_collapse_ok with the link condition as it was written over OpenMesh's
// circulators, flip_edge against TriConnectivity::flip, corners against the face-vertex circulator.
// On meshes with borders, corners of valence 2 and 3, irregular fans from random flips, and the
// shapes random collapses leave behind.
#include "ellicast/codec/decoder.h"
#include "../codec/src/mesh_ops.h"
#include "shapes.h"

#include <random>
#include <vector>

#include <doctest/doctest.h>

using namespace ellicast;

namespace {

using VH = OpenMesh::VertexHandle;
using HH = OpenMesh::HalfedgeHandle;

DecoderTriMesh with_status(DecoderTriMesh m) {
    m.request_vertex_status();
    m.request_edge_status();
    m.request_face_status();
    return m;
}

// An n x n grid in the plane, each square cut along a random diagonal: a border, four corners.
DecoderTriMesh grid(int n, std::mt19937& rng) {
    DecoderTriMesh m;
    std::vector<VH> v;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) v.push_back(m.add_vertex(OpenMesh::Vec3d(i, j, 0.1 * ((i * 7 + j * 3) % 5))));
    std::bernoulli_distribution coin(0.5);
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const VH a = v[j * n + i], b = v[j * n + i + 1], c = v[(j + 1) * n + i + 1], d = v[(j + 1) * n + i];
            if (coin(rng)) {
                m.add_face(a, b, c);
                m.add_face(a, c, d);
            } else {
                m.add_face(a, b, d);
                m.add_face(b, c, d);
            }
        }
    return with_status(std::move(m));
}

// A closed ellipsoid (samples/shapes.h): no border, the poles' high valence.
DecoderTriMesh closed_ellipsoid() {
    const Mesh shape = samples::uv_ellipsoid(9, {0, 0, 0}, {1.0, 0.7, 0.5});
    DecoderTriMesh m;
    std::vector<VH> v;
    for (const auto& p : shape.positions) v.push_back(m.add_vertex(OpenMesh::Vec3d(p[0], p[1], p[2])));
    for (const auto& t : shape.triangles) m.add_face(v[t[0]], v[t[1]], v[t[2]]);
    return with_status(std::move(m));
}

// Random legal flips, then random collapses that OpenMesh allows: fans of every valence.
void scramble(DecoderTriMesh& m, std::mt19937& rng, int flips, int collapses) {
    for (int k = 0; k < flips; ++k) {
        const OpenMesh::EdgeHandle e(int(rng() % m.n_edges()));
        if (!m.status(e).deleted() && m.is_flip_ok(e)) m.flip(e);
    }
    for (int k = 0; k < collapses; ++k) {
        const HH h(int(rng() % m.n_halfedges()));
        if (!m.status(m.edge_handle(h)).deleted() && m.is_collapse_ok(h)) m.collapse(h);
    }
}

// collapse_link_ok as it was written before the decoder restated OpenMesh's test (session 20):
// OpenMesh's is_collapse_ok, then the full link condition over its circulators.
bool link_ok_reference(DecoderTriMesh& mesh, HH h) {
    if (!mesh.is_collapse_ok(h)) return false;
    const auto from = mesh.from_vertex_handle(h), to = mesh.to_vertex_handle(h);
    int apexes = 0;
    if (!mesh.is_boundary(h)) ++apexes;
    if (!mesh.is_boundary(mesh.opposite_halfedge_handle(h))) ++apexes;
    int common = 0;
    for (auto a : mesh.vv_range(from)) {
        if (a == to) continue;
        for (auto b : mesh.vv_range(to)) common += a == b;
    }
    if (common != apexes) return false;
    int faces = 0;
    for (auto f : mesh.vf_range(from))
        for (auto v : mesh.fv_range(f)) faces += v == to;
    return faces == apexes;
}

// Every connectivity array of two meshes, entry by entry.
void require_same_connectivity(const DecoderTriMesh& x, const DecoderTriMesh& y) {
    REQUIRE(x.n_halfedges() == y.n_halfedges());
    for (size_t i = 0; i < x.n_halfedges(); ++i) {
        const HH h{int(i)};
        REQUIRE(x.to_vertex_handle(h) == y.to_vertex_handle(h));
        REQUIRE(x.next_halfedge_handle(h) == y.next_halfedge_handle(h));
        REQUIRE(x.prev_halfedge_handle(h) == y.prev_halfedge_handle(h));
        REQUIRE(x.face_handle(h) == y.face_handle(h));
    }
    for (size_t i = 0; i < x.n_vertices(); ++i) REQUIRE(x.halfedge_handle(VH{int(i)}) == y.halfedge_handle(VH{int(i)}));
    for (size_t i = 0; i < x.n_faces(); ++i) {
        const OpenMesh::FaceHandle f{int(i)};
        REQUIRE(x.halfedge_handle(f) == y.halfedge_handle(f));
    }
}

}  // namespace

TEST_CASE("the decoder's collapse test answers as OpenMesh's is_collapse_ok with the link condition, on every halfedge of scrambled meshes") {
    std::mt19937 rng(11);
    size_t tried = 0, allowed = 0, refused = 0;
    for (int round = 0; round < 6; ++round) {
        DecoderTriMesh m = round < 4 ? grid(6 + 3 * round, rng) : closed_ellipsoid();
        scramble(m, rng, 40 * (round + 1), 4 * round);
        for (size_t i = 0; i < m.n_halfedges(); ++i) {
            const HH h{int(i)};
            const bool reference = link_ok_reference(m, h);
            CHECK(collapse_link_ok(m, h) == reference);
            ++tried;
            (reference ? allowed : refused) += 1;
        }
    }
    // Both answers occur often enough for the comparison to mean something.
    CHECK(tried > 2000);
    CHECK(allowed > 500);
    CHECK(refused > 200);
}

TEST_CASE("the decoder's edge flip leaves the same connectivity as OpenMesh's flip, flip after flip") {
    std::mt19937 rng(5);
    for (int round = 0; round < 3; ++round) {
        DecoderTriMesh theirs = round < 2 ? grid(8 + 4 * round, rng) : closed_ellipsoid();
        DecoderTriMesh ours = theirs;
        int flips = 0;
        for (int k = 0; k < 400; ++k) {
            const OpenMesh::EdgeHandle e(int(rng() % theirs.n_edges()));
            if (!theirs.is_flip_ok(e)) continue;
            theirs.flip(e);
            detail::flip_edge(ours, e);
            ++flips;
        }
        CHECK(flips > 100);
        require_same_connectivity(theirs, ours);
    }
}

TEST_CASE("a face's corners come in the order of OpenMesh's face-vertex circulator") {
    std::mt19937 rng(3);
    DecoderTriMesh m = grid(10, rng);
    scramble(m, rng, 200, 10);
    for (auto f : m.faces()) {
        std::vector<VH> circulated;
        for (auto v : m.fv_range(f)) circulated.push_back(v);
        const auto c = detail::corners(m, f);
        REQUIRE(circulated.size() == 3);
        CHECK(std::vector<VH>(c.begin(), c.end()) == circulated);
    }
}
