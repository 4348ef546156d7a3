// Two operations on the decoder's triangle mesh that OpenMesh offers at a cost its checks make high
// in the insertion's inner loops, restated with the same result. Shared inside the codec only.
#pragma once

#include "ellicast/codec/decoder.h"

#include <array>

namespace ellicast::detail {

// The three corners of triangle f in the order OpenMesh's face-vertex circulator gives them (the
// face's halfedge's target, then following `next`), without the circulator's per-step bookkeeping.
// Every face of a DecoderTriMesh is a triangle.
inline std::array<OpenMesh::VertexHandle, 3> corners(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f) {
    const auto h0 = mesh.halfedge_handle(f);
    const auto h1 = mesh.next_halfedge_handle(h0);
    return {mesh.to_vertex_handle(h0), mesh.to_vertex_handle(h1), mesh.to_vertex_handle(mesh.next_halfedge_handle(h1))};
}

// OpenMesh's TriConnectivity::flip, the same handle updates in the same order, without the check
// that the library build repeats inside it (its assert walks a one-ring: a third of a flip's cost).
// The caller has made sure the flip is legal: e is an inner edge whose two opposite corners are
// distinct and not yet joined.
inline void flip_edge(DecoderTriMesh& mesh, OpenMesh::EdgeHandle e) {
    const auto a0 = mesh.halfedge_handle(e, 0), b0 = mesh.halfedge_handle(e, 1);
    const auto a1 = mesh.next_halfedge_handle(a0), a2 = mesh.next_halfedge_handle(a1);
    const auto b1 = mesh.next_halfedge_handle(b0), b2 = mesh.next_halfedge_handle(b1);
    const auto va0 = mesh.to_vertex_handle(a0), va1 = mesh.to_vertex_handle(a1);
    const auto vb0 = mesh.to_vertex_handle(b0), vb1 = mesh.to_vertex_handle(b1);
    const auto fa = mesh.face_handle(a0), fb = mesh.face_handle(b0);
    mesh.set_vertex_handle(a0, va1);
    mesh.set_vertex_handle(b0, vb1);
    // The two new triangles' cycles: a0 a2 b1 and b0 b2 a1.
    const std::array<std::array<OpenMesh::HalfedgeHandle, 2>, 6> next{{{a0, a2}, {a2, b1}, {b1, a0}, {b0, b2}, {b2, a1}, {a1, b0}}};
    for (const auto& [h, after] : next) mesh.set_next_halfedge_handle(h, after);
    mesh.set_face_handle(a1, fb);
    mesh.set_face_handle(b1, fa);
    mesh.set_halfedge_handle(fa, a0);
    mesh.set_halfedge_handle(fb, b0);
    if (mesh.halfedge_handle(va0) == b0) mesh.set_halfedge_handle(va0, a1);
    if (mesh.halfedge_handle(vb0) == a0) mesh.set_halfedge_handle(vb0, b1);
}

}  // namespace ellicast::detail
