// Growing one candidate ellipsoid from a surface seed (Bischoff & Kobbelt 2002, section 3):
// a sphere tangent at the seed grows inward until it touches the surface elsewhere (computed as a
// shrinking ball, Ma et al. 2012: a few closest-point queries instead of a search), then it is
// stretched along the axes of the local surface (PCA) while it stays inside.
#include "encoder_internal.h"

#include <algorithm>
#include <cmath>

namespace ellicast::detail {

namespace {

double box_far2(const Vec3& p, const TriangleTree::Box& b) {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
        double e = std::max(std::abs(p[k] - b.min[k]), std::abs(b.max[k] - p[k]));
        d += e * e;
    }
    return d;
}

// Adds a triangle of centroid g and area `area` to moments m.
void add_moments(std::array<double, 10>& m, const Vec3& g, double area) {
    m[0] += area;
    for (int j = 0; j < 3; ++j) m[1 + j] += area * g[j];
    m[4] += area * g.x() * g.x(), m[5] += area * g.x() * g.y(), m[6] += area * g.x() * g.z();
    m[7] += area * g.y() * g.y(), m[8] += area * g.y() * g.z(), m[9] += area * g.z() * g.z();
}

// Area moments of the surface within `radius` of `c` (triangles by their centroids).
std::array<double, 10> local_moments(const GrowthContext& ctx, const Vec3& c, double radius) {
    std::array<double, 10> m{};
    const auto& nodes = ctx.tree.nodes();
    const double r2 = radius * radius;
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    const V3 q = to_arr(c);
    while (top > 0) {
        uint32_t k = stack[--top];
        const auto& node = nodes[k];
        if (squared_distance_to_box(q, node.bounds) > r2) continue;
        if (box_far2(c, node.bounds) <= r2) {
            for (int j = 0; j < 10; ++j) m[j] += ctx.node_moments[k][j];
            continue;
        }
        if (node.is_leaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const auto& t = ctx.balls.triangles[i];
                const Vec3 g(t[0], t[1], t[2]);
                if ((g - c).squaredNorm() > r2) continue;
                add_moments(m, g, ctx.areas[i]);
            }
            continue;
        }
        if (top + 2 > 128) continue;
        stack[top++] = node.first;
        stack[top++] = node.right;
    }
    return m;
}

// Axes of the local surface around c: eigenvectors of the area covariance, largest first.
Eigen::Matrix3d local_axes(const GrowthContext& ctx, const Vec3& c, double radius, const Vec3& fallback_normal) {
    auto m = local_moments(ctx, c, radius);
    Eigen::Matrix3d axes;
    if (m[0] > 0) {
        Vec3 mu(m[1] / m[0], m[2] / m[0], m[3] / m[0]);
        Eigen::Matrix3d cov;
        cov << m[4] / m[0], m[5] / m[0], m[6] / m[0], m[5] / m[0], m[7] / m[0], m[8] / m[0], m[6] / m[0],
            m[8] / m[0], m[9] / m[0];
        cov -= mu * mu.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        if (eig.info() == Eigen::Success && eig.eigenvalues().allFinite()) {
            axes.col(0) = eig.eigenvectors().col(2);
            axes.col(1) = eig.eigenvectors().col(1);
            axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
            if (axes.allFinite() && std::abs(axes.determinant() - 1) < 1e-6) return axes;
        }
    }
    // No usable surface around: any frame with the normal as third axis.
    Vec3 n = fallback_normal.normalized();
    Vec3 t = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    axes.col(0) = n.cross(t).normalized();
    axes.col(1) = n.cross(axes.col(0)).normalized();
    axes.col(2) = axes.col(0).cross(axes.col(1));
    return axes;
}

}  // namespace

void prepare_growth(GrowthContext& ctx) {
    const auto& nodes = ctx.tree.nodes();
    const auto& tris = ctx.tree.triangles();
    ctx.balls = tree_balls(ctx.tree);
    ctx.areas.resize(tris.size());
    for (size_t i = 0; i < tris.size(); ++i) {
        const auto& t = tris[i];
        const Vec3 a = to_vec(t.v[0]), b = to_vec(t.v[1]), c = to_vec(t.v[2]);
        ctx.areas[i] = 0.5 * (b - a).cross(c - a).norm();
    }
    ctx.node_moments.assign(nodes.size(), {});
    for (size_t k = nodes.size(); k-- > 0;) {
        const auto& node = nodes[k];
        auto& m = ctx.node_moments[k];
        if (node.is_leaf()) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                const auto& t = ctx.balls.triangles[i];
                add_moments(m, Vec3(t[0], t[1], t[2]), ctx.areas[i]);
            }
        } else {
            for (int j = 0; j < 10; ++j) m[j] = ctx.node_moments[node.first][j] + ctx.node_moments[node.right][j];
        }
    }
}

