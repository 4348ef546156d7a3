// Whole-object and whole-stream reconstruction, and the output mesh with its attributes.
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/triangle_tree.h"
#include "filler_simplify.h"
#include "parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <queue>
#include <unordered_map>

namespace ellicast {

using Vec3 = OpenMesh::Vec3d;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool left_to_surface(const std::array<float, 3>& n) { return n[0] == 0 && n[1] == 0 && n[2] == 0; }

// One corner's term of the angle-weighted vertex normal (spec 24.3): the unit normal of the face
// with edges e1, e2 from the corner, times the corner's angle; 0 for a degenerate face.
Vec3 corner_contribution(const Vec3& e1, const Vec3& e2) {
    const Vec3 m = OpenMesh::cross(e1, e2);
    const double lm = m.norm(), l1 = e1.norm(), l2 = e2.norm();
    if (!(lm > 0) || !(l1 > 0) || !(l2 > 0)) return Vec3(0, 0, 0);
    return m * (std::acos(std::clamp(OpenMesh::dot(e1, e2) / (l1 * l2), -1.0, 1.0)) / lm);
}

// A unit vector from a sum of contributions; (0, 0, 1) where there is none.
std::array<float, 3> unit_or_up(const Vec3& n) {
    const double l = n.norm();
    return l > 0 ? std::array<float, 3>{float(n[0] / l), float(n[1] / l), float(n[2] / l)}
                 : std::array<float, 3>{0, 0, 1};
}

// The order in which the received points (in index order) are inserted. A mapped object's packets
// each hold points along a Morton curve (spec 23.2), and inserted in that order the bunny comes back
// at 0.0134% RMS with every point; in bit-reversed order of their position in the list, a
// hierarchical spread like the order points had before format 1.7, at 0.0106% as before (half the
// packets lost: 0.0366% against 0.0381%). But the crease recovery (normal_repair.cpp), which runs
// when the points carry normals, leaves a face across a corner in that order on the Box, a slab, a
// tunnelled cube and inward normals (tests/test_creases.cpp: largest error 1.1% to 1.8% of the
// diagonal, against under 1%): with normals, the points go in as they are listed.
std::vector<uint32_t> insertion_order(size_t count, bool with_normals) {
    std::vector<uint32_t> order(count);
    for (uint32_t k = 0; k < count; ++k) order[k] = k;
    if (with_normals || count < 2) return order;
    int bits = 0;
    while ((size_t(1) << bits) < count) ++bits;
    auto reversed = [bits](uint32_t x) {
        uint32_t r = 0;
        for (int b = 0; b < bits; ++b) r |= ((x >> b) & 1u) << (bits - 1 - b);
        return r;
    };
    // The indices by their bit-reversed value: walk the reversed values in order and keep those
    // whose index is in range (reversal is its own inverse), in time linear in the count.
    order.clear();
    for (uint64_t r = 0; r < (uint64_t(1) << bits); ++r)
        if (const uint32_t x = reversed(uint32_t(r)); x < count) order.push_back(x);
    return order;
}

// Distance between two attribute sets, for choosing a face corner's set at a seam.
double attribute_distance(const SurfacePoint& a, const SurfacePoint& b, const ObjectInfo& info) {
    if (info.has(kAttrTexcoord)) {
        double du = a.texcoord[0] - b.texcoord[0], dv = a.texcoord[1] - b.texcoord[1];
        return du * du + dv * dv;
    }
    // A normal left to the surface (format 1.8, (0, 0, 0)) is not compared (spec 24.4).
    if (info.has_normals() && !left_to_surface(a.normal) && !left_to_surface(b.normal))
        return 1.0 - (a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1] + a.normal[2] * b.normal[2]);
    if (info.has(kAttrColor)) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += (a.color[k] - b.color[k]) * (a.color[k] - b.color[k]);
        return s;
    }
    return 0;
}

// Further texture-coordinate sets (format 1.14, spec 30.2): part of a point's attribute set when a
// corner's set is chosen; a record not held (NaN) is not compared.
double sets_distance(const PointTexcoordSets* sets, size_t a, size_t b) {
    double d = 0;
    if (!sets) return d;
    for (const auto& set : *sets) {
        const auto &s = set[a], &t = set[b];
        if (std::isnan(s[0]) || std::isnan(t[0])) continue;
        d += (double(s[0]) - t[0]) * (double(s[0]) - t[0]) + (double(s[1]) - t[1]) * (double(s[1]) - t[1]);
    }
    return d;
}

// The output mesh's further sets: as many arrays as the points have sets.
void start_sets(Mesh& out, const PointTexcoordSets* sets) {
    if (sets) out.texcoord_sets.assign(sets->size(), {});
}

void copy_attributes(Mesh& out, const SurfacePoint& p, const ObjectInfo& info, const PointTexcoordSets* sets = nullptr,
                     size_t index = 0) {
    if (info.has_normals()) out.normals.push_back(p.normal);
    if (info.has(kAttrTexcoord)) out.texcoords.push_back(p.texcoord);
    if (info.has(kAttrColor)) out.colors.push_back(p.color);
    if (sets)
        for (size_t s = 0; s < sets->size(); ++s) out.texcoord_sets[s].push_back((*sets)[s][index]);
}

