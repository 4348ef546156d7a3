// Sheets: surface with no inside (a flat figure, a single-sided panel) gets flat ellipsoids that
// straddle it, so its base is a thin closed shell with two sides standing for one surface. A point of
// the sheet goes into both sides; otherwise each side gets a random half of the points, and the
// two halves, flattened onto one plane, leave each other's gaps open.
#include "ellicast/codec/decoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellicast {

using Vec3 = OpenMesh::Vec3d;

namespace {

struct FlatEllipsoid {
    Vec3 center;
    Vec3 axis[3];    // unit axes (columns of the rotation)
    double inv_r[3];  // 1 / radius
    int thin;         // the axis of the smallest radius
    double bound;     // largest radius
};

// Whether e is flat: thinner than two grid cells, twice as wide as thick both ways (a disc, not a
// needle: a needle's side holds surface points at the middle of its thickness). Fills f when it is.
bool make_flat(const Ellipsoid& e, double cell, FlatEllipsoid& f) {
    const double lo = std::min({e.radii[0], e.radii[1], e.radii[2]});
    const double hi = std::max({e.radii[0], e.radii[1], e.radii[2]});
    const double mid = double(e.radii[0]) + e.radii[1] + e.radii[2] - lo - hi;
    if (!(lo > 0) || !(lo <= 2 * cell) || !(mid >= 2 * lo) || !std::isfinite(hi)) return false;
    const double w = e.rotation[0], x = e.rotation[1], y = e.rotation[2], z = e.rotation[3];
    const double n = std::sqrt(w * w + x * x + y * y + z * z);
    if (!(n > 0) || !std::isfinite(n)) return false;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(e.center[k])) return false;
    const double a = w / n, b = x / n, c = y / n, d = z / n;
    f.center = Vec3(e.center[0], e.center[1], e.center[2]);
    // Columns of the rotation matrix of the unit quaternion (a, b, c, d).
    f.axis[0] = Vec3(1 - 2 * (c * c + d * d), 2 * (b * c + a * d), 2 * (b * d - a * c));
    f.axis[1] = Vec3(2 * (b * c - a * d), 1 - 2 * (b * b + d * d), 2 * (c * d + a * b));
    f.axis[2] = Vec3(2 * (b * d + a * c), 2 * (c * d - a * b), 1 - 2 * (b * b + c * c));
    for (int k = 0; k < 3; ++k) f.inv_r[k] = 1.0 / e.radii[k];
    f.thin = e.radii[0] == lo ? 0 : (e.radii[1] == lo ? 1 : 2);
    f.bound = hi;
    return true;
}

// The flat ellipsoids of an object, found by the points they may hold: their reach (a ball of their
// largest radius plus `grow` around the centre) in a bounding-box tree over leaves of 8, the
// ellipsoids in Morton order of their centres. It holds indices, not prepared ellipsoids (a stream of
// a million ellipsoids would otherwise cost 136 MB here), about 16 bytes an ellipsoid. A query
// checks at most kMaxChecks ellipsoids whose boxes hold the point: honest streams overlap a few,
// a hostile one piling discs on one spot would make every query visit all of them.
class FlatIndex {
public:
    static constexpr size_t kMaxChecks = 512;

    FlatIndex(const std::vector<Ellipsoid>& ellipsoids, double cell, double grow)
        : ellipsoids_(ellipsoids), cell_(cell) {
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::max(), hi[k] = -lo[k];
        std::vector<uint32_t> flat;
        for (size_t i = 0; i < ellipsoids.size(); ++i) {
            FlatEllipsoid f;
            if (!make_flat(ellipsoids[i], cell, f)) continue;
            flat.push_back(uint32_t(i));
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], f.center[k]), hi[k] = std::max(hi[k], f.center[k]);
        }
        if (flat.empty()) return;
        std::vector<uint64_t> keyed(flat.size());
        for (size_t j = 0; j < flat.size(); ++j) {
            const Ellipsoid& e = ellipsoids[flat[j]];
            uint64_t code = 0;
            for (int k = 0; k < 3; ++k) {
                const double span = hi[k] - lo[k];
                const uint64_t q = span > 0 ? std::min<uint64_t>(1023, uint64_t((e.center[k] - lo[k]) / span * 1024)) : 0;
                for (int b = 0; b < 10; ++b) code |= ((q >> b) & 1) << (3 * b + k);
            }
            keyed[j] = code << 32 | flat[j];
        }
        flat.clear();
        flat.shrink_to_fit();
        std::sort(keyed.begin(), keyed.end());
        order_.resize(keyed.size());
        for (size_t j = 0; j < keyed.size(); ++j) order_[j] = uint32_t(keyed[j]);
        keyed.clear();
        keyed.shrink_to_fit();
        leaves_ = 1;
        while (leaves_ * kLeaf < order_.size()) leaves_ *= 2;
        boxes_.assign(2 * leaves_, Box{});
        for (size_t j = 0; j < order_.size(); ++j) {
            FlatEllipsoid f;
            make_flat(ellipsoids[order_[j]], cell, f);
            Box& b = boxes_[leaves_ + j / kLeaf];
            const double r = f.bound + grow;
            for (int k = 0; k < 3; ++k) {
                b.lo[k] = std::min(b.lo[k], down(f.center[k] - r));
                b.hi[k] = std::max(b.hi[k], up(f.center[k] + r));
            }
        }
        for (size_t i = leaves_ - 1; i >= 1; --i)
            for (int k = 0; k < 3; ++k) {
                boxes_[i].lo[k] = std::min(boxes_[2 * i].lo[k], boxes_[2 * i + 1].lo[k]);
                boxes_[i].hi[k] = std::max(boxes_[2 * i].hi[k], boxes_[2 * i + 1].hi[k]);
            }
    }

    bool empty() const { return order_.empty(); }

    // True when `holds` is true of a flat ellipsoid whose box holds p (checking at most kMaxChecks).
    template <class Holds>
    bool any(const Vec3& p, Holds holds) const {
        if (order_.empty()) return false;
        size_t checks = 0;
        size_t stack[64];
        int top = 0;
        stack[top++] = 1;
        while (top > 0) {
            const size_t i = stack[--top];
            const Box& b = boxes_[i];
            if (!(p[0] >= b.lo[0] && p[0] <= b.hi[0] && p[1] >= b.lo[1] && p[1] <= b.hi[1] && p[2] >= b.lo[2] &&
                  p[2] <= b.hi[2]))
                continue;
            if (i >= leaves_) {
                const size_t first = (i - leaves_) * kLeaf, last = std::min(order_.size(), first + kLeaf);
                for (size_t j = first; j < last; ++j) {
                    if (++checks > kMaxChecks) return false;
                    FlatEllipsoid f;
                    make_flat(ellipsoids_[order_[j]], cell_, f);
                    if (holds(f)) return true;
                }
                continue;
            }
            stack[top++] = 2 * i + 1;
            stack[top++] = 2 * i;
        }
        return false;
    }