namespace {

// True when triangle (already mapped to the ellipsoid's unit-ball space) meets the unit ball.
bool triangle_meets_unit_ball(const V3 v[3]) {
    for (int k = 0; k < 3; ++k) {
        if (v[0][k] > 1 && v[1][k] > 1 && v[2][k] > 1) return false;
        if (v[0][k] < -1 && v[1][k] < -1 && v[2][k] < -1) return false;
    }
    for (int j = 0; j < 3; ++j)
        if (v[j][0] * v[j][0] + v[j][1] * v[j][1] + v[j][2] * v[j][2] <= 1.0) return true;
    // The triangle's plane clearly apart from the ball (the nearest point of the triangle lies on
    // it or farther): (n . v0)^2 > |n|^2 with a relative margin far above rounding, no square root.
    const double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double d = n[0] * v[0][0] + n[1] * v[0][1] + n[2] * v[0][2];
    if (d * d > (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * (1 + 1e-6)) return false;
    static const V3 origin{0, 0, 0};
    V3 p = closest_point_on_triangle(origin, v[0], v[1], v[2]);
    return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= 1.0;
}

}  // namespace

bool ellipsoid_meets_triangle(const Candidate& e, const TriangleTree::Triangle& t) {
    const Eigen::Matrix3d M = e.radii.cwiseInverse().asDiagonal() * e.axes.transpose();
    V3 v[3];
    for (int j = 0; j < 3; ++j) {
        Vec3 w = M * (to_vec(t.v[j]) - e.center);
        v[j] = {w.x(), w.y(), w.z()};
    }
    return triangle_meets_unit_ball(v);
}

namespace {

// A ball holding a node's box: its centre and half its diagonal.
std::array<double, 4> node_ball(const TriangleTree::Node& node) {
    Vec3 mid, ext;
    for (int k = 0; k < 3; ++k) {
        mid[k] = 0.5 * (node.bounds.min[k] + node.bounds.max[k]);
        ext[k] = 0.5 * (node.bounds.max[k] - node.bounds.min[k]);
    }
    return {mid.x(), mid.y(), mid.z(), ext.norm()};
}

// Per node, a slab holding its triangles across their mean normal (area-weighted: the sum of their
// cross products): {n, least n . x, greatest n . x} over their corners; all zero where the normals
// cancel. Thin where the surface under a node is nearly flat, however large the node.
std::vector<std::array<double, 5>> node_slabs(const TriangleTree& tree, const std::vector<std::array<uint32_t, 2>>& spans) {
    const auto& nodes = tree.nodes();
    const auto& tris = tree.triangles();
    std::vector<Vec3> sum(nodes.size(), Vec3::Zero());
    for (size_t k = nodes.size(); k-- > 0;) {  // children after their parent
        const auto& node = nodes[k];
        if (!node.is_leaf()) {
            sum[k] = sum[node.first] + sum[node.right];
            continue;
        }
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const Vec3 a = to_vec(tris[i].v[0]), b = to_vec(tris[i].v[1]), c = to_vec(tris[i].v[2]);
            const Vec3 n = (b - a).cross(c - a);
            if (n.allFinite()) sum[k] += n;
        }
    }
    std::vector<std::array<double, 5>> slabs(nodes.size(), {0, 0, 0, 0, 0});
    for (size_t k = 0; k < nodes.size(); ++k) {
        const double length = sum[k].norm();
        if (!(length > 0) || !std::isfinite(length)) continue;
        const Vec3 n = sum[k] / length;
        double lo = INFINITY, hi = -INFINITY;
        for (uint32_t i = spans[k][0]; i < spans[k][1]; ++i)
            for (const auto& v : tris[i].v) {
                const double d = n.dot(to_vec(v));
                lo = std::min(lo, d), hi = std::max(hi, d);
            }
        slabs[k] = {n.x(), n.y(), n.z(), lo, hi};
    }
    return slabs;
}

}  // namespace

