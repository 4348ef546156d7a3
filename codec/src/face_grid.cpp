// Nearest triangle of a changing mesh: a uniform grid of face lists with lazy deletion.
#include "ellicast/codec/decoder.h"

#include "closest_point.h"
#include "mesh_ops.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellicast {

using Vec3 = OpenMesh::Vec3d;

void FaceGrid::reset(const Vec3& lo, const Vec3& hi, double cell, size_t max_cells) {
    lo_ = lo;
    cell_ = cell > 0 ? cell : 1;
    for (int k = 0; k < 3; ++k) {
        double extent = std::max(0.0, hi[k] - lo[k]);
        dims_[k] = std::clamp(int(std::ceil(extent / cell_)) + 1, 1, 1024);
    }
    // Keep the number of cells bounded (a few million at most).
    max_cells = std::clamp<size_t>(max_cells, 1, size_t(4) << 20);
    while (size_t(dims_[0]) * dims_[1] * dims_[2] > max_cells) {
        cell_ *= 1.25;
        for (int k = 0; k < 3; ++k)
            dims_[k] = std::clamp(int(std::ceil(std::max(0.0, hi[k] - lo[k]) / cell_)) + 1, 1, 1024);
    }
    cells_.assign(size_t(dims_[0]) * dims_[1] * dims_[2], {});
    version_.clear();
    seen_.clear();
    stamp_ = 0;
    live_ = 0;
}

void FaceGrid::cell_range(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f, std::array<int, 3>& lo,
                          std::array<int, 3>& hi) const {
    const auto corner = detail::corners(mesh, f);
    const Vec3 &a = mesh.point(corner[0]), &b = mesh.point(corner[1]), &c = mesh.point(corner[2]);
    for (int k = 0; k < 3; ++k) {
        const double mn = std::min({a[k], b[k], c[k]}), mx = std::max({a[k], b[k], c[k]});
        lo[k] = std::clamp(int(std::floor((mn - lo_[k]) / cell_)), 0, dims_[k] - 1);
        hi[k] = std::clamp(int(std::floor((mx - lo_[k]) / cell_)), 0, dims_[k] - 1);
    }
}

void FaceGrid::add_entries(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f) {
    std::array<int, 3> lo, hi;
    cell_range(mesh, f, lo, hi);
    const uint32_t ver = version_[f.idx()];
    const size_t span = size_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    // A large face (long and thin ones appear while points far from the base arrive) goes only into
    // the cells its triangle can touch: those whose centre is within half a cell diagonal of it.
    const bool exact = span > 8;
    Vec3 a, b, c;
    if (exact) {
        const auto corner = detail::corners(mesh, f);
        a = mesh.point(corner[0]), b = mesh.point(corner[1]), c = mesh.point(corner[2]);
    }
    const double reach2 = 0.75 * cell_ * cell_ * 1.0001;  // (sqrt(3)/2 cell)^2
    Vec3 normal(0, 0, 0);
    if (exact) {
        normal = OpenMesh::cross(b - a, c - a);
        double l = normal.norm();
        if (l > 0) normal /= l;
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) {
                if (exact) {
                    Vec3 centre = lo_ + Vec3((i + 0.5) * cell_, (j + 0.5) * cell_, (k + 0.5) * cell_);
                    double plane = OpenMesh::dot(centre - a, normal);
                    if (plane * plane > reach2) continue;  // far from the triangle's plane
                    std::array<double, 3> bary;
                    if ((detail::closest_point_on_triangle(centre, a, b, c, &bary) - centre).sqrnorm() > reach2) continue;
                }
                auto& list = cells_[cell_of(i, j, k)];
                // Drop stale entries of this cell before it grows: keeps every cell within about twice
                // its live entries, at a cost proportional to the growth.
                if (list.size() == list.capacity() && list.size() >= 8) {
                    list.erase(std::remove_if(list.begin(), list.end(),
                                              [&](const Entry& e) { return e.version != version_[e.face]; }),
                               list.end());
                }
                list.push_back({uint32_t(f.idx()), ver});
            }
}

void FaceGrid::build(const DecoderTriMesh& mesh) {
    for (auto& c : cells_) c.clear();
    version_.assign(mesh.n_faces(), 0);
    live_ = 0;
    for (auto f : mesh.faces()) {
        version_[f.idx()] = 1;
        ++live_;
        add_entries(mesh, f);
    }
}

void FaceGrid::update(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f) {
    if (size_t(f.idx()) >= version_.size()) version_.resize(mesh.n_faces(), 0);
    uint32_t& ver = version_[f.idx()];
    if (ver & 1) {
        // Its old entries go stale; add_entries drops them when their cell grows.
        ver += 2;
    } else {
        ver += 1;
        ++live_;
    }
    add_entries(mesh, f);
}

