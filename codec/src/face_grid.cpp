// Nearest triangle of a changing mesh: a uniform grid of face lists, brought up to date lazily.
//
// A changed face is only marked; the marked faces are (re)registered at the next query, once each
// however often they changed in between (a split, then the flips around it, then a collapse). Each
// registration bumps the face's version: its older entries go stale, are skipped, and are dropped
// from a cell whenever it would grow. Each entry carries a bounding sphere of its triangle: a query
// computes the exact closest point only for faces whose sphere could beat the best so far, nearest
// sphere first. Among faces at the same distance the one with the smallest index wins, so the
// answer depends on the mesh alone, not on the order in which its faces were registered.
#include "ellicast/codec/decoder.h"

#include "closest_point.h"

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
    dirty_flag_.clear();
    dirty_.clear();
    live_ = 0;
}

void FaceGrid::cell_range(const Vec3& mn, const Vec3& mx, Range& range) const {
    for (int k = 0; k < 3; ++k) {
        range.lo[k] = int16_t(std::clamp(int(std::floor((mn[k] - lo_[k]) / cell_)), 0, dims_[k] - 1));
        range.hi[k] = int16_t(std::clamp(int(std::floor((mx[k] - lo_[k]) / cell_)), 0, dims_[k] - 1));
    }
}

void FaceGrid::add_entries(const DecoderTriMesh& mesh, OpenMesh::FaceHandle f) {
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
    Vec3 mn = a, mx = a;
    mn.minimize(b), mx.maximize(b);
    mn.minimize(c), mx.maximize(c);
    Range range;
    cell_range(mn, mx, range);
    // The bounding sphere, in single precision around a rounded centre and rounded outwards.
    Entry entry;
    entry.face = uint32_t(f.idx());
    entry.version = version_[f.idx()];
    const Vec3 centre = (a + b + c) / 3.0;
    for (int k = 0; k < 3; ++k) entry.centre[k] = float(centre[k]);
    const Vec3 cf(entry.centre[0], entry.centre[1], entry.centre[2]);
    const double r = std::sqrt(std::max({(a - cf).sqrnorm(), (b - cf).sqrnorm(), (c - cf).sqrnorm()}));
    entry.radius = std::isfinite(r) ? float(r * (1 + 1e-6)) + 1e-30f : std::numeric_limits<float>::infinity();

    const size_t span = size_t(range.hi[0] - range.lo[0] + 1) * (range.hi[1] - range.lo[1] + 1) *
                        (range.hi[2] - range.lo[2] + 1);
    // A large face (long and thin ones appear while points far from the base arrive) goes only into
    // the cells its triangle can touch: those whose centre is within half a cell diagonal of it.
    const bool exact = span > 8;
    const double reach2 = 0.75 * cell_ * cell_ * 1.0001;  // (sqrt(3)/2 cell)^2
    Vec3 normal(0, 0, 0);
    if (exact) {
        normal = OpenMesh::cross(b - a, c - a);
        double l = normal.norm();
        if (l > 0) normal /= l;
    }
    for (int k = range.lo[2]; k <= range.hi[2]; ++k)
        for (int j = range.lo[1]; j <= range.hi[1]; ++j)
            for (int i = range.lo[0]; i <= range.hi[0]; ++i) {
                if (exact) {
                    Vec3 centre_ijk = lo_ + Vec3((i + 0.5) * cell_, (j + 0.5) * cell_, (k + 0.5) * cell_);
                    double plane = OpenMesh::dot(centre_ijk - a, normal);
                    if (plane * plane > reach2) continue;  // far from the triangle's plane
                    if ((detail::closest_point_on_triangle(centre_ijk, a, b, c) - centre_ijk).sqrnorm() > reach2) continue;
                }
                auto& list = cells_[cell_of(i, j, k)];
                // Drop stale entries of this cell before it grows: keeps every cell within about twice
                // its live entries, at a cost proportional to the growth.
                if (list.size() == list.capacity() && list.size() >= 8) {
                    list.erase(std::remove_if(list.begin(), list.end(),
                                              [&](const Entry& e) { return e.version != version_[e.face]; }),
                               list.end());
                }
                list.push_back(entry);
            }
}

void FaceGrid::grow_to(size_t faces) {
    if (version_.size() < faces) {
        const size_t size = std::max(faces, version_.size() + version_.size() / 2);
        version_.resize(size, 0);
        dirty_flag_.resize(size, 0);
    }
}

void FaceGrid::build(const DecoderTriMesh& mesh) {
    for (auto& c : cells_) c.clear();
    version_.assign(mesh.n_faces(), 0);
    dirty_flag_.assign(mesh.n_faces(), 0);
    dirty_.clear();
    live_ = 0;
    for (auto f : mesh.faces()) {
        version_[f.idx()] = 1;
        ++live_;
        add_entries(mesh, f);
    }
}

