// Removing marching-cubes vertices by collapsing them into nearby original vertices.
#include "ellicast/codec/decoder.h"

#include "mesh_ops.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ellicast {

bool collapse_link_ok(DecoderTriMesh& mesh, OpenMesh::HalfedgeHandle h) {
    // First OpenMesh's TriConnectivity::is_collapse_ok, restated here over the two one-rings gathered
    // once (OpenMesh's walks them three times through circulators whose every step is checked: it
    // took 7,700 instructions a call, 7.6% of the bunny's reconstruction). Its tests (each can only
    // refuse, so their order does not change the answer):
    if (mesh.status(mesh.edge_handle(h)).deleted()) return false;
    const auto o = mesh.opposite_halfedge_handle(h);
    const auto from = mesh.to_vertex_handle(o), to = mesh.to_vertex_handle(h);
    if (mesh.status(from).deleted() || mesh.status(to).deleted()) return false;
    // The two edges of a face beside the edge must not both lie on the border; vl and vr are the
    // faces' third corners (invalid where the edge is a border).
    OpenMesh::VertexHandle vl, vr;
    for (const auto side : {h, o}) {
        if (mesh.is_boundary(side)) continue;
        const auto h1 = mesh.next_halfedge_handle(side), h2 = mesh.next_halfedge_handle(h1);
        (side == h ? vl : vr) = mesh.to_vertex_handle(h1);
        if (mesh.is_boundary(mesh.opposite_halfedge_handle(h1)) && mesh.is_boundary(mesh.opposite_halfedge_handle(h2)))
            return false;
    }
    if (vl == vr) return false;  // equal, or both invalid
    // An edge between two border vertices must be a border edge.
    if (mesh.is_boundary(from) && mesh.is_boundary(to) && !mesh.is_boundary(h) && !mesh.is_boundary(o)) return false;
    // One pass over the two one-rings: no neighbour common to both ends but vl and vr (OpenMesh's
    // test), and then the link condition in full: as many common neighbours, and as many faces
    // holding both ends, as the edge has faces (counted with repetition: a vertex met twice around a
    // non-manifold one counts twice).
    static thread_local std::vector<OpenMesh::VertexHandle> ring_to;
    ring_to.clear();
    for (auto b : mesh.vv_range(to)) ring_to.push_back(b);
    int apexes = 0;
    if (!mesh.is_boundary(h)) ++apexes;
    if (!mesh.is_boundary(o)) ++apexes;
    int common = 0;
    for (auto a : mesh.vv_range(from)) {
        if (a == to) continue;  // not a neighbour of itself: never common
        const int shared = int(std::count(ring_to.begin(), ring_to.end(), a));
        if (shared > 0 && a != vl && a != vr) return false;
        common += shared;
    }
    if (common != apexes) return false;
    int faces = 0;
    for (auto f : mesh.vf_range(from))
        for (auto v : detail::corners(mesh, f)) faces += v == to;
    return faces == apexes;
}

using Vec3 = OpenMesh::Vec3d;

