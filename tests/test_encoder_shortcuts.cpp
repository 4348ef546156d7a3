// The encoder's shortcuts give the answers of the plain computations they replace: the tests against
// the surface that skip triangles and nodes by their balls and try the last blockers first, and the
// selection that keeps each candidate's voxel runs between rounds. The encoder's streams depend on
// these answers bit for bit (the same input, the same stream), so a shortcut may only be faster.
#include "../codec/src/encoder_internal.h"
#include "shapes.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <set>

using namespace ellicast;
using namespace ellicast::detail;

namespace {

// A lumpy closed surface: an ellipsoid with bumps, and a box beside it (two parts, flat faces and
// sharp edges as well as curved ones).
Mesh lumpy_scene() {
    Mesh m = samples::uv_ellipsoid(40, {0, 0, 0}, {1.0, 0.7, 0.5});
    for (auto& p : m.positions) {
        const double bump = 1.0 + 0.08 * std::sin(7 * p[0]) * std::cos(5 * p[1]) + 0.04 * std::sin(11 * p[2]);
        for (auto& c : p) c = float(c * bump);
    }
    Mesh b = samples::box({0.6f, 0.5f, 0.9f});
    const uint32_t first = uint32_t(m.positions.size());
    for (auto p : b.positions) m.positions.push_back({p[0] + 1.6f, p[1], p[2]});
    for (auto t : b.triangles) m.triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
    return m;
}

Candidate random_candidate(Random& rng, const TriangleTree::Box& box) {
    Candidate e;
    for (int k = 0; k < 3; ++k) e.center[k] = box.min[k] + rng.uniform() * (box.max[k] - box.min[k]);
    Eigen::Quaterniond q(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
    e.axes = q.normalized().toRotationMatrix();
    for (int k = 0; k < 3; ++k) e.radii[k] = 0.01 + 0.4 * rng.uniform() * rng.uniform();
    return e;
}

}  // namespace

// The answer by definition: no triangle, tried one by one, meets the ellipsoid.
bool clear_by_brute_force(const TriangleTree& tree, const Candidate& e) {
    for (const auto& t : tree.triangles())
        if (ellipsoid_meets_triangle(e, t)) return false;
    return true;
}

TEST_CASE("the encoder's surface test answers as each triangle does, with or without its shortcuts (balls, last blockers)") {
    const Mesh m = lumpy_scene();
    const TriangleTree tree(m.positions, m.triangles);
    const TreeBalls balls = tree_balls(tree);
    REQUIRE(balls.nodes.size() == tree.nodes().size());
    REQUIRE(balls.triangles.size() == tree.triangles().size());
    Random rng(20261128);
    Blockers blockers;
    size_t clear = 0, blocked = 0, grazing = 0;
    for (int i = 0; i < 6000; ++i) {
        Candidate e = random_candidate(rng, tree.bounds());
        const bool plain = clear_by_brute_force(tree, e);
        CHECK(clear_of_surface(tree, e) == plain);
        CHECK(clear_of_surface(tree, e, &blockers, &balls) == plain);
        CHECK(clear_of_surface(tree, e, nullptr, &balls) == plain);
        (plain ? clear : blocked) += 1;
        if (!plain || i % 4 != 0) continue;
        // Grow it until it just touches the surface (by bisection), then ask on both sides of the
        // touch: where rounding decides, the tree's culls and the shortcuts must decide alike.
        double lo = 1, hi = 64;
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            Candidate t = e;
            t.radii *= mid;
            (clear_by_brute_force(tree, t) ? lo : hi) = mid;
        }
        for (double s : {lo, hi, std::nextafter(lo, 0.0), std::nextafter(hi, 100.0)}) {
            Candidate t = e;
            t.radii *= s;
            const bool expected = clear_by_brute_force(tree, t);
            CHECK(clear_of_surface(tree, t) == expected);
            CHECK(clear_of_surface(tree, t, &blockers, &balls) == expected);
            ++grazing;
        }
    }
    MESSAGE(clear << " clear, " << blocked << " blocked, " << grazing << " grazing");
    CHECK(clear > 500);
    CHECK(blocked > 500);
    CHECK(grazing > 400);
}