// Points of an object as a point set; identical positions of a surface object are one vertex.
Mesh point_set(const ObjectInfo& info, const std::vector<SurfacePoint>& points, bool merge_identical,
               const PointTexcoordSets* sets) {
    Mesh out;
    start_sets(out, sets);
    out.is_point_set = true;
    out.colors_have_alpha = info.has(kAttrColorAlpha);
    std::unordered_map<uint64_t, std::vector<uint32_t>> seen;
    for (size_t k = 0; k < points.size(); ++k) {
        const SurfacePoint& p = points[k];
        if (merge_identical) {
            uint64_t key = 0;
            for (float f : p.position) key = key * 1000003u ^ std::hash<float>{}(f);
            auto& list = seen[key];
            bool dup = false;
            for (uint32_t i : list) dup |= out.positions[i] == p.position;
            if (dup) continue;
            list.push_back(uint32_t(out.positions.size()));
        }
        out.positions.push_back(p.position);
        copy_attributes(out, p, info, sets, k);
    }
    // Points without a surface cannot have surface normals (format 1.8): none rather than some.
    if (info.surface_normals && std::any_of(out.normals.begin(), out.normals.end(), left_to_surface)) out.normals.clear();
    return out;
}

// When every point arrived, a connected component holding no original vertex is an artefact of
// the ellipsoids (every part of the original surface has vertices): it is removed.
size_t remove_components_without_originals(Reconstruction& r) {
    DecoderTriMesh& mesh = r.mesh;
    std::vector<int> component(mesh.n_faces(), -1);
    size_t removed = 0;
    std::vector<OpenMesh::FaceHandle> stack, members;
    for (auto f : mesh.faces()) {
        if (component[f.idx()] >= 0) continue;
        members.clear();
        stack.assign(1, f);
        component[f.idx()] = 1;
        bool has_original = false;
        while (!stack.empty()) {
            auto g = stack.back();
            stack.pop_back();
            members.push_back(g);
            for (auto v : mesh.fv_range(g)) has_original |= r.is_original(v);
            for (auto n : mesh.ff_range(g))
                if (component[n.idx()] < 0) component[n.idx()] = 1, stack.push_back(n);
        }
        if (has_original) continue;
        for (auto g : members) {
            std::array<OpenMesh::VertexHandle, 3> vs;
            int k = 0;
            for (auto v : mesh.fv_range(g)) vs[k++] = v;
            r.face_removed(g);
            mesh.delete_face(g, true);
            for (auto v : vs)
                if (mesh.status(v).deleted()) --r.mc_vertices;
        }
        ++removed;
    }
    return removed;
}

}  // namespace

