// Flat ellipsoids for sheets: surface with no inside on either side (a leaf, a flag, a single-sided
// panel) has no volume to fill, yet the decoder needs a base there. Samples of such surface (its
// vertices, and points inside its faces where they are larger than the grid) are clustered
// greedily (within four voxels of a first unassigned sample, more when the budget is short, in
// sample order, normals within about 45 degrees) and each cluster becomes a disc-like ellipsoid fitted by PCA, about one voxel thick,
// straddling the sheet. Dense samples make neighbouring discs overlap enough that their union
// holds a layer of grid nodes everywhere: the decoder's thin base then has no holes.
#include "encoder_internal.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace ellicast::detail {

namespace {

// One disc per cluster of samples within `rho` of a first unassigned one; `complete` tells whether
// every sample found a cluster within `max_count`.
std::vector<Candidate> clustered_discs(const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                                       const std::vector<uint32_t>& part, const std::vector<uint32_t>& sheet, double h,
                                       double rho, size_t max_count, bool& complete) {
    std::vector<Candidate> out;
    complete = true;
    // Samples of different parts, or whose normals differ by more than about 45 degrees (panes
    // meeting at a corner), stand for different sheets: one disc across both would bridge them.
    const double kSameSheet = 0.7;
    auto cell = [&](const Vec3& p) {
        return std::array<int, 3>{int(std::floor(p.x() / rho)), int(std::floor(p.y() / rho)), int(std::floor(p.z() / rho))};
    };
    std::map<std::array<int, 3>, std::vector<uint32_t>> cells;
    for (uint32_t s : sheet) cells[cell(samples[s])].push_back(s);
    std::vector<char> assigned(samples.size(), 0);
    for (uint32_t s : sheet) {
        if (assigned[s]) continue;
        if (out.size() >= max_count) {
            complete = false;
            break;
        }
        std::vector<uint32_t> group;
        auto c0 = cell(samples[s]);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    auto it = cells.find({c0[0] + dx, c0[1] + dy, c0[2] + dz});
                    if (it == cells.end()) continue;
                    for (uint32_t t : it->second)
                        if (!assigned[t] && part[t] == part[s] && (samples[t] - samples[s]).norm() <= rho &&
                            (t == s || std::abs(normals[t].dot(normals[s])) >= kSameSheet))
                            group.push_back(t);
                }
        std::sort(group.begin(), group.end());
        // A few samples left between discs already laid are inside one of them most of the time:
        // a disc of their own would be a small round blob, no flatter than thick. Well inside one
        // (where the union is thick), or anywhere inside one when the budget is short.
        const double inside = rho > 4 * h ? 1.0 : 0.5;
        if (group.size() < 3) {
            auto covered = [&](uint32_t t) {
                for (const Candidate& c : out) {
                    const Vec3 local = c.axes.transpose() * (samples[t] - c.center);
                    if (local.cwiseQuotient(c.radii).squaredNorm() <= inside) return true;
                }
                return false;
            };
            if (std::all_of(group.begin(), group.end(), covered)) {
                for (uint32_t t : group) assigned[t] = 1;
                continue;
            }
        }
        Vec3 mean = Vec3::Zero();
        for (uint32_t t : group) mean += samples[t];
        mean /= double(group.size());
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        Vec3 navg = Vec3::Zero();
        for (uint32_t t : group) {
            Vec3 d = samples[t] - mean;
            cov += d * d.transpose();
            navg += normals[t];
        }
        Candidate flat;
        flat.center = mean;
        if (group.size() >= 3) {
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
            flat.axes.col(0) = eig.eigenvectors().col(2);
            flat.axes.col(1) = eig.eigenvectors().col(1);
            flat.axes.col(2) = flat.axes.col(0).cross(flat.axes.col(1)).normalized();
        } else {  // too few samples for a plane: a disc across the normal
            Vec3 n = navg.norm() > 0 ? Vec3(navg.normalized()) : Vec3::UnitZ();
            Vec3 t = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
            flat.axes.col(0) = n.cross(t).normalized();
            flat.axes.col(1) = n.cross(flat.axes.col(0)).normalized();
            flat.axes.col(2) = n;
        }
        Vec3 extent = Vec3::Zero();
        for (uint32_t t : group) extent = extent.cwiseMax((flat.axes.transpose() * (samples[t] - mean)).cwiseAbs());
        flat.radii = Vec3(std::max(extent.x() * 1.15 + 0.5 * h, h), std::max(extent.y() * 1.15 + 0.5 * h, h),
                          std::max(extent.z() + 0.5 * h, 0.75 * h));
        for (uint32_t t : group) assigned[t] = 1;
        out.push_back(flat);
    }
    return out;
}

}  // namespace