namespace {

// The smallest cosine between a face's normal before and after moving `from` onto `to`'s position,
// over the faces around `from` that survive the collapse of halfedge from -> to; -2 when one of
// them would become degenerate.
double collapse_worst_dot(const DecoderTriMesh& mesh, OpenMesh::HalfedgeHandle h) {
    const auto from = mesh.from_vertex_handle(h), to = mesh.to_vertex_handle(h);
    const Vec3 target = mesh.point(to);
    double worst = 1;
    for (auto f : mesh.vf_range(from)) {
        Vec3 p[3], q[3];
        int n = 0;
        bool has_to = false;
        for (auto v : detail::corners(mesh, f)) {
            has_to |= v == to;
            p[n] = mesh.point(v);
            q[n] = v == from ? target : p[n];
            ++n;
        }
        if (has_to) continue;  // removed by the collapse
        Vec3 before = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
        Vec3 after = OpenMesh::cross(q[1] - q[0], q[2] - q[0]);
        double lb = before.norm(), la = after.norm();
        double scale = std::max({(q[1] - q[0]).sqrnorm(), (q[2] - q[0]).sqrnorm(), (q[2] - q[1]).sqrnorm()});
        if (!(la > 1e-6 * scale)) return -2;
        if (!(lb > 0)) continue;  // a degenerate face gets better, whatever its new normal
        worst = std::min(worst, OpenMesh::dot(before, after) / (la * lb));
    }
    return worst;
}

// Collapses marching-cubes vertex m. Without `force` it needs enough original neighbours and a
// collapse that turns no face beyond the fold-over bound; with `force` it takes the best legal
// collapse into an original neighbour, or into any neighbour when `any_target` is set.
// Largest valence a collapse may leave behind (the candidate arrays above hold 64 neighbours).
constexpr size_t kMaxCollapseValence = 48;

bool try_collapse(Reconstruction& r, OpenMesh::VertexHandle m, bool force, bool any_target,
                  OpenMesh::VertexHandle* into = nullptr, bool flip_after = true) {
    DecoderTriMesh& mesh = r.mesh;
    if (mesh.status(m).deleted() || r.is_original(m)) return false;
    int total = 0, originals = 0;
    double nearest2 = std::numeric_limits<double>::max();
    for (auto v : mesh.vv_range(m)) {
        ++total;
        if (r.is_original(v)) {
            ++originals;
            nearest2 = std::min(nearest2, (mesh.point(v) - mesh.point(m)).sqrnorm());
        }
    }
    if (!force) {
        const double reach = r.options.collapse_spacing_factor * r.point_spacing * r.spacing_scale;
        const bool close = originals > 0 && nearest2 <= reach * reach;
        const bool surrounded = originals >= r.options.collapse_min_originals &&
                                originals >= r.options.collapse_min_fraction * total;
        if (!close && !surrounded) return false;
    } else if (originals == 0 && !any_target) {
        return false;
    }
    const double cos_fold = std::cos(r.options.foldover_degrees * M_PI / 180.0);
    const Vec3 pm = mesh.point(m);
    // Candidates: nearest first.
    std::array<std::pair<double, OpenMesh::HalfedgeHandle>, 64> cand;
    int n = 0;
    for (auto h : mesh.voh_range(m)) {
        auto to = mesh.to_vertex_handle(h);
        if (originals > 0 && !r.is_original(to)) continue;
        if (n < int(cand.size())) cand[n++] = {(mesh.point(to) - pm).sqrnorm(), h};
    }
    std::sort(cand.begin(), cand.begin() + n,
              [](const auto& x, const auto& y) { return x.first < y.first || (x.first == y.first && x.second.idx() < y.second.idx()); });
    OpenMesh::HalfedgeHandle chosen;
    double chosen_dot = -3;
    const size_t valence_m = mesh.valence(m);
    for (int i = 0; i < n; ++i) {
        auto h = cand[i].second;
        // A fan this large means few originals must absorb many marching-cubes vertices (a cube sent
        // as 8 corners): every further collapse and flip would cost time in proportion to the fan,
        // quadratic overall. Leave such vertices in place instead.
        if (valence_m + mesh.valence(mesh.to_vertex_handle(h)) > kMaxCollapseValence) continue;
        if (!collapse_link_ok(mesh, h)) continue;  // not is_collapse_ok alone: see collapse_link_ok
        double d = collapse_worst_dot(mesh, h);
        if (d >= cos_fold) {
            chosen = h;
            break;
        }
        if (force && d > chosen_dot && d > -2) chosen = h, chosen_dot = d;
    }
    if (!chosen.is_valid()) {
        ++r.rejected_collapses;
        return false;
    }
    const auto target = mesh.to_vertex_handle(chosen);
    if (into) *into = target;
    std::array<OpenMesh::FaceHandle, 64> around;
    int na = 0;
    for (auto f : mesh.vf_range(m))
        if (na < int(around.size())) around[na++] = f;
    mesh.collapse(chosen);
    for (int i = 0; i < na; ++i) {
        if (mesh.status(around[i]).deleted()) r.face_removed(around[i]);
    }
    reindex_faces_around(r, target);
    --r.mc_vertices;
    ++r.collapses;
    if (flip_after) flip_edges_around(r, target);
    return true;
}

// Flips the link edge of m (an edge opposite m in one of its faces) whose flip makes the best-shaped
// pair of faces, so that m gains a neighbour. Returns false when no link edge can flip.
bool flip_link_edge(Reconstruction& r, OpenMesh::VertexHandle m) {
    DecoderTriMesh& mesh = r.mesh;
    OpenMesh::EdgeHandle best;
    double best_area = 0;
    const Vec3 pm = mesh.point(m);
    for (auto h : mesh.voh_range(m)) {
        if (mesh.is_boundary(h)) continue;
        auto link = mesh.next_halfedge_handle(h);
        auto e = mesh.edge_handle(link);
        if (mesh.is_boundary(e)) continue;
        const Vec3& a = mesh.point(mesh.from_vertex_handle(link));
        const Vec3& b = mesh.point(mesh.to_vertex_handle(link));
        const Vec3& x = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(link))));
        // New faces (m, a, x) and (m, x, b): the smaller one's area over its longest squared edge.
        auto quality = [](const Vec3& p, const Vec3& q, const Vec3& s) {
            double l = std::max({(q - p).sqrnorm(), (s - q).sqrnorm(), (p - s).sqrnorm()});
            return l > 0 ? OpenMesh::cross(q - p, s - p).norm() / l : 0.0;
        };
        double area = std::min(quality(pm, a, x), quality(pm, x, b));
        if (area > best_area && mesh.is_flip_ok(e)) best_area = area, best = e;
    }
    if (!best.is_valid() || best_area < 1e-6) return false;
    detail::flip_edge(mesh, best);
    r.face_changed(mesh.face_handle(mesh.halfedge_handle(best, 0)));
    r.face_changed(mesh.face_handle(mesh.halfedge_handle(best, 1)));
    ++r.flips;
    return true;
}

}  // namespace

