// Ellipsoids -> a grid of clamped signed distances over the part of the object's frame they cover.
#include "ellicast/codec/decoder.h"

#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellicast {
namespace {

struct PreparedEllipsoid {
    double c[3];
    double m[3][3];     // diag(1/r) R^T: maps x - c to the unit-sphere frame
    double half[3];     // half extents of the axis-aligned bounding box
    double r_min;
};

bool prepare(const Ellipsoid& e, PreparedEllipsoid& p) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(e.center[i]) || !std::isfinite(e.radii[i]) || !(e.radii[i] > 0)) return false;
    }
    double w = e.rotation[0], x = e.rotation[1], y = e.rotation[2], z = e.rotation[3];
    if (!std::isfinite(w) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return false;
    double n = std::sqrt(w * w + x * x + y * y + z * z);
    if (!(n > 1e-12)) return false;
    w /= n, x /= n, y /= n, z /= n;
    // Rotation matrix of the unit quaternion; column i = direction of semi-axis i.
    double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    p.r_min = std::numeric_limits<double>::max();
    for (int i = 0; i < 3; ++i) {
        p.c[i] = e.center[i];
        double r = e.radii[i];
        p.r_min = std::min(p.r_min, r);
        for (int k = 0; k < 3; ++k) p.m[i][k] = R[k][i] / r;  // row i of diag(1/r) R^T
    }
    for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int i = 0; i < 3; ++i) s += (R[k][i] * e.radii[i]) * (R[k][i] * e.radii[i]);
        p.half[k] = std::sqrt(s);
    }
    return true;
}

// The box the usable ellipsoids cover, and how many are not usable. Each is prepared again where
// it is drawn: holding every prepared ellipsoid (128 bytes each) would cost a stream of a million
// ellipsoids 128 MB for nothing.
struct Cover {
    double mn[3], mx[3];
    size_t usable = 0, bad = 0;
};

Cover cover_of(const std::vector<Ellipsoid>& ellipsoids) {
    Cover c;
    for (int k = 0; k < 3; ++k) c.mn[k] = std::numeric_limits<double>::max(), c.mx[k] = -c.mn[k];
    for (const auto& e : ellipsoids) {
        PreparedEllipsoid p;
        if (!prepare(e, p)) {
            ++c.bad;
            continue;
        }
        ++c.usable;
        for (int k = 0; k < 3; ++k) {
            c.mn[k] = std::min(c.mn[k], p.c[k] - p.half[k]);
            c.mx[k] = std::max(c.mx[k], p.c[k] + p.half[k]);
        }
    }
    return c;
}

// Node index range of the grid: the union of the ellipsoids' boxes, one cell of margin, on the
// frame's lattice.
void node_range(const Cover& cover, const Frame& frame, int resolution, long lo[3], long hi[3]) {
    const double h = double(frame.scale) / resolution;
    for (int k = 0; k < 3; ++k) {
        lo[k] = long(std::floor((cover.mn[k] - double(frame.origin[k])) / h)) - 1;
        hi[k] = long(std::ceil((cover.mx[k] - double(frame.origin[k])) / h)) + 1;
    }
}

}  // namespace

size_t ellipsoid_grid_nodes(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution) {
    if (resolution < kMinGridResolution || resolution > kMaxGridResolution || !std::isfinite(frame.scale) ||
        !(frame.scale > 0))
        return 0;
    const Cover cover = cover_of(ellipsoids);
    if (cover.usable == 0) return 0;
    long lo[3], hi[3];
    node_range(cover, frame, resolution, lo, hi);
    size_t total = 1;
    for (int k = 0; k < 3; ++k) {
        const size_t n = size_t(hi[k] - lo[k] + 1);
        if (n != 0 && total > std::numeric_limits<size_t>::max() / n) return std::numeric_limits<size_t>::max();
        total *= n;
    }
    return total;
}

double ellipsoid_raster_work(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution) {
    if (resolution < kMinGridResolution || resolution > kMaxGridResolution || !std::isfinite(frame.scale) ||
        !(frame.scale > 0))
        return 0;
    const double h = double(frame.scale) / resolution;
    double work = 0;
    for (const auto& e : ellipsoids) {
        PreparedEllipsoid p;
        if (!prepare(e, p)) continue;
        double nodes = 1;
        for (int k = 0; k < 3; ++k) nodes *= std::min(2 * p.half[k] / h + 4, double(kMaxGridNodes));
        work += nodes;
    }
    return work;
}

