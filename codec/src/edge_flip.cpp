// Local edge flips after an insertion or a collapse.
//
// An edge (a, b) between faces (a, b, c) and (b, a, d) may become (c, d):
//  - flat (both dihedral angles, before and after, under the flat threshold): flip when the
//    smallest angle of the two faces grows (the surface analogue of a Delaunay flip);
//  - curved: the data-dependent triangulation rule (Dyn, Levin & Rippa 1990): flip when the total
//    angle between neighbouring face normals over the quad's five edges drops by 5%, and, if the
//    smallest angle shrinks, by 30% (a crease, not the noise of a smooth part); never into a sliver.
//    Edges then run along creases instead of across them;
//  - folded over (dihedral beyond the fold-over bound): flip when that straightens the edge;
//  - never when a new face would turn more than the fold-over bound away from the old faces' mean
//    normal (unless folded), or would be degenerate.
#include "ellicast/codec/decoder.h"

#include "mesh_ops.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using Vec3 = OpenMesh::Vec3d;

namespace {

const double kSliverCos = std::cos(3.0 * M_PI / 180.0);

// acos within 7e-5 rad (Abramowitz & Stegun 4.4.45), at a fraction of std::acos's cost.
double fast_acos(double x) {
    x = std::clamp(x, -1.0, 1.0);
    const double a = std::abs(x);
    const double r = std::sqrt(1 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
    return x >= 0 ? r : M_PI - r;
}

// Cosine of the smallest angle of triangle (p, q, r); larger = worse.
double worst_cos(const Vec3& p, const Vec3& q, const Vec3& r) {
    auto c = [](const Vec3& o, const Vec3& x, const Vec3& y) {
        Vec3 u = x - o, v = y - o;
        double l = std::sqrt(u.sqrnorm() * v.sqrnorm());
        return l > 0 ? OpenMesh::dot(u, v) / l : 1.0;
    };
    return std::max({c(p, q, r), c(q, r, p), c(r, p, q)});
}

bool unit(Vec3& n) {
    double l = n.norm();
    if (!(l > 1e-300)) return false;
    n /= l;
    return true;
}

}  // namespace

// Unit normal of the face across halfedge h's edge (the face of h's opposite); false on a border or
// a degenerate face.
static bool across_normal(const DecoderTriMesh& mesh, OpenMesh::HalfedgeHandle h, Vec3& n) {
    auto o = mesh.opposite_halfedge_handle(h);
    if (mesh.is_boundary(o)) return false;
    const Vec3& p = mesh.point(mesh.from_vertex_handle(o));
    const Vec3& q = mesh.point(mesh.to_vertex_handle(o));
    const Vec3& s = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(o)));
    n = OpenMesh::cross(q - p, s - p);
    return unit(n);
}

// OpenMesh's TriConnectivity::is_flip_ok, inline (it is called for every flip about to be made): the
// edge is inner and its two opposite vertices are distinct and not yet joined. h0, h1: the edge's
// halfedges.
static bool flip_keeps_manifold(const DecoderTriMesh& mesh, OpenMesh::HalfedgeHandle h0, OpenMesh::HalfedgeHandle h1) {
    const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
    const auto d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
    if (c == d) return false;
    for (auto w : mesh.vv_range(c))
        if (w == d) return false;
    return true;
}