size_t collapse_mc_vertices_near(Reconstruction& r, OpenMesh::VertexHandle v) {
    if (r.mc_vertices == 0) return 0;
    // A small worklist: the marching-cubes neighbours of v, then those of each vertex collapsed into.
    std::array<OpenMesh::VertexHandle, 256> work;
    int n = 0;
    auto add_ring = [&](OpenMesh::VertexHandle c) {
        for (auto w : r.mesh.vv_range(c))
            if (!r.is_original(w) && n < int(work.size())) work[n++] = w;
    };
    add_ring(v);
    size_t done = 0;
    for (int i = 0; i < n && done < 32; ++i) {
        OpenMesh::VertexHandle into;
        if (!try_collapse(r, work[i], false, false, &into)) continue;
        ++done;
        add_ring(into);
    }
    return done;
}

size_t collapse_all_mc_vertices(Reconstruction& r, bool force) {
    size_t total = 0;
    if (r.mc_vertices == 0) return 0;
    r.index_paused = true;
    // Stage 0: the ordinary rule; when forcing, stage 1: any original neighbour is enough; stage 2:
    // marching-cubes neighbours too. Each stage works through a queue: a vertex is tried again only
    // when a collapse next to it changed its neighbourhood.
    DecoderTriMesh& mesh = r.mesh;
    // A stream far sparser than its base (a cube sent as its 8 corners): nearly every forced
    // collapse lands on one of a few originals, and flipping around that ever larger fan after each
    // would cost many times the base. The forced stages then collapse without flipping, and one
    // flip pass follows.
    const bool sparse = force && r.mc_vertices > 4 * r.original_vertices;
    std::vector<char> queued(mesh.n_vertices(), 0);
    std::vector<OpenMesh::VertexHandle> queue;
    for (int stage = 0; stage < (force ? 3 : 1) && r.mc_vertices > 0; ++stage) {
        queue.clear();
        std::fill(queued.begin(), queued.end(), 0);
        for (auto v : mesh.vertices())
            if (!r.is_original(v)) queue.push_back(v), queued[v.idx()] = 1;
        std::reverse(queue.begin(), queue.end());  // pop_back takes them in index order
        while (!queue.empty() && r.mc_vertices > 0) {
            auto m = queue.back();
            queue.pop_back();
            queued[m.idx()] = 0;
            if (mesh.status(m).deleted() || r.is_original(m)) continue;
            // Remember the neighbourhood: after a collapse its marching-cubes vertices are retried.
            std::array<OpenMesh::VertexHandle, 64> ring;
            int n = 0;
            for (auto w : mesh.vv_range(m))
                if (n < int(ring.size())) ring[n++] = w;
            if (!try_collapse(r, m, stage >= 1, stage >= 2, nullptr, !(sparse && stage >= 1))) continue;
            ++total;
            for (int i = 0; i < n; ++i) {
                auto w = ring[i];
                if (mesh.status(w).deleted()) continue;
                for (auto x : mesh.vv_range(w)) {
                    if (r.is_original(x) || queued[x.idx()]) continue;
                    queued[x.idx()] = 1;
                    queue.push_back(x);
                }
                if (!r.is_original(w) && !queued[w.idx()]) queued[w.idx()] = 1, queue.push_back(w);
            }
        }
    }
    if (sparse) {
        // The flips left out above, once, on the (now small) mesh.
        for (auto v : mesh.vertices()) flip_edges_around(r, v);
    }
    if (force) {
        // Last stage: a vertex no collapse can remove (typically a spike over originals in a row,
        // say samples along a crease, whose removal would leave a flat triangle) first gets a link
        // edge flipped towards it, which gives it one more neighbour, and is tried again.
        for (auto m : mesh.vertices()) {
            if (r.mc_vertices == 0) break;
            for (int attempt = 0; attempt < 4 && !mesh.status(m).deleted() && !r.is_original(m); ++attempt) {
                if (try_collapse(r, m, true, true)) {
                    ++total;
                    break;
                }
                if (!flip_link_edge(r, m)) break;
            }
        }
    }
    return total;
}

}  // namespace ellicast