std::vector<Candidate> sheet_ellipsoids(const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                                        const std::vector<uint32_t>& part, const std::vector<uint32_t>& sheet,
                                        double h, size_t max_count) {
    // Clusters four voxels across; wider ones (fewer, flatter discs) when the budget cannot cover
    // every sample with those, since a sheet left without a base comes back with holes.
    bool complete = false;
    std::vector<Candidate> out;
    double rho = 4 * h;
    for (int attempt = 0; attempt < 5 && !complete; ++attempt, rho *= 1.5)
        out = clustered_discs(samples, normals, part, sheet, h, rho, max_count, complete);
    return out;
}

}  // namespace ellicast::detail

namespace ellicast::detail {

void face_samples(const TriangleTree& tree, const std::vector<char>& allowed, double h, size_t max_count,
                  std::vector<Vec3>& points, std::vector<Vec3>& normals, std::vector<uint32_t>& triangles) {
    points.clear();
    normals.clear();
    triangles.clear();
    if (!(h > 0)) return;
    auto skipped = [&](const TriangleTree::Triangle& t) { return !allowed.empty() && !allowed[t.index]; };
    auto longest = [](const TriangleTree::Triangle& t) {
        const Vec3 a = to_vec(t.v[0]), b = to_vec(t.v[1]), c = to_vec(t.v[2]);
        return std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    };
    // A triangle cut into n parts per edge holds (n + 1)(n + 2) / 2 lattice points.
    double spacing = h, total = 0;
    for (const auto& t : tree.triangles()) {
        if (skipped(t)) continue;
        const double n = std::ceil(longest(t) / h);
        if (n > 2) total += 0.5 * (n + 1) * (n + 2);
    }
    if (total > double(max_count)) spacing *= std::sqrt(total / double(max_count));
    for (const auto& t : tree.triangles()) {
        if (skipped(t)) continue;
        const double length = longest(t);
        if (!(length > 2 * h) || !std::isfinite(length)) continue;
        const int n = int(std::min(std::ceil(length / spacing), 4096.0));
        const Vec3 a = to_vec(t.v[0]), b = to_vec(t.v[1]), c = to_vec(t.v[2]);
        Vec3 normal = (b - a).cross(c - a);
        if (!(normal.norm() > 0)) continue;
        normal.normalize();
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                if ((i == 0 && j == 0) || i == n || j == n) continue;  // the corners
                points.push_back(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a));
                normals.push_back(normal);
                triangles.push_back(t.index);
            }
    }
}

MeshParts mesh_parts(const Mesh& mesh, const std::vector<uint32_t>& weld) {
    // Union-find over the welded vertices, joined along every triangle.
    std::vector<uint32_t> parent(weld.size());
    for (size_t i = 0; i < parent.size(); ++i) parent[i] = uint32_t(i);
    auto root = [&](uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    std::vector<uint64_t> edges;
    edges.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) {
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = weld[t[e]], b = weld[t[(e + 1) % 3]];
            edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
            parent[root(a)] = root(b);
        }
    }
    MeshParts parts;
    parts.of_vertex.resize(weld.size());
    for (size_t i = 0; i < weld.size(); ++i) parts.of_vertex[i] = root(weld[i]);
    parts.of_triangle.resize(mesh.triangles.size());
    for (size_t i = 0; i < mesh.triangles.size(); ++i) parts.of_triangle[i] = parts.of_vertex[mesh.triangles[i][0]];
    std::sort(edges.begin(), edges.end());
    parts.open.assign(weld.size(), 0);
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) parts.open[root(uint32_t(edges[i] >> 32))] = 1;
        i = j;
    }
    return parts;
}

}  // namespace ellicast::detail