Mesh extract_mesh(const Reconstruction& r, const ObjectInfo& info, const std::vector<SurfacePoint>& points,
                  const PointTexcoordSets* texcoord_sets) {
    const DecoderTriMesh& mesh = r.mesh;
    Mesh out;
    start_sets(out, texcoord_sets);
    out.colors_have_alpha = info.has(kAttrColorAlpha);
    const size_t nv = mesh.n_vertices();
    // Each marching-cubes vertex borrows the attribute sets of its nearest original vertex (along
    // the mesh: a multi-source Dijkstra from every original vertex).
    std::vector<int> source(nv, -1);
    std::vector<double> dist(nv, std::numeric_limits<double>::max());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (auto v : mesh.vertices()) {
        if (r.is_original(v)) {
            source[v.idx()] = v.idx();
            dist[v.idx()] = 0;
            // Only an original next to a marching-cubes vertex can pass its sets on (its other
            // neighbours are at distance 0 already): the others need not enter the queue.
            bool passes_on = false;
            for (auto w : mesh.vv_range(v))
                if (!r.is_original(w)) {
                    passes_on = true;
                    break;
                }
            if (passes_on) queue.push({0.0, v.idx()});
        }
    }
    while (!queue.empty()) {
        auto [d, vi] = queue.top();
        queue.pop();
        if (d > dist[vi]) continue;
        OpenMesh::VertexHandle v(vi);
        for (auto w : mesh.vv_range(v)) {
            double nd = d + (mesh.point(w) - mesh.point(v)).norm();
            if (nd < dist[w.idx()]) {
                dist[w.idx()] = nd;
                source[w.idx()] = source[vi];
                queue.push({nd, w.idx()});
            }
        }
    }
    const bool any_original = r.original_vertices > 0;
    const bool has_attributes =
        any_original && ((info.attributes & (kAttrNormal | kAttrTexcoord | kAttrColor)) != 0 || info.surface_normals);
    // Geometric vertex normals, for vertices with no original to borrow from and for points whose
    // normal is left to the surface (format 1.8): the angle-weighted sum of spec 24.3 over the faces
    // shown around the vertex.
    auto geometric_normal = [&](OpenMesh::VertexHandle v) {
        Vec3 n(0, 0, 0);
        const Vec3 p = mesh.point(v);
        for (auto h : mesh.voh_range(v)) {
            if (mesh.is_boundary(h)) continue;
            n += corner_contribution(mesh.point(mesh.to_vertex_handle(h)) - p,
                                     mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - p);
        }
        return unit_or_up(n);
    };
    auto sets_of = [&](OpenMesh::VertexHandle v) -> const std::vector<uint32_t>* {
        int s = source[v.idx()];
        if (s < 0) return nullptr;
        return &r.vertex_points[s];
    };

    // A vertex normally holds a few attribute sets (a seam's); a hostile stream can put every point
    // at one position. The choice looks at the first kMaxSetsCompared sets of each corner only, so
    // it costs at most that squared per corner rather than the square of the points there (all
    // points of a small model at one position took 33 s).
    constexpr size_t kMaxSetsCompared = 16;
    // (vertex, point) -> output vertex: a vertex's first pair in flat arrays, the further ones (a
    // seam's vertex with several sets) in a map.
    constexpr uint32_t kNone = 0xFFFFFFFFu;
    std::vector<uint32_t> first_set(nv, kNone), first_out(nv, kNone);
    std::unordered_map<uint64_t, uint32_t> more_outputs;
    out.positions.reserve(nv);
    out.triangles.reserve(mesh.n_faces());
    for (auto f : mesh.faces()) {
        OpenMesh::VertexHandle corner[3];
        int k = 0;
        for (auto v : mesh.fv_range(f)) corner[k++] = v;
        std::array<uint32_t, 3> tri;
        for (int c = 0; c < 3; ++c) {
            const auto* sets = has_attributes ? sets_of(corner[c]) : nullptr;
            int64_t chosen = -1;
            if (sets && !sets->empty()) {
                chosen = (*sets)[0];
                if (sets->size() > 1) {
                    double best = std::numeric_limits<double>::max();
                    const size_t candidates = std::min(sets->size(), kMaxSetsCompared);
                    for (size_t si = 0; si < candidates; ++si) {
                        const uint32_t s = (*sets)[si];
                        double cost = 0;
                        for (int o = 0; o < 3; ++o) {
                            if (o == c) continue;
                            const auto* other = sets_of(corner[o]);
                            if (!other || other->empty()) continue;
                            double m = std::numeric_limits<double>::max();
                            const size_t compared = std::min(other->size(), kMaxSetsCompared);
                            for (size_t ti = 0; ti < compared; ++ti)
                                m = std::min(m, attribute_distance(points[s], points[(*other)[ti]], info) +
                                                    sets_distance(texcoord_sets, s, (*other)[ti]));
                            cost += m;
                        }
                        if (cost < best) best = cost, chosen = s;
                    }
                }
            }
            const uint32_t set = chosen < 0 ? kNone : uint32_t(chosen);
            const size_t vi = size_t(corner[c].idx());
            const uint32_t next_index = uint32_t(out.positions.size());
            bool fresh = false;
            uint32_t index;
            if (first_out[vi] == kNone) {
                first_set[vi] = set, first_out[vi] = index = next_index;
                fresh = true;
            } else if (first_set[vi] == set) {
                index = first_out[vi];
            } else {
                auto [it, added] = more_outputs.emplace((uint64_t(uint32_t(vi)) << 32) | set, next_index);
                index = it->second;
                fresh = added;
            }
            if (fresh) {
                const Vec3& p = mesh.point(corner[c]);
                out.positions.push_back({float(p[0]), float(p[1]), float(p[2])});
                if (chosen >= 0) {
                    copy_attributes(out, points[size_t(chosen)], info, texcoord_sets, size_t(chosen));
                    if (info.surface_normals && left_to_surface(out.normals.back()))
                        out.normals.back() = geometric_normal(corner[c]);
                } else if (info.has_normals()) {
                    out.normals.push_back(geometric_normal(corner[c]));
                }
            }
            tri[c] = index;
        }
        out.triangles.push_back(tri);
    }
    // Attribute arrays are either complete or empty.
    if (out.normals.size() != out.positions.size()) out.normals.clear();
    if (out.texcoords.size() != out.positions.size()) out.texcoords.clear();
    if (out.colors.size() != out.positions.size()) out.colors.clear();
    if (out.texcoords.empty()) out.texcoord_sets.clear();
    for (auto& set : out.texcoord_sets)
        if (set.size() != out.positions.size()) out.texcoord_sets.clear();
    return out;
}