// Returns true when edge e was flipped.
static bool try_flip(Reconstruction& r, OpenMesh::EdgeHandle e, double cos_flat, double cos_fold) {
    DecoderTriMesh& mesh = r.mesh;
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) return false;
    auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const Vec3& a = mesh.point(mesh.from_vertex_handle(h0));
    const Vec3& b = mesh.point(mesh.to_vertex_handle(h0));
    const Vec3& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0)));
    const Vec3& d = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1)));
    Vec3 n1 = OpenMesh::cross(b - a, c - a), n2 = OpenMesh::cross(a - b, d - b);
    Vec3 m1 = OpenMesh::cross(d - a, c - a), m2 = OpenMesh::cross(b - d, c - d);
    // New faces must not be (nearly) degenerate: compare their area with their squared edge length.
    const double scale = std::max({(a - b).sqrnorm(), (c - d).sqrnorm(), (a - c).sqrnorm(), (b - d).sqrnorm()});
    const double l1 = m1.norm(), l2 = m2.norm();  // each norm once (unit() would take it again)
    if (l1 < 1e-6 * scale || l2 < 1e-6 * scale) return false;
    if (!(l1 > 1e-300) || !(l2 > 1e-300)) return false;
    m1 /= l1, m2 /= l2;
    bool old_ok = unit(n1) && unit(n2);
    // The smallest angles, old and new: only where a rule below reads them (a folded pair does not).
    double old_worst = 0, new_worst = 0;
    auto measure = [&] {
        old_worst = std::max(worst_cos(a, b, c), worst_cos(b, a, d));
        new_worst = std::max(worst_cos(a, d, c), worst_cos(d, b, c));
    };
    if (!old_ok) {  // a degenerate old face: any legal flip that helps
        measure();
        if (!(new_worst < old_worst) || !flip_keeps_manifold(mesh, h0, h1)) return false;
        detail::flip_edge(mesh, e);
        r.face_changed(mesh.face_handle(h0));
        r.face_changed(mesh.face_handle(h1));
        ++r.flips;
        return true;
    }
    Vec3 mean = n1 + n2;
    if (!unit(mean)) mean = n1;
    const double new_dot = OpenMesh::dot(m1, m2), old_dot = OpenMesh::dot(n1, n2);
    const bool folded = old_dot < cos_fold;
    if (OpenMesh::dot(m1, mean) < cos_fold || OpenMesh::dot(m2, mean) < cos_fold) {
        if (!folded) return false;
    }
    bool flip;
    if (folded) {
        flip = new_dot > old_dot + 1e-9;
    } else if (old_dot > cos_flat && new_dot > cos_flat) {
        measure();
        flip = new_worst < old_worst - 1e-12;
    } else {
        // Curved: the data-dependent triangulation rule (Dyn, Levin & Rippa, "Data dependent
        // triangulations for piecewise linear interpolation", 1990): the diagonal with the smaller
        // total angle between the normals of neighbouring faces over the quad's five edges. It lays
        // edges along creases and across no ridge; the minimum-angle rule alone cut across them.
        auto angle = [](const Vec3& x, const Vec3& y) { return fast_acos(OpenMesh::dot(x, y)); };
        double cost_old = angle(n1, n2), cost_new = angle(m1, m2);
        const auto hbc = mesh.next_halfedge_handle(h0), hca = mesh.next_halfedge_handle(hbc);
        const auto had = mesh.next_halfedge_handle(h1), hdb = mesh.next_halfedge_handle(had);
        Vec3 o;
        if (across_normal(mesh, hbc, o)) cost_old += angle(n1, o), cost_new += angle(m2, o);
        if (across_normal(mesh, hca, o)) cost_old += angle(n1, o), cost_new += angle(m1, o);
        if (across_normal(mesh, had, o)) cost_old += angle(n2, o), cost_new += angle(m1, o);
        if (across_normal(mesh, hdb, o)) cost_old += angle(n2, o), cost_new += angle(m2, o);
        flip = cost_new < 0.95 * cost_old - 1e-9;  // by a margin: no flip-flopping on smooth parts
        if (flip) measure();
        // On smooth parts the rule alone lays long thin triangles along the curvature: a flip that
        // makes the smallest angle smaller must cut the total angle by 30% (a crease, not noise).
        flip = flip && (new_worst < old_worst || cost_new < 0.7 * cost_old);
        // No slivers (an angle under 3 degrees) unless the old pair was worse: they would turn into
        // zero-area triangles in the single-precision output.
        flip = flip && (new_worst < kSliverCos || new_worst < old_worst);
    }
    if (!flip || !flip_keeps_manifold(mesh, h0, h1)) return false;  // topology last: it walks a one-ring
    detail::flip_edge(mesh, e);
    r.face_changed(mesh.face_handle(h0));
    r.face_changed(mesh.face_handle(h1));
    ++r.flips;
    return true;
}

size_t flip_edges_around(Reconstruction& r, OpenMesh::VertexHandle v) {
    DecoderTriMesh& mesh = r.mesh;
    const double cos_flat = std::cos(r.options.flat_angle_degrees * M_PI / 180.0);
    const double cos_fold = std::cos(r.options.foldover_degrees * M_PI / 180.0);
    // One stack for every call (no allocation per insertion); the function does not call itself.
    static thread_local std::vector<OpenMesh::EdgeHandle> stack;
    stack.clear();
    for (auto h : mesh.voh_range(v)) {
        if (mesh.is_boundary(h)) continue;
        stack.push_back(mesh.edge_handle(mesh.next_halfedge_handle(h)));
        stack.push_back(mesh.edge_handle(h));
    }
    size_t flips = 0;
    const size_t budget = size_t(std::max(1, r.options.max_flips_per_insertion));
    while (!stack.empty() && flips < budget) {
        auto e = stack.back();
        stack.pop_back();
        if (!try_flip(r, e, cos_flat, cos_fold)) continue;
        ++flips;
        // The quad's four outer edges may now want a flip.
        auto h = mesh.halfedge_handle(e, 0);
        auto o = mesh.halfedge_handle(e, 1);
        stack.push_back(mesh.edge_handle(mesh.next_halfedge_handle(h)));
        stack.push_back(mesh.edge_handle(mesh.prev_halfedge_handle(h)));
        stack.push_back(mesh.edge_handle(mesh.next_halfedge_handle(o)));
        stack.push_back(mesh.edge_handle(mesh.prev_halfedge_handle(o)));
    }
    return flips;
}

}  // namespace ellicast