TreeBalls tree_balls(const TriangleTree& tree) {
    TreeBalls balls;
    const auto& nodes = tree.nodes();
    balls.nodes.reserve(nodes.size());
    for (const auto& node : nodes) balls.nodes.push_back(node_ball(node));
    balls.spans.resize(nodes.size());
    for (size_t k = nodes.size(); k-- > 0;) {
        const auto& node = nodes[k];
        balls.spans[k] = node.is_leaf() ? std::array<uint32_t, 2>{node.first, node.first + node.count}
                                        : std::array<uint32_t, 2>{balls.spans[node.first][0], balls.spans[node.right][1]};
    }
    balls.slabs = node_slabs(tree, balls.spans);
    balls.triangles.reserve(tree.triangles().size());
    for (const auto& t : tree.triangles()) {
        const Vec3 a = to_vec(t.v[0]), b = to_vec(t.v[1]), c = to_vec(t.v[2]);
        const Vec3 g = (a + b + c) / 3.0;
        const double r = std::sqrt(std::max({(a - g).squaredNorm(), (b - g).squaredNorm(), (c - g).squaredNorm()}));
        balls.triangles.push_back({g.x(), g.y(), g.z(), r});
        Vec3 n = (b - a).cross(c - a);
        const double length = n.norm();
        if (!(length > 0) || !std::isfinite(length)) {
            balls.planes.push_back({0, 0, 0, 0, 0});
            continue;
        }
        n /= length;
        const double offset = n.dot(a);
        const double slab = std::max(std::abs(n.dot(b) - offset), std::abs(n.dot(c) - offset));
        balls.planes.push_back({n.x(), n.y(), n.z(), offset, slab});
    }
    return balls;
}

namespace {

// A node holding at most this many triangles is read as one leaf by clear_of_surface: its triangles
// are tested in turn, without visiting (and culling) the nodes below it. The tree's own leaves
// (at most 4 triangles) serve its closest-point queries; for the ellipsoid test, whose triangle
// culls are cheaper than a node's, 16 took 6 to 8% off an encode (the 50k torus, one thread).
constexpr uint32_t kFlatTriangles = 16;

}  // namespace