private:
    static constexpr size_t kLeaf = 8;
    struct Box {
        float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                       std::numeric_limits<float>::infinity()};
        float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity()};
    };
    // Floats rounded outward, so that a box holds every point the exact test may accept.
    static float down(double x) {
        float f = float(x);
        return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
    }
    static float up(double x) {
        float f = float(x);
        return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
    }
    const std::vector<Ellipsoid>& ellipsoids_;
    double cell_;
    std::vector<uint32_t> order_;  // flat ellipsoids' indices in Morton order of their centres
    size_t leaves_ = 0;
    std::vector<Box> boxes_;  // node i's children 2i and 2i + 1; leaves from leaves_
};

// p's squared ellipsoidal coordinates in f: across its thickness and along its plane.
void flat_coordinates(const FlatEllipsoid& f, const Vec3& p, double& across, double& along) {
    across = along = 0;
    const Vec3 d = p - f.center;
    for (int k = 0; k < 3; ++k) {
        const double t = OpenMesh::dot(d, f.axis[k]) * f.inv_r[k];
        (k == f.thin ? across : along) += t * t;
    }
}

}  // namespace

std::vector<char> points_on_sheets(const std::vector<Ellipsoid>& ellipsoids, double cell,
                                   const std::vector<SurfacePoint>& points) {
    std::vector<char> on_sheet(points.size(), 0);
    const FlatIndex flat(ellipsoids, cell, 0);
    if (flat.empty()) return on_sheet;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 p(points[i].position[0], points[i].position[1], points[i].position[2]);
        on_sheet[i] = flat.any(p, [&](const FlatEllipsoid& f) {
            if ((p - f.center).sqrnorm() > f.bound * f.bound) return false;
            // Well inside the ellipsoid across its thickness: an ellipsoid kept inside a surface
            // never holds a point of it there, so this one straddles a sheet.
            double across, along;
            flat_coordinates(f, p, across, along);
            return across <= 0.25 && along <= 1;
        });
    }
    return on_sheet;
}