bool rasterize_ellipsoids(const std::vector<Ellipsoid>& ellipsoids, const Frame& frame, int resolution,
                          EllipsoidGrid& out, std::string& error, size_t* skipped, unsigned threads) {
    out = EllipsoidGrid{};
    if (resolution < kMinGridResolution || resolution > kMaxGridResolution) {
        error = "grid resolution " + std::to_string(resolution) + " is outside " + std::to_string(kMinGridResolution) +
                ".." + std::to_string(kMaxGridResolution);
        return false;
    }
    if (!std::isfinite(frame.scale) || !(frame.scale > 0)) {
        error = "the object's frame has no positive finite scale";
        return false;
    }
    const Cover cover = cover_of(ellipsoids);
    if (skipped) *skipped = cover.bad;
    if (cover.usable == 0) return true;

    const double h = double(frame.scale) / resolution;
    const double o[3] = {frame.origin[0], frame.origin[1], frame.origin[2]};
    long lo[3], hi[3];
    node_range(cover, frame, resolution, lo, hi);
    size_t total = 1;
    for (int k = 0; k < 3; ++k) {
        size_t n = size_t(hi[k] - lo[k] + 1);
        if (n > kMaxGridNodes || total * n > kMaxGridNodes) {
            error = "a grid of resolution " + std::to_string(resolution) +
                    " over these ellipsoids would exceed " + std::to_string(kMaxGridNodes) +
                    " nodes; choose a smaller --grid";
            return false;
        }
        total *= n;
        out.nodes[k] = int(n);
        out.origin[k] = o[k] + double(lo[k]) * h;
    }
    out.cell = h;
    out.value.assign(total, float(-h));

    // Slabs of z planes, one a thread: every ellipsoid is drawn into each slab it reaches.
    const int slabs = int(std::clamp<unsigned>(threads, 1, unsigned(std::min(out.nodes[2], 64))));
    detail::parallel_for(size_t(slabs), unsigned(slabs), [&](size_t slab) {
        const int z_first = int(int64_t(out.nodes[2]) * int64_t(slab) / slabs);
        const int z_last = int(int64_t(out.nodes[2]) * int64_t(slab + 1) / slabs) - 1;
        for (const auto& e : ellipsoids) {
            PreparedEllipsoid p;
            if (!prepare(e, p)) continue;
            int b0[3], b1[3];
            for (int k = 0; k < 3; ++k) {
                b0[k] = std::max(0, int(std::floor((p.c[k] - p.half[k] - out.origin[k]) / h)) - 1);
                b1[k] = std::min(out.nodes[k] - 1, int(std::ceil((p.c[k] + p.half[k] - out.origin[k]) / h)) + 1);
            }
            b0[2] = std::max(b0[2], z_first);
            b1[2] = std::min(b1[2], z_last);
            // Nodes with value above -h satisfy sqrt(q) < 1 + h / r_min; solve the row quadratic for them.
            const double limit = (1 + h / p.r_min) * (1 + h / p.r_min);
            // q(i) along a row is |v0 + i * dv|^2 with dv = h * column 0 of m.
            const double dv[3] = {h * p.m[0][0], h * p.m[1][0], h * p.m[2][0]};
            const double a = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
            for (int kz = b0[2]; kz <= b1[2]; ++kz) {
                const double z = out.origin[2] + kz * h - p.c[2];
                for (int jy = b0[1]; jy <= b1[1]; ++jy) {
                    const double y = out.origin[1] + jy * h - p.c[1];
                    const double x0 = out.origin[0] - p.c[0];  // x of node i = 0, relative to the centre
                    double v0[3];
                    for (int r = 0; r < 3; ++r) v0[r] = p.m[r][0] * x0 + p.m[r][1] * y + p.m[r][2] * z;
                    const double b = 2 * (v0[0] * dv[0] + v0[1] * dv[1] + v0[2] * dv[2]);
                    const double c = v0[0] * v0[0] + v0[1] * v0[1] + v0[2] * v0[2] - limit;
                    const double disc = b * b - 4 * a * c;
                    if (disc < 0) continue;
                    const double sq = std::sqrt(disc);
                    int i0 = std::max(b0[0], int(std::floor((-b - sq) / (2 * a))));
                    int i1 = std::min(b1[0], int(std::ceil((-b + sq) / (2 * a))));
                    float* row = &out.value[out.index(0, jy, kz)];
                    for (int ix = i0; ix <= i1; ++ix) {
                        const double x = out.origin[0] + ix * h - p.c[0];
                        double v[3];
                        for (int r = 0; r < 3; ++r) v[r] = p.m[r][0] * x + p.m[r][1] * y + p.m[r][2] * z;
                        const double nv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                        double g;
                        if (nv < 1e-12) {
                            g = p.r_min;
                        } else {
                            const double t = std::sqrt(x * x + y * y + z * z);
                            g = t * (1 - nv) / nv;  // distance along the ray from the centre
                        }
                        float gf = float(std::max(g, -h));
                        if (gf > row[ix]) row[ix] = gf;
                    }
                }
            }
        }
    });
    return true;
}

}  // namespace ellicast