bool clear_of_surface(const TriangleTree& tree, const Candidate& e, Blockers* blockers,
                      const TreeBalls* balls) {
    const auto& nodes = tree.nodes();
    if (nodes.empty()) return true;
    const auto& tris = tree.triangles();
    if (!(e.radii.minCoeff() > 0) || !e.radii.allFinite() || !e.center.allFinite()) return false;
    // M maps the ellipsoid to the unit ball.
    const Eigen::Matrix3d M = e.radii.cwiseInverse().asDiagonal() * e.axes.transpose();
    const double inv_rmin = 1.0 / e.radii.minCoeff();
    // The ellipsoid's support along a unit vector n is |support n|.
    const Eigen::Matrix3d support = e.radii.asDiagonal() * e.axes.transpose();
    auto mapped = [&](const TriangleTree::Triangle& t, V3 v[3]) {
        for (int j = 0; j < 3; ++j) {
            Vec3 w = M * (to_vec(t.v[j]) - e.center);
            v[j] = {w.x(), w.y(), w.z()};
        }
    };
    if (blockers) {  // the triangles that stopped the previous tries often stop this one
        for (uint32_t k = 0; k < blockers->count; ++k) {
            const uint32_t t = blockers->triangles[k];
            if (t >= tris.size()) continue;
            V3 v[3];
            mapped(tris[t], v);
            if (triangle_meets_unit_ball(v)) return false;
        }
    }
    // The ellipsoid's bounding box, a hair wider: the culls below only skip what is clearly apart,
    // so that the answer is the triangles' own (triangle_meets_unit_ball), whatever the order in
    // which they are tried and however the tree groups them.
    Vec3 half;
    for (int k = 0; k < 3; ++k)
        half[k] = (e.axes.row(k).transpose().cwiseProduct(e.radii)).norm() * (1 + 1e-9) + 1e-12 * std::abs(e.center[k]);
    const V3 c = to_arr(e.center);
    // A node is skipped when its bounding ball, mapped into unit-ball space, stays clearly outside the
    // unit ball: when the squared distance of its mapped centre exceeds (1 + radius / r_min)^2, with a
    // margin. The difference of the two (no square root) also orders the children: the answer does
    // not depend on the order, only how soon a blocked ellipsoid is found out.
    auto mapped_gap = [&](uint32_t k) {
        const std::array<double, 4> ball = balls ? balls->nodes[k] : node_ball(nodes[k]);
        const double reach = 1.0 + 1e-9 + ball[3] * inv_rmin;
        return (M * (Vec3(ball[0], ball[1], ball[2]) - e.center)).squaredNorm() - reach * reach;
    };
    // Each node with its mapped gap, computed once (when its parent orders its children).
    struct Entry {
        uint32_t node;
        double gap;  // > 0: clearly apart
    };
    // A node whose box is apart from the ellipsoid's box is not taken (before its gap is computed).
    auto apart = [&](uint32_t k) {
        const auto& b = nodes[k].bounds;
        bool out = false;
        for (int j = 0; j < 3; ++j) out = out || b.min[j] > c[j] + half[j] || b.max[j] < c[j] - half[j];
        return out;
    };
    // Nor is a node whose slab (tree_balls) lies clearly apart from the ellipsoid, which reaches
    // |support n| either side of its centre along n, with the margins of the triangles' planes below:
    // the surface under an ellipsoid that hugs it is such a slab, culled whole where the boxes and
    // balls reach into it.
    auto slab_apart = [&](uint32_t k) {
        if (!balls) return false;
        const auto& s = balls->slabs[k];
        const Vec3 n(s[0], s[1], s[2]);
        const double along = n.dot(e.center);
        const double gap = std::max(s[3] - along, along - s[4]) - 1e-12 * (std::abs(along) + std::abs(s[3]) + std::abs(s[4]));
        return gap > 0 && gap * gap > (support * n).squaredNorm() * (1 + 1e-6);
    };
    constexpr double kApart = 1.0;  // the gap of a node not taken: clearly apart
    auto gap_of = [&](uint32_t k) { return apart(k) || slab_apart(k) ? kApart : mapped_gap(k); };
    Entry stack[128];
    int top = 0;
    stack[top++] = {0, gap_of(0)};
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.gap > 0) continue;  // only the root
        const auto& node = nodes[entry.node];
        const uint32_t lo = balls ? balls->spans[entry.node][0] : node.first;
        const uint32_t hi = balls ? balls->spans[entry.node][1] : node.first + node.count;
        if (node.is_leaf() || (balls && hi - lo <= kFlatTriangles)) {
            for (uint32_t i = lo; i < hi; ++i) {
                if (balls) {
                    // The ball mapped into unit-ball space lies within radius / r_min of its mapped
                    // centre; a margin keeps rounding from skipping a triangle that touches. First:
                    // past the node culls, more triangles are settled by it than by their planes.
                    const auto& ball = balls->triangles[i];
                    const double reach = 1.0 + 1e-9 + ball[3] * inv_rmin;
                    if ((M * (Vec3(ball[0], ball[1], ball[2]) - e.center)).squaredNorm() > reach * reach) continue;
                    // The triangle's plane (the slab holding it) clearly apart from the ellipsoid:
                    // the centre lies farther from it than the ellipsoid's support along its normal,
                    // |diag(r) A' n|, with margins far above rounding. Most triangles near an
                    // ellipsoid that hugs the surface are nearly tangent to it: this settles them.
                    const auto& plane = balls->planes[i];
                    const Vec3 n(plane[0], plane[1], plane[2]);
                    const double along = n.dot(e.center);
                    const double gap =
                        std::abs(along - plane[3]) - plane[4] - 1e-12 * (std::abs(along) + std::abs(plane[3]));
                    if (gap > 0 && gap * gap > (support * n).squaredNorm() * (1 + 1e-6)) continue;
                }
                V3 v[3];
                mapped(tris[i], v);
                if (triangle_meets_unit_ball(v)) {
                    if (blockers) blockers->add(i);
                    return false;
                }
            }
            continue;
        }
        if (top + 2 > 128) return false;
        // Nearer child last, so it is visited first: a blocked ellipsoid is found out sooner.
        const Entry left{node.first, gap_of(node.first)}, right{node.right, gap_of(node.right)};
        const Entry& nearer = left.gap <= right.gap ? left : right;
        const Entry& farther = left.gap <= right.gap ? right : left;
        if (farther.gap <= 0) stack[top++] = farther;
        if (nearer.gap <= 0) stack[top++] = nearer;
    }
    return true;
}

bool ellipsoid_inside(const GrowthContext& ctx, const Candidate& e, Blockers* blockers) {
    if (ctx.grid.sample(e.center) <= 0.5) return false;
    if (!ctx.closed) {
        // An open surface has holes an ellipsoid could slip through without touching a triangle:
        // its inner part must lie inside on the winding grid too.
        static const double d = 0.57735026919;
        static const double dirs[14][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},  {0, -1, 0}, {0, 0, 1},
                                           {0, 0, -1}, {d, d, d}, {d, d, -d}, {d, -d, d}, {d, -d, -d},
                                           {-d, d, d}, {-d, d, -d}, {-d, -d, d}, {-d, -d, -d}};
        for (const auto& dir : dirs) {
            Vec3 local(dir[0] * e.radii.x(), dir[1] * e.radii.y(), dir[2] * e.radii.z());
            Vec3 p = e.center + 0.75 * (e.axes * local);
            if (ctx.grid.sample(p) <= 0.5) return false;
        }
    }
    return clear_of_surface(ctx.tree, e, blockers, &ctx.balls);
}

