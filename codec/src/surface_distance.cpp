// Surface-to-surface distance: area-uniform samples on one side, closest points on the other.
#include "ellicast/codec/surface_distance.h"

#include "ellicast/codec/triangle_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

namespace ellicast {

namespace {

using V3 = std::array<double, 3>;

// splitmix64: a small, fast, portable generator (std distributions differ between libraries).
struct Random {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
};

V3 to_v3(const std::array<float, 3>& p) { return {p[0], p[1], p[2]}; }

double triangle_area(const V3& a, const V3& b, const V3& c) {
    V3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    V3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

bool valid_triangle(const Mesh& m, const std::array<uint32_t, 3>& t) {
    return t[0] < m.positions.size() && t[1] < m.positions.size() && t[2] < m.positions.size();
}

size_t triangle_count(const std::vector<Mesh>& meshes) {
    size_t n = 0;
    for (const auto& m : meshes) n += m.triangles.size();
    return n;
}

// One soup of every mesh's triangles, for the tree.
void merge(const std::vector<Mesh>& meshes, std::vector<std::array<float, 3>>& positions,
           std::vector<std::array<uint32_t, 3>>& triangles) {
    for (const auto& m : meshes) {
        uint32_t base = uint32_t(positions.size());
        positions.insert(positions.end(), m.positions.begin(), m.positions.end());
        for (const auto& t : m.triangles)
            if (valid_triangle(m, t)) triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
}

DirectedDistance measure(const std::vector<Mesh>& from, const TriangleTree& to, const SurfaceDistanceOptions& options,
                         double threshold) {
    size_t count = options.samples;
    if (count == 0) count = std::clamp<size_t>(10 * triangle_count(from), 100000, 2000000);
    std::vector<V3> samples = sample_surface(from, count, options.seed);
    // Vertices of triangles count towards the maximum only (they carry no area); isolated
    // vertices are not part of the surface.
    std::vector<V3> vertices;
    for (const auto& m : from) {
        std::vector<char> used(m.positions.size(), 0);
        for (const auto& t : m.triangles)
            if (valid_triangle(m, t)) used[t[0]] = used[t[1]] = used[t[2]] = 1;
        for (size_t i = 0; i < m.positions.size(); ++i)
            if (used[i]) vertices.push_back(to_v3(m.positions[i]));
    }
    unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min<unsigned>(threads, 16);
    struct Partial {
        double max = 0, sum = 0, sum2 = 0;
        size_t far = 0;
    };
    std::vector<Partial> partial(threads);
    auto work = [&](unsigned t) {
        Partial& p = partial[t];
        for (size_t i = t; i < samples.size(); i += threads) {
            double d = std::sqrt(to.closest_point(samples[i]).squared_distance);
            p.max = std::max(p.max, d);
            p.sum += d;
            p.sum2 += d * d;
            p.far += d > threshold ? 1 : 0;
        }
        for (size_t i = t; i < vertices.size(); i += threads)
            p.max = std::max(p.max, std::sqrt(to.closest_point(vertices[i]).squared_distance));
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (auto& th : pool) th.join();
    DirectedDistance out;
    out.samples = samples.size();
    double sum = 0, sum2 = 0;
    size_t far = 0;
    for (const auto& p : partial) {
        out.max = std::max(out.max, p.max);
        sum += p.sum, sum2 += p.sum2, far += p.far;
    }
    if (!samples.empty()) {
        out.mean = sum / samples.size();
        out.rms = std::sqrt(sum2 / samples.size());
        out.far_fraction = double(far) / samples.size();
    }
    return out;
}

}  // namespace

std::vector<std::array<double, 3>> sample_surface(const std::vector<Mesh>& meshes, size_t count, uint64_t seed) {
    std::vector<V3> out;
    double total = 0;
    for (const auto& m : meshes)
        for (const auto& t : m.triangles)
            if (valid_triangle(m, t))
                total += triangle_area(to_v3(m.positions[t[0]]), to_v3(m.positions[t[1]]), to_v3(m.positions[t[2]]));
    if (!(total > 0) || count == 0) return out;
    out.reserve(count + triangle_count(meshes));
    Random rng{seed};
    const double per_area = double(count) / total;
    for (const auto& m : meshes)
        for (const auto& t : m.triangles) {
            if (!valid_triangle(m, t)) continue;
            V3 a = to_v3(m.positions[t[0]]), b = to_v3(m.positions[t[1]]), c = to_v3(m.positions[t[2]]);
            double expected = triangle_area(a, b, c) * per_area;
            size_t n = size_t(expected);
            if (rng.uniform() < expected - double(n)) ++n;
            for (size_t s = 0; s < n; ++s) {
                double r1 = rng.uniform(), r2 = rng.uniform();
                if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
                out.push_back({a[0] + r1 * (b[0] - a[0]) + r2 * (c[0] - a[0]),
                               a[1] + r1 * (b[1] - a[1]) + r2 * (c[1] - a[1]),
                               a[2] + r1 * (b[2] - a[2]) + r2 * (c[2] - a[2])});
            }
        }
    return out;
}

double bounding_box_diagonal(const std::vector<Mesh>& meshes) {
    V3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    V3 hi{-lo[0], -lo[1], -lo[2]};
    bool any = false;
    for (const auto& m : meshes)
        for (const auto& p : m.positions) {
            any = true;
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
        }
    if (!any) return 0;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return std::sqrt(d2);
}

bool surface_distance(const std::vector<Mesh>& a, const std::vector<Mesh>& b, const SurfaceDistanceOptions& options,
                      SurfaceDistance& out, std::string& error) {
    out = SurfaceDistance{};
    std::vector<std::array<float, 3>> pa, pb;
    std::vector<std::array<uint32_t, 3>> ta, tb;
    merge(a, pa, ta);
    merge(b, pb, tb);
    if (ta.empty()) {
        error = "the first model has no triangle (a point set has no surface to measure)";
        return false;
    }
    if (tb.empty()) {
        error = "the second model has no triangle (a point set has no surface to measure)";
        return false;
    }
    TriangleTree tree_a(pa, ta), tree_b(pb, tb);
    out.diagonal = bounding_box_diagonal(a);
    out.threshold = options.threshold_percent / 100.0 * out.diagonal;
    out.a_to_b = measure(a, tree_b, options, out.threshold);
    out.b_to_a = measure(b, tree_a, options, out.threshold);
    return true;
}

}  // namespace ellicast