bool decode_object(const ObjectInfo& info, const std::vector<Ellipsoid>& ellipsoids,
                   const std::vector<SurfacePoint>& points, int grid_hint, const DecodeOptions& options,
                   size_t object_index, Mesh& out, ObjectDecodeReport& report, std::string& error,
                   const PointTexcoordSets* sets) {
    report = ObjectDecodeReport{};
    report.ellipsoids = ellipsoids.size();
    report.points = points.size();
    report.complete = points.size() >= info.point_count;
    out = Mesh{};
    auto progress = [&](const char* stage, double fraction) {
        if (options.progress) options.progress(stage, fraction);
    };
    auto t0 = std::chrono::steady_clock::now();

    if (info.kind == ObjectKind::PointSet) {
        out = point_set(info, points, false, sets);
        report.vertices_out = out.positions.size();
        report.timings.output = seconds_since(t0);
        return true;
    }
    auto points_only = [&](const std::string& why) {
        out = point_set(info, points, true, sets);
        report.notes.push_back(why + (points.empty() ? ": nothing to build"
                                                     : ": no base surface; writing the " +
                                                           std::to_string(out.positions.size()) +
                                                           " received points as a point set"));
        report.vertices_out = out.positions.size();
        report.timings.output = seconds_since(t0);
        return true;
    };
    if (ellipsoids.empty()) return points_only("no ellipsoid received");

    int resolution = options.grid_resolution > 0 ? options.grid_resolution
                                                 : (grid_hint > 0 ? grid_hint : kDefaultGridResolution);
    if (options.grid_resolution <= 0) {
        // The work follows what arrived (spec 13): lower the resolution until the grid fits.
        resolution = std::clamp(resolution, kMinGridResolution, kMaxGridResolution);
        const double elements = double(ellipsoids.size()) + double(points.size());
        const size_t budget = size_t(std::min<double>(double(kMaxGridNodes),
                                                      double(options.base_grid_nodes) +
                                                          double(options.grid_nodes_per_element) * elements));
        const int wanted = resolution;
        size_t nodes = ellipsoid_grid_nodes(ellipsoids, info.frame, resolution);
        while (nodes > budget && resolution > kMinGridResolution) {
            const int lower = int(std::floor(resolution * std::cbrt(double(budget) / double(nodes))));
            resolution = std::max(kMinGridResolution, std::min(resolution - 1, lower));
            nodes = ellipsoid_grid_nodes(ellipsoids, info.frame, resolution);
        }
        if (resolution != wanted)
            report.notes.push_back("grid " + std::to_string(wanted) + " lowered to " + std::to_string(resolution) +
                                   ": at most " + std::to_string(budget) + " grid nodes for the " +
                                   std::to_string(size_t(elements)) + " ellipsoids and points received");
        // And the rasterizer's work: ellipsoids that each cover much of the object.
        const double work_budget = options.base_raster_work + options.raster_work_per_element * elements;
        const int fits = resolution;
        double work = ellipsoid_raster_work(ellipsoids, info.frame, resolution);
        while (work > work_budget && resolution > kMinGridResolution) {
            const int lower = int(std::floor(resolution * std::cbrt(work_budget / work)));
            resolution = std::max(kMinGridResolution, std::min(resolution - 1, lower));
            work = ellipsoid_raster_work(ellipsoids, info.frame, resolution);
        }
        if (resolution != fits)
            report.notes.push_back("grid " + std::to_string(fits) + " lowered to " + std::to_string(resolution) +
                                   ": the " + std::to_string(ellipsoids.size()) +
                                   " ellipsoids received overlap so much that rasterizing them would visit over " +
                                   std::to_string(uint64_t(work_budget)) + " grid nodes");
    }
    EllipsoidGrid grid;
    report.grid_resolution = resolution;
    progress("rasterize", 0);
    if (!rasterize_ellipsoids(ellipsoids, info.frame, resolution, grid, error, &report.skipped_ellipsoids,
                              options.threads))
        return false;
    report.timings.rasterize = seconds_since(t0);
    progress("rasterize", 1);
    if (report.skipped_ellipsoids > 0)
        report.notes.push_back(std::to_string(report.skipped_ellipsoids) + " degenerate ellipsoid(s) skipped");
    if (grid.empty()) return points_only("no usable ellipsoid");

    auto t1 = std::chrono::steady_clock::now();
    DecoderTriMesh base = marching_cubes(grid);
    // An incomplete object is written with at most face_budget triangles (simplify_filler below).
    // A base far larger than that would only be simplified away, after costing the insertion and the
    // cleanup their time: past eight times the budget, a coarser grid first, to about eight times it
    // (four times cost the 2CylinderEngine at one cycle of 50% loss 0.34% RMS instead of 0.29%).
    const size_t face_budget =
        report.complete || options.faces_per_point <= 0
            ? 0
            : std::max<size_t>(options.min_faces, size_t(options.faces_per_point * double(info.point_count)));
    // With no point received the base is all there is to show (the first picture): a grid for about
    // the budget itself, so that no simplification is needed and the picture stays quick.
    const double base_factor = points.empty() ? 1.0 : 8.0;
    if (face_budget > 0 && options.grid_resolution <= 0 && base.n_faces() > base_factor * double(face_budget) &&
        resolution > kMinGridResolution) {
        const int wanted = resolution;
        resolution = std::max(kMinGridResolution,
                              int(std::floor(resolution * std::sqrt(base_factor * double(face_budget) / double(base.n_faces())))));
        EllipsoidGrid coarser;
        size_t skipped = 0;    // counted already, at the first grid
        std::string ignored;   // a failure keeps the first grid, and the call's error stays empty
        if (resolution < wanted &&
            rasterize_ellipsoids(ellipsoids, info.frame, resolution, coarser, ignored, &skipped, options.threads) &&
            !coarser.empty()) {
            DecoderTriMesh smaller = marching_cubes(coarser);
            if (smaller.n_faces() > 0) {
                report.notes.push_back("grid " + std::to_string(wanted) + " lowered to " + std::to_string(resolution) +
                                       ": a base of " + std::to_string(base.n_faces()) + " triangles for an object of " +
                                       std::to_string(info.point_count) + " points, not all received");
                base = std::move(smaller);
                grid = std::move(coarser);
                report.grid_resolution = resolution;
            }
        }
    }
    const std::vector<char> on_sheet = points_on_sheets(ellipsoids, grid.cell, points);
    grid.value = {};
    report.timings.marching_cubes = seconds_since(t1);
    report.base_vertices = base.n_vertices();
    report.base_faces = base.n_faces();
    if (base.n_faces() == 0) return points_only("the ellipsoids enclose no grid node");
    report.has_surface = true;

    Reconstruction r;
    start_reconstruction(r, std::move(base), info.frame, grid.cell, std::max<size_t>(points.size(), info.point_count),
                         options.reconstruction);
    if (info.has_normals()) r.normals = &points;
    r.sheet_points = &on_sheet;
    if (options.snapshot) options.snapshot(object_index, 0, extract_mesh(r, info, points, sets));

    auto t2 = std::chrono::steady_clock::now();
    double snapshot_time = 0;
    const std::vector<uint32_t> order = insertion_order(points.size(), r.normals != nullptr);
    for (size_t k = 0; k < points.size(); ++k) {
        if (options.deadline && (k & 255) == 0 && std::chrono::steady_clock::now() >= *options.deadline) {
            report.notes.push_back("stopped at the deadline after inserting " + std::to_string(k) + " of " +
                                   std::to_string(points.size()) + " points");
            break;
        }
        const size_t i = order[k];
        OpenMesh::VertexHandle v;
        Insertion kind = insert_point(r, uint32_t(i), points[i].position, v);
        if (kind == Insertion::NoMesh) break;
        if (kind != Insertion::SeamDuplicate) {
            flip_edges_around(r, v);
            collapse_mc_vertices_near(r, v);
            OpenMesh::VertexHandle back;
            if (on_sheet[i] && insert_on_other_side(r, uint32_t(i), points[i].position, v, 3 * grid.cell, back)) {
                ++report.sheet_points;
                flip_edges_around(r, back);
                collapse_mc_vertices_near(r, back);
            }
        }
        if ((k & 1023) == 0) progress("insert points", double(k) / points.size());
        if (options.snapshot && options.snapshot_every > 0 && (k + 1) % options.snapshot_every == 0 &&
            k + 1 < points.size()) {
            auto ts = std::chrono::steady_clock::now();
            options.snapshot(object_index, k + 1, extract_mesh(r, info, points, sets));
            snapshot_time += seconds_since(ts);
        }
    }
    progress("insert points", 1);
    report.timings.insertion = seconds_since(t2) - snapshot_time;

    auto t3 = std::chrono::steady_clock::now();
    // The stream is over: an incomplete one keeps its points' real (wider) spacing, so marching-cubes
    // vertices that close to an original go too.
    if (!report.complete && r.original_vertices > 0)
        r.spacing_scale = std::min(4.0, std::sqrt(double(info.point_count) / double(r.original_vertices)));
    collapse_all_mc_vertices(r, report.complete && !points.empty());
    if (report.complete && r.original_vertices > 0) {
        if (report.sheet_points > 0) remove_sheet_leftovers(r, ellipsoids, grid.cell);
        size_t removed = remove_components_without_originals(r);
        if (removed > 0)
            report.notes.push_back(std::to_string(removed) + " base component(s) with no original vertex removed");
    }
    // Every normal has arrived: faces across creases and folds at corners are put right.
    if (report.complete) agree_with_received_normals(r);
    report.timings.cleanup = seconds_since(t3);

    auto t4 = std::chrono::steady_clock::now();
    out = extract_mesh(r, info, points, sets);
    // The grid's estimate can overshoot a little: a base alone is trimmed only past twice the budget.
    if (face_budget > 0 && (!points.empty() || out.triangles.size() > 2 * face_budget)) {
        report.simplified_faces = detail::simplify_filler(out, points, face_budget);
    }
    report.timings.output = seconds_since(t4);
    report.vertices_out = out.positions.size();
    report.faces_out = out.triangles.size();
    report.mc_vertices_left = r.mc_vertices;
    report.face_splits = r.face_splits;
    report.edge_splits = r.edge_splits;
    report.vertex_moves = r.vertex_moves;
    report.seam_merges = r.seam_merges;
    report.flips = r.flips;
    report.collapses = r.collapses;
    if (report.complete && r.mc_vertices > 0)
        report.notes.push_back(std::to_string(r.mc_vertices) +
                               " marching-cubes vertex(es) could not be collapsed (topology)");
    if (options.snapshot && options.snapshot_every > 0 && !points.empty())
        options.snapshot(object_index, points.size(), out);
    return true;
}