TEST_CASE("the selection of ellipsoids chooses the same with its kept voxel runs as without, over growing candidate lists") {
    const Mesh m = lumpy_scene();
    const TriangleTree tree(m.positions, m.triangles);
    const VoxelGrid grid = build_closed_winding_grid(tree, tree.bounds(), 40, 2);
    const VoxelGrid fine = build_closed_winding_grid(tree, tree.bounds(), 80, 2);
    std::vector<Vec3> samples;
    for (size_t i = 0; i < m.positions.size(); i += 3)
        samples.emplace_back(m.positions[i][0], m.positions[i][1], m.positions[i][2]);
    Random rng(7);
    std::vector<Candidate> candidates;
    SelectionCache cache_plain, cache_fine;
    // Rounds as the encoder has them: more candidates each time, the coverage aimed at rising.
    for (int round = 0; round < 4; ++round) {
        for (int i = 0; i < 150; ++i) {
            Candidate e = random_candidate(rng, tree.bounds());
            if (clear_of_surface(tree, e) && grid.sample(e.center) > 0.5) candidates.push_back(e);
        }
        const double aim = 0.6 + 0.1 * round;
        for (const VoxelGrid* measure : {static_cast<const VoxelGrid*>(nullptr), &fine}) {
            SelectionCache& cache = measure ? cache_fine : cache_plain;
            const SelectionResult fresh =
                select_ellipsoids(grid, measure, candidates, samples, grid.h, aim, 40, 60, {});
            const SelectionResult kept =
                select_ellipsoids(grid, measure, candidates, samples, grid.h, aim, 40, 60, {}, &cache);
            CHECK(kept.volume == fresh.volume);
            CHECK(kept.surface == fresh.surface);
            CHECK(kept.coverage == fresh.coverage);
            CHECK(!fresh.volume.empty());
            CHECK(cache.spans.size() == candidates.size());
            // Each candidate's near samples, as the surface pass found them through its voxel runs,
            // are those read one by one: in the candidate grown by `near` and nearest a voxel
            // under its runs grown by `near` and a voxel.
            REQUIRE(cache.near_samples.size() == candidates.size());
            size_t near_pairs = 0;
            for (size_t i = 0; i < candidates.size(); ++i) {
                const Candidate& e = candidates[i];
                const std::vector<Span> runs = rasterize(grid, e, 2 * grid.h);
                std::vector<uint32_t> expected;
                for (uint32_t k = 0; k < samples.size(); ++k) {
                    int idx[3];
                    bool in_grid = true;
                    for (int j = 0; j < 3; ++j) {
                        idx[j] = int(std::lround((samples[k][j] - grid.origin[j]) / grid.h));
                        in_grid = in_grid && idx[j] >= 0 && idx[j] < grid.n[j];
                    }
                    if (!in_grid) continue;
                    const uint32_t row = uint32_t(idx[1] + idx[2] * grid.n[1]);
                    bool under = false;
                    for (const Span& sp : runs) under = under || (sp.row == row && idx[0] >= sp.x0 && idx[0] < sp.x1);
                    const Vec3 local = e.axes.transpose() * (samples[k] - e.center);
                    if (under && local.cwiseQuotient(e.radii + Vec3::Constant(grid.h)).squaredNorm() <= 1.0)
                        expected.push_back(k);
                }
                CHECK(cache.near_samples[i] == expected);
                near_pairs += expected.size();
            }
            CHECK(near_pairs > 50);
        }
    }
    CHECK(candidates.size() > 100);
}

TEST_CASE("voxel runs count, clear and fill the bits under them as bit-by-bit reads do, on rows of one word and of several") {
    for (int width : {5, 63, 64, 65, 130, 200}) {
        VoxelGrid grid;
        grid.n[0] = width, grid.n[1] = 7, grid.n[2] = 3;
        const size_t rows = size_t(grid.n[1]) * grid.n[2];
        VoxelBits bits(grid, false);
        Random rng{uint32_t(width)};
        for (size_t row = 0; row < rows; ++row)
            for (int x = 0; x < width; ++x)
                if (rng.uniform() < 0.6) bits.set(size_t(x), row, true);
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<Span> spans;
            for (int k = 0, n = 1 + int(rng.below(6)); k < n; ++k) {
                const uint32_t row = rng.below(uint32_t(rows));
                uint32_t x0 = rng.below(uint32_t(width));
                uint32_t x1 = x0 + 1 + rng.below(uint32_t(width) - x0);
                if (trial % 7 == 0) x0 = 0, x1 = uint32_t(width);          // a whole row
                if (trial % 11 == 0 && width >= 128) x0 = 64, x1 = 128;  // exactly one whole word
                spans.push_back({row, uint16_t(x0), uint16_t(x1)});
            }
            size_t expected = 0;
            for (const Span& s : spans)
                for (size_t x = s.x0; x < s.x1; ++x) expected += bits.get(x, s.row);
            REQUIRE(bits.count(spans) == expected);
            if (trial % 3 == 0) {
                VoxelBits copy = bits;
                copy.clear(spans);
                for (const Span& s : spans)
                    for (size_t x = s.x0; x < s.x1; ++x) CHECK_FALSE(copy.get(x, s.row));
                CHECK(copy.count(spans) == 0);
                std::set<std::pair<size_t, size_t>> under;  // runs may overlap
                for (const Span& s : spans)
                    for (size_t x = s.x0; x < s.x1; ++x)
                        if (bits.get(x, s.row)) under.insert({s.row, x});
                CHECK(copy.count_all() + under.size() == bits.count_all());
                copy.fill(spans);
                size_t width_sum = 0;
                for (const Span& s : spans) width_sum += size_t(s.x1 - s.x0);
                if (spans.size() == 1) CHECK(copy.count(spans) == width_sum);
            }
        }
        // Runs one short of a word, a word's last bit, across a word's end.
        for (uint32_t row = 0; row < rows; ++row)
            for (uint32_t w = 0; 64 * w < uint32_t(width); ++w)
                for (auto [a, b] : {std::pair{0u, 63u}, std::pair{1u, 64u}, std::pair{63u, 64u}, std::pair{62u, 66u}}) {
                    const uint32_t x0 = 64 * w + a, x1 = std::min(64 * w + b, uint32_t(width));
                    if (x0 >= x1) continue;
                    size_t expected = 0;
                    for (size_t x = x0; x < x1; ++x) expected += bits.get(x, row);
                    CHECK(bits.count({{row, uint16_t(x0), uint16_t(x1)}}) == expected);
                }
        CHECK(bits.count({{0, 3, 3}}) == 0);  // an empty run holds nothing
    }
}