void FaceGrid::remove(OpenMesh::FaceHandle f) {
    if (size_t(f.idx()) >= version_.size()) return;
    uint32_t& ver = version_[f.idx()];
    if (ver & 1) {
        ver += 1;
        --live_;
    }
}

OpenMesh::FaceHandle FaceGrid::nearest(const DecoderTriMesh& mesh, const Vec3& p, Vec3& closest,
                                       std::array<double, 3>& bary,
                                       const std::function<bool(OpenMesh::FaceHandle)>& accept,
                                       double max_distance) const {
    OpenMesh::FaceHandle best;
    if (live_ == 0) return best;
    if (seen_.size() < version_.size()) seen_.resize(version_.size(), 0);
    if (++stamp_ == 0) {
        std::fill(seen_.begin(), seen_.end(), 0);
        stamp_ = 1;
    }
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
    double best_d2 = max_distance < std::numeric_limits<double>::max() ? max_distance * max_distance
                                                                       : std::numeric_limits<double>::max();
    const int max_ring = std::max({dims_[0], dims_[1], dims_[2]});
    auto visit = [&](int i, int j, int k) {
        for (const Entry& e : cells_[cell_of(i, j, k)]) {
            if (e.version != version_[e.face] || seen_[e.face] == stamp_) continue;
            seen_[e.face] = stamp_;
            OpenMesh::FaceHandle f(int(e.face));
            if (accept && !accept(f)) continue;
            const auto corner = detail::corners(mesh, f);
            const Vec3& a = mesh.point(corner[0]);
            const Vec3& b = mesh.point(corner[1]);
            const Vec3& cc = mesh.point(corner[2]);
            std::array<double, 3> bc;
            Vec3 q = detail::closest_point_on_triangle(p, a, b, cc, &bc);
            double d2 = (q - p).sqrnorm();
            if (d2 < best_d2) best_d2 = d2, best = f, closest = q, bary = bc;
        }
    };
    // Distance from p to the faces of its cell's box, to bound what lies beyond each ring.
    double to_low[3], to_high[3];
    for (int k = 0; k < 3; ++k) {
        to_low[k] = p[k] - (lo_[k] + c[k] * cell_);
        to_high[k] = lo_[k] + (c[k] + 1) * cell_ - p[k];
    }
    auto cell_gap2 = [&](int i, int j, int k) {
        // Squared distance from p to cell (i, j, k), from the offsets to p's own cell.
        int idx[3] = {i, j, k};
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
            int off = idx[a] - c[a];
            double g = off > 0 ? to_high[a] + (off - 1) * cell_ : (off < 0 ? to_low[a] + (-off - 1) * cell_ : 0.0);
            if (g > 0) d2 += g * g;
        }
        return d2;
    };
    for (int r = 0; r <= max_ring; ++r) {
        int i0 = c[0] - r, i1 = c[0] + r, j0 = c[1] - r, j1 = c[1] + r, k0 = c[2] - r, k1 = c[2] + r;
        for (int k = std::max(k0, 0); k <= std::min(k1, dims_[2] - 1); ++k)
            for (int j = std::max(j0, 0); j <= std::min(j1, dims_[1] - 1); ++j) {
                bool shell = (k == k0 || k == k1 || j == j0 || j == j1);
                if (shell) {
                    for (int i = std::max(i0, 0); i <= std::min(i1, dims_[0] - 1); ++i)
                        if (cell_gap2(i, j, k) < best_d2) visit(i, j, k);
                } else {
                    if (i0 >= 0 && cell_gap2(i0, j, k) < best_d2) visit(i0, j, k);
                    if (i1 < dims_[0] && cell_gap2(i1, j, k) < best_d2) visit(i1, j, k);
                }
            }
        // Everything beyond ring r is at least this far from p.
        double reach = std::numeric_limits<double>::max();
        for (int a = 0; a < 3; ++a) {
            if (c[a] - r > 0) reach = std::min(reach, std::max(0.0, to_low[a]) + r * cell_);
            if (c[a] + r < dims_[a] - 1) reach = std::min(reach, std::max(0.0, to_high[a]) + r * cell_);
        }
        if (best.is_valid() && best_d2 <= reach * reach) break;
        if (reach > max_distance) break;  // nothing accepted within max_distance
        if (reach == std::numeric_limits<double>::max()) break;  // the whole grid was visited
    }
    return best;
}

}  // namespace ellicast