void fill_surface_normals(Mesh& mesh) {
    if (mesh.normals.size() != mesh.positions.size()) return;
    std::vector<uint32_t> open;
    for (uint32_t v = 0; v < mesh.normals.size(); ++v)
        if (left_to_surface(mesh.normals[v])) open.push_back(v);
    if (open.empty()) return;
    std::vector<Vec3> sum(mesh.positions.size(), Vec3(0, 0, 0));
    auto at = [&](uint32_t v) { return Vec3(mesh.positions[v][0], mesh.positions[v][1], mesh.positions[v][2]); };
    for (const auto& t : mesh.triangles) {
        for (int c = 0; c < 3; ++c) {
            const uint32_t i = t[c];
            if (!left_to_surface(mesh.normals[i])) continue;
            const Vec3 p = at(i);
            sum[i] += corner_contribution(at(t[(c + 1) % 3]) - p, at(t[(c + 2) % 3]) - p);
        }
    }
    for (uint32_t v : open) mesh.normals[v] = unit_or_up(sum[v]);
}

size_t shared_base_grid_nodes(const ReceivedStream& stream, const DecodeOptions& options) {
    size_t with_base = 0;
    for (const auto& o : stream.objects()) with_base += o.info && !o.ellipsoids.empty();
    if (with_base == 0) return options.base_grid_nodes;
    return std::min(options.base_grid_nodes, std::max<size_t>(4096, kBaseGridNodesInAll / with_base));
}