namespace {

// Stretches e while it stays inside: per axis (the first `axes` of them) try to extend both ends,
// then one end (moving the centre), with halving steps.
void stretch(const GrowthContext& ctx, Candidate& e, int axes, Blockers& blockers) {
    int tests = 0;
    for (double step = 1.0; step > 0.02 && tests < 120; step *= 0.5) {
        bool improved = true;
        for (int round = 0; improved && round < 6 && tests < 120; ++round) {
            improved = false;
            for (int axis = 0; axis < axes; ++axis) {
                double delta = step * e.radii[axis];
                for (int mode = 0; mode < 3; ++mode) {
                    Candidate t = e;
                    if (mode == 0) {
                        t.radii[axis] += delta;
                    } else {
                        t.radii[axis] += 0.5 * delta;
                        t.center += e.axes.col(axis) * (mode == 1 ? 0.5 * delta : -0.5 * delta);
                    }
                    ++tests;
                    if (ellipsoid_inside(ctx, t, &blockers)) {
                        e = t;
                        improved = true;
                        break;
                    }
                }
            }
        }
    }
}

}  // namespace

bool grow_ellipsoid(const GrowthContext& ctx, const Vec3& p, const Vec3& n, Candidate& out) {
    // Initial radius: half the way along n until the winding grid says outside.
    const double h = ctx.grid.h;
    double exit = h;
    const double limit = h * (ctx.grid.n[0] + ctx.grid.n[1] + ctx.grid.n[2]);
    while (exit < limit && ctx.grid.sample(p + n * exit) > 0.5) exit += 0.5 * h;
    double r = std::max(0.5 * exit, ctx.min_radius);

    // Shrinking ball: the largest ball tangent at p (centre on the inward normal) holding no surface.
    for (int it = 0; it < 40; ++it) {
        Vec3 c = p + n * r;
        ClosestPoint cp = ctx.tree.closest_point(to_arr(c));
        if (!cp.found) return false;
        double d = std::sqrt(cp.squared_distance);
        if (d >= r * (1 - 1e-4)) break;
        Vec3 q = to_vec(cp.point);
        double denom = 2.0 * n.dot(q - p);
        double next = denom > 1e-15 ? (q - p).squaredNorm() / denom : 0.5 * r;
        r = next < r ? next : 0.5 * r;
        if (r < ctx.min_radius) return false;
    }
    // A hair smaller than the ball, so that it does not touch the surface at p: an absolute gap
    // (a tenth of a voxel) for a large ball, whose relative 3% would leave a voxel uncovered.
    Candidate e;
    e.radii = Vec3::Constant(r - std::min(0.03 * r, 0.1 * h));
    e.center = p + n * r;
    e.axes = local_axes(ctx, e.center, 2.5 * r, n);
    Blockers blockers;
    int shrink = 0;
    while (!ellipsoid_inside(ctx, e, &blockers)) {
        if (++shrink > 6) return false;
        e.radii *= 0.7;
        e.center = p + n * (e.radii.x() / 0.97);
        if (e.radii.x() < ctx.min_radius) return false;
    }

    stretch(ctx, e, 3, blockers);
    out = e;
    return true;
}

bool grow_flat(const GrowthContext& ctx, const Vec3& p, const Vec3& n, double thickness, double turn, Candidate& out) {
    const double h = ctx.grid.h;
    double t = std::max(thickness, ctx.min_radius);
    Candidate e;
    Blockers blockers;
    for (int tries = 0;; ++tries) {
        e.center = p + n * t;
        e.radii = Vec3::Constant(t - std::min(0.03 * t, 0.1 * h));
        if (ellipsoid_inside(ctx, e, &blockers)) break;
        t *= 0.7;
        if (tries >= 6 || t < ctx.min_radius) return false;
    }
    // The tangent axes of the local surface (over a few voxels), the normal as third axis.
    const Eigen::Matrix3d pca = local_axes(ctx, e.center, std::max(2.5 * t, 4 * h), n);
    Vec3 a = pca.col(0) - pca.col(0).dot(n) * n;
    if (a.norm() < 1e-3) a = pca.col(1) - pca.col(1).dot(n) * n;
    if (a.norm() < 1e-3) a = n.cross(std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY());
    a.normalize();
    a = std::cos(turn) * a + std::sin(turn) * n.cross(a);
    e.axes.col(0) = a;
    e.axes.col(1) = n.cross(a).normalized();
    e.axes.col(2) = e.axes.col(0).cross(e.axes.col(1));
    stretch(ctx, e, 2, blockers);
    out = e;
    return true;
}

}  // namespace ellicast::detail
