// The triangle tree answers closest-point queries exactly like a brute-force scan.
#include "ellicast/codec/triangle_tree.h"
#include "shapes.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace ellicast;

namespace {

// A closed unit UV sphere with `n` rings.
void make_sphere(int n, std::vector<std::array<float, 3>>& pos, std::vector<std::array<uint32_t, 3>>& tri) {
    Mesh m = samples::uv_ellipsoid(n, {0, 0, 0}, {1, 1, 1});
    pos = std::move(m.positions);
    tri = std::move(m.triangles);
}

}  // namespace

TEST_CASE("triangle tree closest point matches a brute-force scan") {
    std::vector<std::array<float, 3>> pos;
    std::vector<std::array<uint32_t, 3>> tri;
    make_sphere(24, pos, tri);
    TriangleTree tree(pos, tri);
    REQUIRE(tree.triangle_count() == tri.size());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2, 2);
    for (int q = 0; q < 300; ++q) {
        std::array<double, 3> p{u(rng), u(rng), u(rng)};
        double brute = INFINITY;
        for (const auto& t : tri) {
            std::array<double, 3> a{pos[t[0]][0], pos[t[0]][1], pos[t[0]][2]};
            std::array<double, 3> b{pos[t[1]][0], pos[t[1]][1], pos[t[1]][2]};
            std::array<double, 3> c{pos[t[2]][0], pos[t[2]][1], pos[t[2]][2]};
            auto cp = closest_point_on_triangle(p, a, b, c);
            double d = (cp[0] - p[0]) * (cp[0] - p[0]) + (cp[1] - p[1]) * (cp[1] - p[1]) + (cp[2] - p[2]) * (cp[2] - p[2]);
            brute = std::min(brute, d);
        }
        ClosestPoint c = tree.closest_point(p);
        REQUIRE(c.found);
        CHECK(c.squared_distance == doctest::Approx(brute).epsilon(1e-12));
        CHECK(c.triangle < tri.size());
        // The reported point lies on the reported triangle.
        const auto& t = tri[c.triangle];
        std::array<double, 3> a{pos[t[0]][0], pos[t[0]][1], pos[t[0]][2]};
        std::array<double, 3> b{pos[t[1]][0], pos[t[1]][1], pos[t[1]][2]};
        std::array<double, 3> cc{pos[t[2]][0], pos[t[2]][1], pos[t[2]][2]};
        auto on = closest_point_on_triangle(c.point, a, b, cc);
        CHECK(std::abs(on[0] - c.point[0]) + std::abs(on[1] - c.point[1]) + std::abs(on[2] - c.point[2]) < 1e-9);
        // A radius-limited query finds nothing when the surface is farther.
        double d = std::sqrt(brute);
        CHECK_FALSE(tree.closest_point(p, d * 0.99).found);
        CHECK(tree.any_within(p, d * 1.01 + 1e-12));
        CHECK_FALSE(tree.any_within(p, d * 0.99));
    }
    // Outside a corner, every triangle around it is as near: the answer is the first of them in
    // the input, whatever order the tree visits them in.
    size_t ties = 0;
    for (size_t v = 0; v < pos.size(); v += 7) {
        const std::array<double, 3> p{1.5 * pos[v][0], 1.5 * pos[v][1], 1.5 * pos[v][2]};
        double brute = INFINITY;
        uint32_t first = 0, at = 0;
        for (uint32_t i = 0; i < tri.size(); ++i) {
            const auto& t = tri[i];
            std::array<double, 3> a{pos[t[0]][0], pos[t[0]][1], pos[t[0]][2]};
            std::array<double, 3> b{pos[t[1]][0], pos[t[1]][1], pos[t[1]][2]};
            std::array<double, 3> c{pos[t[2]][0], pos[t[2]][1], pos[t[2]][2]};
            auto cp = closest_point_on_triangle(p, a, b, c);
            double d = (cp[0] - p[0]) * (cp[0] - p[0]) + (cp[1] - p[1]) * (cp[1] - p[1]) + (cp[2] - p[2]) * (cp[2] - p[2]);
            if (d < brute) brute = d, first = i, at = 1;
            else if (d == brute) ++at;
        }
        ties += at > 1;
        const ClosestPoint c = tree.closest_point(p);
        REQUIRE(c.found);
        CHECK(c.squared_distance == brute);
        CHECK(c.triangle == first);
    }
    CHECK(ties > 10);
}

TEST_CASE("triangle tree ignores out-of-range indices and non-finite corners, and handles empty input") {
    std::vector<std::array<float, 3>> pos{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {NAN, 0, 0}};
    std::vector<std::array<uint32_t, 3>> tri{{0, 1, 2}, {0, 1, 9}, {0, 1, 3}};
    TriangleTree tree(pos, tri);
    CHECK(tree.triangle_count() == 1);
    ClosestPoint c = tree.closest_point({0.2, 0.2, 1.0});
    REQUIRE(c.found);
    CHECK(c.triangle == 0);
    CHECK(c.squared_distance == doctest::Approx(1.0));
    TriangleTree empty(std::span<const std::array<float, 3>>{}, std::span<const std::array<uint32_t, 3>>{});
    CHECK(empty.empty());
    CHECK_FALSE(empty.closest_point({0, 0, 0}).found);
    CHECK(std::isinf(empty.distance({0, 0, 0})));
}

TEST_CASE("closest point on a degenerate triangle is on its longest edge") {
    auto p = closest_point_on_triangle({0.5, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    CHECK(p[0] == doctest::Approx(0.5));
    CHECK(p[1] == doctest::Approx(0.0));
}