namespace {

// Format 1.14 (spec 30.2): the further sets object `object` shows, the first `count` of its
// TEXCOORDS sets: those holding a record, up to the first that holds none (glTF numbers sets
// without gaps); none for an object without texture coordinates.
size_t shown_sets(const ReceivedObject& o) {
    if (!o.info || !o.info->has(kAttrTexcoord)) return 0;
    size_t count = 0;
    while (count < o.texcoord_sets.size() && !o.texcoord_sets[count].records.empty()) ++count;
    return count;
}

// The shown sets' coordinates of the points of `indices` (NaN where a record has not arrived).
PointTexcoordSets point_sets(const ReceivedObject& o, const std::vector<uint32_t>& indices) {
    PointTexcoordSets sets(shown_sets(o));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t s = 0; s < sets.size(); ++s) {
        const ReceivedTexcoordSet& held = o.texcoord_sets[s];
        sets[s].reserve(indices.size());
        for (uint32_t i : indices) {
            const uint16_t* r = held.records.find(i);
            sets[s].push_back(r ? dequantize_texcoord({r[0], r[1]}, held.range) : std::array<float, 2>{nan, nan});
        }
    }
    return sets;
}

// Spec 30.2: a vertex whose point's record has not arrived (or that stands for no point) takes the
// record of the held point nearest to it.
void fill_missing_sets(Mesh& mesh, const ReceivedStream& stream, size_t object) {
    const ReceivedObject& o = stream.objects()[object];
    for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s) {
        auto& values = mesh.texcoord_sets[s];
        if (std::none_of(values.begin(), values.end(), [](const auto& t) { return std::isnan(t[0]); })) continue;
        std::vector<std::array<float, 3>> positions;
        std::vector<std::array<float, 2>> records;
        const ReceivedTexcoordSet& held = o.texcoord_sets[s];
        for (const auto& [i, r] : held.records) {
            const std::optional<QuantizedPoint> p = o.points.find(i);
            if (!p) continue;
            positions.push_back(dequantize_point(*p, *stream.info(), *o.info).position);
            records.push_back(dequantize_texcoord({r[0], r[1]}, held.range));
        }
        if (records.empty()) {  // no held point has a record: the set cannot be shown
            mesh.texcoord_sets.resize(s);
            return;
        }
        std::vector<std::array<uint32_t, 3>> corners(positions.size());
        for (uint32_t k = 0; k < corners.size(); ++k) corners[k] = {k, k, k};
        const TriangleTree tree(positions, corners);
        for (size_t v = 0; v < values.size(); ++v) {
            if (!std::isnan(values[v][0])) continue;
            const auto& q = mesh.positions[v];
            const ClosestPoint c = tree.closest_point({q[0], q[1], q[2]});
            values[v] = records[c.found ? c.triangle : 0];
        }
    }
}

}  // namespace