bool insert_on_other_side(Reconstruction& r, uint32_t point_index, const std::array<float, 3>& position,
                          OpenMesh::VertexHandle first, double reach, OpenMesh::VertexHandle& vertex) {
    DecoderTriMesh& mesh = r.mesh;
    const Vec3 p(position[0], position[1], position[2]);
    Vec3 normal(0, 0, 0);
    for (auto f : mesh.vf_range(first)) {
        auto it = mesh.cfv_iter(f);
        const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
        normal += OpenMesh::cross(b - a, c - a);
    }
    const double length = normal.norm();
    if (!(length > 0)) return false;  // a sheet's rim: its faces already face both ways
    normal /= length;
    // The nearest face within reach that faces the other way and is not around `first`.
    Vec3 closest;
    std::array<double, 3> bary;
    auto other_side = [&](OpenMesh::FaceHandle f) {
        auto it = mesh.cfv_iter(f);
        const OpenMesh::VertexHandle va = *it, vb = *++it, vc = *++it;
        if (va == first || vb == first || vc == first) return false;
        const Vec3 n = OpenMesh::cross(mesh.point(vb) - mesh.point(va), mesh.point(vc) - mesh.point(va));
        const double l = n.norm();
        return l > 0 && OpenMesh::dot(n, normal) < -0.5 * l;
    };
    OpenMesh::FaceHandle f = r.faces.nearest(mesh, p, closest, bary, other_side, reach);
    if (!f.is_valid()) return false;
    // Once both sides lie flat on the sheet, the nearest face can be one beside the point rather
    // than under it, and a split there would fold. Walk towards the face under the point.
    OpenMesh::VertexHandle corner[3];
    auto weights = [&](OpenMesh::FaceHandle face) {
        int n = 0;
        for (auto v : mesh.fv_range(face)) corner[n++] = v;  // FaceGrid::nearest's corner order
        const Vec3 a = mesh.point(corner[0]), b = mesh.point(corner[1]), c = mesh.point(corner[2]);
        const Vec3 nf = OpenMesh::cross(b - a, c - a);
        const double n2 = nf.sqrnorm();
        std::array<double, 3> w{OpenMesh::dot(OpenMesh::cross(c - b, p - b), nf) / n2,
                                OpenMesh::dot(OpenMesh::cross(a - c, p - c), nf) / n2, 0.0};
        w[2] = 1 - w[0] - w[1];
        return w;
    };
    const OpenMesh::FaceHandle nearest = f;
    std::array<double, 3> w = weights(f);
    for (int step = 0; step < 16; ++step) {
        const int worst = int(std::min_element(w.begin(), w.end()) - w.begin());
        if (!(w[worst] < 0)) break;
        OpenMesh::FaceHandle next;  // across the edge opposite the most negative corner
        for (auto h : mesh.fh_range(f))
            if (mesh.from_vertex_handle(h) != corner[worst] && mesh.to_vertex_handle(h) != corner[worst])
                next = mesh.opposite_face_handle(h);
        if (!next.is_valid() || !other_side(next)) break;
        f = next;
        w = weights(f);
    }
    if (std::isfinite(w[0] + w[1] + w[2]) && *std::min_element(w.begin(), w.end()) >= 0) {
        bary = w;
    } else if (f != nearest) {
        double sum = 0;
        for (double& x : w) sum += (x = std::isfinite(x) ? std::max(0.0, x) : 0.0);
        bary = sum > 0 ? std::array<double, 3>{w[0] / sum, w[1] / sum, w[2] / sum}
                       : std::array<double, 3>{1.0 / 3, 1.0 / 3, 1.0 / 3};
    }
    insert_into_face(r, point_index, position, f, bary, vertex);
    return true;
}


size_t remove_sheet_leftovers(Reconstruction& r, const std::vector<Ellipsoid>& ellipsoids, double cell) {
    if (r.mc_vertices == 0) return 0;
    const FlatIndex flat(ellipsoids, cell, cell);
    if (flat.empty()) return 0;
    DecoderTriMesh& mesh = r.mesh;
    std::vector<OpenMesh::VertexHandle> leftovers;
    for (auto v : mesh.vertices()) {
        if (r.is_original(v)) continue;
        const Vec3 p = mesh.point(v);
        const bool leftover = flat.any(p, [&](FlatEllipsoid f) {
            // On the shell of a flat ellipsoid: inside it grown by a cell (marching cubes places
            // its vertices on grid edges, up to a cell off the ellipsoid's surface).
            if ((p - f.center).norm() > f.bound + cell) return false;
            for (double& inv : f.inv_r) inv = 1 / (1 / inv + cell);
            double across, along;
            flat_coordinates(f, p, across, along);
            return across + along <= 1;
        });
        if (leftover) leftovers.push_back(v);
    }
    size_t removed = 0;
    for (auto v : leftovers) {
        if (mesh.status(v).deleted()) continue;
        std::vector<OpenMesh::FaceHandle> faces(mesh.vf_begin(v), mesh.vf_end(v));
        // Every point keeps a face: an original vertex whose faces all touch v stays with them.
        bool keeps_all = true;
        for (auto u : mesh.vv_range(v)) {
            if (!r.is_original(u)) continue;
            bool other = false;
            for (auto f : mesh.vf_range(u))
                if (std::find(faces.begin(), faces.end(), f) == faces.end()) other = true;
            keeps_all &= other;
        }
        if (!keeps_all) {
            // Then v moves onto its nearest original neighbour: its faces shrink to slivers there.
            OpenMesh::VertexHandle nearest;
            double best = std::numeric_limits<double>::max();
            for (auto u : mesh.vv_range(v)) {
                const double d = (mesh.point(u) - mesh.point(v)).sqrnorm();
                if (r.is_original(u) && d < best) best = d, nearest = u;
            }
            if (nearest.is_valid()) {
                mesh.set_point(v, mesh.point(nearest));
                reindex_faces_around(r, v);
            }
            continue;
        }
        for (auto f : faces) {
            std::array<OpenMesh::VertexHandle, 3> vs;
            int k = 0;
            for (auto u : mesh.fv_range(f)) vs[k++] = u;
            r.face_removed(f);
            mesh.delete_face(f, true);
            for (auto u : vs)
                if (mesh.status(u).deleted() && !r.is_original(u)) --r.mc_vertices, ++removed;
        }
    }
    return removed;
}

}  // namespace ellicast