void FaceGrid::update(const DecoderTriMesh& /*mesh*/, OpenMesh::FaceHandle f) {
    grow_to(size_t(f.idx()) + 1);
    if (dirty_flag_[f.idx()]) return;
    dirty_flag_[f.idx()] = 1;
    dirty_.push_back(uint32_t(f.idx()));
}

void FaceGrid::remove(OpenMesh::FaceHandle f) {
    if (size_t(f.idx()) >= version_.size()) return;
    uint32_t& ver = version_[f.idx()];
    if (ver & 1) {  // its entries go stale
        ver += 1;
        --live_;
    }
}

void FaceGrid::flush(const DecoderTriMesh& mesh) {
    for (uint32_t fi : dirty_) {
        if (!dirty_flag_[fi]) continue;
        dirty_flag_[fi] = 0;
        const OpenMesh::FaceHandle f{int(fi)};
        if (mesh.status(f).deleted()) {
            remove(f);
            continue;
        }
        uint32_t& ver = version_[fi];
        if (ver & 1) {
            ver += 2;  // the old entries go stale
        } else {
            ver += 1;
            ++live_;
        }
        add_entries(mesh, f);
    }
    dirty_.clear();
}

OpenMesh::FaceHandle FaceGrid::nearest(const DecoderTriMesh& mesh, const Vec3& p, Vec3& closest,
                                       std::array<double, 3>& bary,
                                       const std::function<bool(OpenMesh::FaceHandle)>& accept,
                                       double max_distance) {
    flush(mesh);
    OpenMesh::FaceHandle best;
    if (live_ == 0) return best;
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
    double best_d2 = max_distance < std::numeric_limits<double>::max() ? max_distance * max_distance
                                                                       : std::numeric_limits<double>::max();
    const int max_ring = std::max({dims_[0], dims_[1], dims_[2]});
    // Whether a sphere's lower bound on the distance can still reach the best (with a margin: the
    // bound is computed in single-precision coordinates).
    auto may_beat = [&](double lower) { return !(lower > 0 && lower * lower > best_d2 * (1 + 1e-9)); };
    auto evaluate = [&](const Entry& en) {
        if (en.version != version_[en.face]) return;  // stale
        const OpenMesh::FaceHandle f{int(en.face)};
        if (accept && !accept(f)) return;
        auto fv = mesh.cfv_iter(f);
        const Vec3& a = mesh.point(*fv);
        const Vec3& b = mesh.point(*++fv);
        const Vec3& cc = mesh.point(*++fv);
        std::array<double, 3> bc;
        Vec3 q = detail::closest_point_on_triangle(p, a, b, cc, &bc);
        double d2 = (q - p).sqrnorm();
        if (d2 < best_d2 || (d2 == best_d2 && best.is_valid() && f.idx() < best.idx()))
            best_d2 = d2, best = f, closest = q, bary = bc;
    };
    auto visit = [&](int i, int j, int k) {
        const auto& list = cells_[cell_of(i, j, k)];
        if (list.empty()) return;
        // The sphere nearest p first: it usually holds the answer, which then prunes the others.
        size_t first = 0;
        double first_lower = std::numeric_limits<double>::max();
        for (size_t e = 0; e < list.size(); ++e) {
            const Entry& en = list[e];
            const double dx = p[0] - en.centre[0], dy = p[1] - en.centre[1], dz = p[2] - en.centre[2];
            const double lower = std::sqrt(dx * dx + dy * dy + dz * dz) - en.radius;
            if (lower < first_lower) first_lower = lower, first = e;
        }
        if (!may_beat(first_lower)) return;
        evaluate(list[first]);
        for (size_t e = 0; e < list.size(); ++e) {
            if (e == first) continue;
            const Entry& en = list[e];
            const double dx = p[0] - en.centre[0], dy = p[1] - en.centre[1], dz = p[2] - en.centre[2];
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (may_beat(d - en.radius)) evaluate(en);
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
                        if (cell_gap2(i, j, k) <= best_d2) visit(i, j, k);
                } else {
                    if (i0 >= 0 && cell_gap2(i0, j, k) <= best_d2) visit(i0, j, k);
                    if (i1 < dims_[0] && cell_gap2(i1, j, k) <= best_d2) visit(i1, j, k);
                }
            }
        // Everything beyond ring r is at least this far from p.
        double reach = std::numeric_limits<double>::max();
        for (int a = 0; a < 3; ++a) {
            if (c[a] - r > 0) reach = std::min(reach, std::max(0.0, to_low[a]) + r * cell_);
            if (c[a] + r < dims_[a] - 1) reach = std::min(reach, std::max(0.0, to_high[a]) + r * cell_);
        }
        if (best.is_valid() && best_d2 < reach * reach) break;
        if (reach > max_distance) break;  // nothing accepted within max_distance
        if (reach == std::numeric_limits<double>::max()) break;  // the whole grid was visited
    }
    return best;
}

}  // namespace ellicast