TEST_CASE("the points' order is coarse to fine as the plain reading of it gives, with a set of each level's cells") {
    // The reference: per level, the cells of every point already taken, then in the seeded shuffle
    // each point whose cell is still free; what no level separates (duplicates) at the end.
    auto plain = [](const std::vector<std::array<uint32_t, 3>>& positions, int bits, uint32_t seed) {
        const size_t n = positions.size();
        std::vector<uint32_t> shuffled(n);
        for (uint32_t i = 0; i < n; ++i) shuffled[i] = i;
        Random rng(seed ^ 0x9E3779B9u);
        for (size_t i = n; i > 1; --i) std::swap(shuffled[i - 1], shuffled[rng.below(uint32_t(i))]);
        std::vector<uint32_t> order;
        std::vector<bool> taken(n, false);
        for (int level = 1; level <= bits && order.size() < n; ++level) {
            const int shift = bits - level;
            auto cell = [&](uint32_t i) {
                const auto& p = positions[i];
                return std::array<uint32_t, 3>{p[0] >> shift, p[1] >> shift, p[2] >> shift};
            };
            std::set<std::array<uint32_t, 3>> occupied;
            for (uint32_t i : order) occupied.insert(cell(i));
            for (uint32_t i : shuffled)
                if (!taken[i] && occupied.insert(cell(i)).second) taken[i] = true, order.push_back(i);
        }
        for (uint32_t i : shuffled)
            if (!taken[i]) order.push_back(i);
        return order;
    };
    Random rng(11);
    for (int bits : {8, 14, 16}) {
        for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(500), size_t(6000)}) {
            std::vector<std::array<uint32_t, 3>> positions(n);
            const uint32_t top = (uint32_t(1) << bits) - 1;
            for (size_t i = 0; i < n; ++i) {
                if (i % 5 == 4) {  // a duplicate of an earlier point
                    positions[i] = positions[rng.below(uint32_t(i))];
                } else if (i % 5 == 3) {  // a cluster in one corner
                    for (auto& c : positions[i]) c = rng.below(8);
                } else {
                    for (auto& c : positions[i]) c = std::min(top, rng.below(top + 1));
                }
            }
            CAPTURE(bits);
            CAPTURE(n);
            const std::vector<uint32_t> order = spread_order(positions, bits, 77);
            CHECK(order == plain(positions, bits, 77));
        }
    }
}

TEST_CASE("a parallel loop's exception comes back to its caller, whatever thread threw it") {
    for (unsigned threads : {1u, 2u, 4u}) {
        CAPTURE(threads);
        std::atomic<size_t> ran{0};
        CHECK_THROWS_WITH_AS(ellicast::detail::parallel_for(1000, threads,
                                                           [&](size_t i) {
                                                               ++ran;
                                                               if (i == 500) throw std::runtime_error("index 500");
                                                           }),
                             "index 500", std::runtime_error);
        CHECK(ran.load() >= 1);
        CHECK(ran.load() <= 1000);
        // Without a throw every index runs once.
        std::vector<int> seen(1000, 0);
        ellicast::detail::parallel_for(seen.size(), threads, [&](size_t i) { ++seen[i]; });
        CHECK(std::all_of(seen.begin(), seen.end(), [](int v) { return v == 1; }));
    }
}