bool exact_mesh(const ReceivedStream& stream, size_t object, Mesh& out, std::string& why, bool& unusable) {
    unusable = false;
    std::vector<Triangle> triangles;
    std::vector<QuantizedPoint> carried;
    const Error e = exact_layer(stream, object, triangles, carried, why);
    if (e != Error::Ok) {
        unusable = e == Error::MalformedPayload;
        return false;
    }
    const ObjectInfo& info = *stream.objects()[object].info;
    // Every point (index = position), then the vertices the exact layer carries (format 1.11, spec 27).
    std::vector<SurfacePoint> points = stream.points(object);
    points.reserve(points.size() + carried.size());
    for (const QuantizedPoint& q : carried) points.push_back(dequantize_point(q, *stream.info(), info));
    std::vector<uint32_t> vertex(points.size(), UINT32_MAX);
    // Format 1.14: each point's further sets (by index: every point is held); none for a carried vertex.
    std::vector<uint32_t> indices(points.size());
    for (uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
    const PointTexcoordSets sets = point_sets(stream.objects()[object], indices);
    const size_t point_count = info.point_count;
    Mesh m;
    m.colors_have_alpha = info.has(kAttrColorAlpha);
    m.texcoord_sets.assign(sets.size(), {});
    // At most every point and carried vertex, each once (a point no triangle uses is left out).
    m.triangles.reserve(triangles.size());
    m.positions.reserve(points.size());
    if (info.has_normals()) m.normals.reserve(points.size());
    if (info.has(kAttrTexcoord)) m.texcoords.reserve(points.size());
    if (info.has(kAttrColor)) m.colors.reserve(points.size());
    for (const Triangle& t : triangles) {
        std::array<uint32_t, 3> face;
        for (int k = 0; k < 3; ++k) {
            uint32_t& v = vertex[t[k]];
            if (v == UINT32_MAX) {
                v = uint32_t(m.positions.size());
                const SurfacePoint& p = points[t[k]];
                m.positions.push_back(p.position);
                if (info.has_normals()) m.normals.push_back(p.normal);
                if (info.has(kAttrTexcoord)) m.texcoords.push_back(p.texcoord);
                if (info.has(kAttrColor)) m.colors.push_back(p.color);
                for (size_t s = 0; s < sets.size(); ++s)
                    m.texcoord_sets[s].push_back(t[k] < point_count ? sets[s][t[k]]
                                                                    : std::array<float, 2>{NAN, NAN});
            }
            face[k] = v;
        }
        m.triangles.push_back(face);
    }
    // Surface normals (format 1.8, spec 24.4): the exact object's own, over its triangles.
    if (info.surface_normals) fill_surface_normals(m);
    fill_missing_sets(m, stream, object);
    out = std::move(m);
    return true;
}

bool decode_stream(const ReceivedStream& stream, const DecodeOptions& options, std::vector<Mesh>& meshes,
                   StreamDecodeReport& report, std::string& error, std::vector<size_t>* mesh_objects) {
    meshes.clear();
    if (mesh_objects) mesh_objects->clear();
    report = StreamDecodeReport{};
    if (!stream.info()) {
        const std::string why = stream.stream_info_problem();
        if (!why.empty()) {
            error = "no STREAM_INFO packet was accepted (" + why + "): nothing can be decoded";
            return false;
        }
        error = "no STREAM_INFO packet arrived: the object table and quantization frames are unknown, so "
                "nothing can be decoded";
        return false;
    }
    const StreamInfo& info = *stream.info();
    const auto& objects = stream.objects();
    report.objects.resize(objects.size());
    DecodeOptions shared = options;
    shared.base_grid_nodes = shared_base_grid_nodes(stream, options);
    size_t decoded = 0, failed = 0;
    // First the exact layers, side by side on options.threads; then, in order, the objects whose
    // exact layer is whole and what each other object's reconstruction starts from; then the
    // reconstructions, side by side (each object on its own: its mesh, report and error); and last,
    // in order again, their notes and meshes: the result does not depend on the thread count.
    struct Reconstruct {
        size_t object;
        std::vector<char> keep;  // with a region of interest: which of its points to insert
        size_t inserted = 0, held = 0;
        std::string exact_note, error;
        Mesh mesh;
        bool ok = false;
    };
    const unsigned threads = options.snapshot_every > 0 ? 1u : std::max(1u, options.threads);
    // Each exact layer is a function of the stream alone.
    struct Layer {
        bool ok = false, unusable = false;
        std::string why;
        Mesh mesh;
    };
    std::vector<Layer> layers(objects.size());
    std::vector<size_t> with_layer;
    if (options.exact && options.snapshot_every == 0)
        for (size_t i = 0; i < objects.size(); ++i)
            if (objects[i].info && objects[i].connectivity) with_layer.push_back(i);
    detail::parallel_for(with_layer.size(), threads, [&](size_t k) {
        Layer& layer = layers[with_layer[k]];
        layer.ok = exact_mesh(stream, with_layer[k], layer.mesh, layer.why, layer.unusable);
    });
    std::vector<Reconstruct> work;
    for (size_t i = 0; i < objects.size(); ++i) {
        if (!objects[i].info) {
            ++report.objects_without_info;
            report.objects[i].notes.push_back("its STREAM_INFO entry never arrived: skipped");
            continue;
        }
        std::string exact_note;
        if (const auto& c = objects[i].connectivity) {
            report.objects[i].has_connectivity = true;
            report.objects[i].connectivity_bytes = c->received_bytes;
            report.objects[i].connectivity_size = c->coded_size;
        }
        // Snapshots show the reconstruction as points arrive, so they keep to it (spec 13).
        if (options.exact && options.snapshot_every == 0 && objects[i].connectivity) {
            const Layer& layer = layers[i];
            if (layer.ok) {
                const Mesh& mesh = layer.mesh;
                ObjectDecodeReport& r = report.objects[i];
                r.exact = r.complete = r.has_surface = true;
                r.ellipsoids = objects[i].ellipsoids.size();
                r.points = objects[i].points.size();
                r.vertices_out = mesh.positions.size();
                r.faces_out = mesh.triangles.size();
                continue;
            }
            if (layer.unusable) exact_note = "its exact layer is unusable (" + layer.why + "): reconstructed";
        }
        Reconstruct job;
        job.object = i;
        job.exact_note = std::move(exact_note);
        job.inserted = objects[i].points.size();
        // The region of interest is asked here, in order (the caller's function is not asked from
        // several threads); the points themselves are made where the object is reconstructed, so
        // that only the objects under way hold theirs.
        if (options.insert_if) {
            const std::vector<SurfacePoint> points = stream.points(i);
            job.keep.resize(points.size());
            for (size_t k = 0; k < points.size(); ++k) job.keep[k] = options.insert_if(i, points[k].position) ? 1 : 0;
            job.inserted = size_t(std::count(job.keep.begin(), job.keep.end(), 1));
            job.held = points.size() - job.inserted;
        }
        work.push_back(std::move(job));
    }
    // Side by side, one progress for them all: each object's share (by its points) of the work done,
    // its rasterization a tenth of it. Snapshots are made one object after the other.
    std::mutex progress_lock;
    std::vector<double> done(work.size(), 0.0), weight(work.size());
    double total_weight = 0;
    for (size_t k = 0; k < work.size(); ++k) total_weight += weight[k] = double(work[k].inserted) + 1000;
    detail::parallel_for(work.size(), threads, [&](size_t k) {
        Reconstruct& job = work[k];
        const size_t i = job.object;
        std::vector<SurfacePoint> points = stream.points(i);
        // The points' indices, in the same order: only an object with further sets (format 1.14) needs them.
        const bool with_sets = !objects[i].texcoord_sets.empty();
        std::vector<uint32_t> indices;
        if (with_sets) {
            indices.reserve(points.size());
            for (const auto& [index, q] : objects[i].points) indices.push_back(index);
        }
        if (!job.keep.empty()) {
            size_t kept = 0;
            for (size_t j = 0; j < points.size(); ++j)
                if (job.keep[j]) {
                    points[kept] = points[j];
                    if (with_sets) indices[kept] = indices[j];
                    ++kept;
                }
            points.resize(kept);
            if (with_sets) indices.resize(kept);
        }
        const PointTexcoordSets sets = point_sets(objects[i], indices);  // format 1.14
        DecodeOptions own = shared;
        if (work.size() > 1) own.threads = 1;  // the objects share the threads
        if (options.progress && threads > 1 && work.size() > 1)
            own.progress = [&, k](const std::string& stage, double fraction) {
                const std::lock_guard<std::mutex> hold(progress_lock);
                done[k] = stage == "rasterize" ? 0.1 * fraction : 0.1 + 0.9 * fraction;
                double sum = 0;
                for (size_t j = 0; j < work.size(); ++j) sum += weight[j] * done[j];
                options.progress("decode objects", sum / total_weight);
            };
        job.ok = decode_object(*objects[i].info, stream.ellipsoids(i), points, info.grid_hint, own, i, job.mesh,
                               report.objects[i], job.error, sets.empty() ? nullptr : &sets);
    });
    size_t next = 0;  // the next job, in object order
    for (size_t i = 0; i < objects.size(); ++i) {
        if (layers[i].ok) {
            ++decoded;
            layers[i].mesh.name = "object" + std::to_string(i);
            meshes.push_back(std::move(layers[i].mesh));
            if (mesh_objects) mesh_objects->push_back(i);
            continue;
        }
        if (next == work.size() || work[next].object != i) continue;  // no STREAM_INFO entry
        Reconstruct& job = work[next++];
        if (!job.ok) {
            // One object that cannot be built does not cost the others theirs.
            if (!job.exact_note.empty()) report.objects[i].notes.push_back(job.exact_note);
            report.objects[i].notes.push_back("not decoded: " + job.error);
            error += (error.empty() ? "" : "; ") + ("object " + std::to_string(i) + ": " + job.error);
            ++failed;
            continue;
        }
        if (!job.exact_note.empty()) report.objects[i].notes.push_back(job.exact_note);
        if (job.held > 0)
            report.objects[i].notes.push_back(std::to_string(job.held) + " of " +
                                              std::to_string(job.held + job.inserted) +
                                              " points held outside the region of interest (not inserted)");
        if (const auto& c = objects[i].connectivity) {  // decode_object starts its report afresh
            report.objects[i].has_connectivity = true;
            report.objects[i].connectivity_bytes = c->received_bytes;
            report.objects[i].connectivity_size = c->coded_size;
        }
        ++decoded;
        const auto& t = report.objects[i].timings;
        report.timings.rasterize += t.rasterize;
        report.timings.marching_cubes += t.marching_cubes;
        report.timings.insertion += t.insertion;
        report.timings.cleanup += t.cleanup;
        report.timings.output += t.output;
        Mesh& mesh = job.mesh;
        if (mesh.positions.empty()) continue;
        fill_missing_sets(mesh, stream, i);
        mesh.name = "object" + std::to_string(i);
        meshes.push_back(std::move(mesh));
        if (mesh_objects) mesh_objects->push_back(i);
    }
    report.objects_failed = failed;
    if (failed > 0 && decoded == 0) return false;
    error.clear();  // the failures are in the objects' notes
    return true;
}

}  // namespace ellicast
