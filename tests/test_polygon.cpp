// Polygon faces: triangulated into exactly their area and orientation (concave ones too), the fan
// kept where it was right, a face that is not simple fanned with one warning or refused when large.
#include "ellicast/converters/mesh_input.h"
#include "ellicast/converters/polygon.h"
#include "support.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using namespace ellicast;

namespace {

using Corners = std::vector<std::array<float, 3>>;
constexpr double kPi = 3.14159265358979323846;

struct P {
    double x, y;
};

// A polygon given in the plane, placed in space on a tilted plane (so that the projection is tested).
Corners place(const std::vector<P>& poly) {
    Corners out;
    const double c = std::cos(0.7), s = std::sin(0.7);
    for (const P& p : poly) out.push_back({float(p.x), float(c * p.y), float(s * p.y + 3)});
    return out;
}

std::vector<P> unplace(const Corners& corners) {
    const double c = std::cos(0.7), s = std::sin(0.7);
    std::vector<P> out;
    for (const auto& q : corners) out.push_back({q[0], c * q[1] + s * (q[2] - 3)});
    return out;
}

double cross(const P& a, const P& b, const P& c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

double signed_area(const std::vector<P>& p) {
    double a = 0;
    for (size_t i = 0; i < p.size(); ++i) a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
    return 0.5 * a;
}

bool inside_polygon(const std::vector<P>& p, P q) {
    bool in = false;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
        if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
            in = !in;
    return in;
}

// The triangles are n - 2, keep the polygon's orientation, sum to its area, and cover every sampled
// point inside it exactly once and none outside.
void check_covers(const std::vector<P>& poly, const PolygonTriangulation& t) {
    const std::vector<P> flat = unplace(place(poly));
    REQUIRE(t.simple);
    REQUIRE(t.triangles.size() == poly.size() - 2);
    const double area = signed_area(flat);
    const double sign = area > 0 ? 1 : -1;
    double sum = 0;
    for (const auto& tri : t.triangles) {
        for (uint32_t i : tri) REQUIRE(i < poly.size());
        const double a = 0.5 * cross(flat[tri[0]], flat[tri[1]], flat[tri[2]]) * sign;
        CHECK(a >= -1e-9 * std::abs(area));
        sum += std::abs(a);
    }
    CHECK(sum == doctest::Approx(std::abs(area)).epsilon(1e-5));
    double x0 = 1e30, x1 = -1e30, y0 = 1e30, y1 = -1e30;
    for (const P& q : flat) x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    int wrong = 0;
    for (int i = 0; i < 61; ++i)
        for (int j = 0; j < 61; ++j) {
            const P q{x0 + (x1 - x0) * (i + 0.5137) / 61, y0 + (y1 - y0) * (j + 0.4861) / 61};
            int covered = 0;
            for (const auto& tri : t.triangles) {
                const P &a = flat[tri[0]], &b = flat[tri[1]], &c = flat[tri[2]];
                const double s0 = cross(a, b, q) * sign, s1 = cross(b, c, q) * sign, s2 = cross(c, a, q) * sign;
                covered += s0 > 0 && s1 > 0 && s2 > 0;
            }
            wrong += covered != (inside_polygon(flat, q) ? 1 : 0);
        }
    CHECK(wrong == 0);
}

std::vector<P> l_shape() { return {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}; }

// Teeth of width 1 and height 5 on a base of height 1, gaps of width 1 between them.
std::vector<P> comb(int teeth) {
    std::vector<P> p = {{0, 0}, {2.0 * teeth - 1, 0}};
    for (int k = teeth - 1; k >= 0; --k) {
        p.push_back({2.0 * k + 1, 5});
        p.push_back({2.0 * k, 5});
        if (k > 0) p.push_back({2.0 * k, 1}), p.push_back({2.0 * k - 1, 1});
    }
    return p;
}

std::vector<P> star(int n) {
    std::vector<P> p;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * kPi * i / n, r = i % 2 == 0 ? 1.0 : 0.5;
        p.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return p;
}

// A thick spiral: ears come two at a time, so the monotone partition does the work.
std::vector<P> spiral(int per_side) {
    std::vector<P> outer, inner;
    for (int i = 0; i < per_side; ++i) {
        const double t = 6 * kPi * i / (per_side - 1);
        outer.push_back({(1 + 0.5 * t) * std::cos(t), (1 + 0.5 * t) * std::sin(t)});
        inner.push_back({(0.5 + 0.5 * t) * std::cos(t), (0.5 + 0.5 * t) * std::sin(t)});
    }
    std::vector<P> p(outer.begin(), outer.end());
    p.insert(p.end(), inner.rbegin(), inner.rend());
    return p;
}

std::string obj_of(const std::vector<std::vector<P>>& faces) {
    std::ostringstream out;
    out.precision(9);
    size_t base = 1;
    for (const auto& f : faces) {
        for (const P& q : f) out << "v " << q.x << " " << q.y << " 0\n";
        out << "f";
        for (size_t i = 0; i < f.size(); ++i) out << " " << base + i;
        out << "\n";
        base += f.size();
    }
    return out.str();
}

std::filesystem::path write_obj(const std::string& test, const std::string& text) {
    const auto dir = ellicast::test::scratch_dir(test);
    const auto path = dir / "polygon.obj";
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Triangles of a loaded mesh projected on z = 0: total area and whether any two overlap at the
// sampled points.
double loaded_area(const Mesh& m) {
    double sum = 0;
    for (const auto& t : m.triangles) {
        const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
        sum += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    return sum;
}

}  // namespace

TEST_CASE("a concave polygon (an L, a comb, a star) triangulates into n - 2 triangles covering exactly its area, in its orientation") {
    for (const auto& poly : {l_shape(), comb(7), star(40), star(2000), spiral(300)}) {
        CAPTURE(poly.size());
        check_covers(poly, triangulate_polygon(place(poly)));
        // Clockwise: the triangles turn clockwise too.
        std::vector<P> reversed(poly.rbegin(), poly.rend());
        check_covers(reversed, triangulate_polygon(place(reversed)));
    }
    // A convex polygon of many corners is simple too, split in halving rounds rather than fanned.
    std::vector<P> circle;
    for (int i = 0; i < 1000; ++i) circle.push_back({std::cos(2 * kPi * i / 1000), std::sin(2 * kPi * i / 1000)});
    const auto t = triangulate_polygon(place(circle));
    check_covers(circle, t);
    size_t from_first = 0;
    for (const auto& tri : t.triangles) from_first += tri[0] == 0 || tri[1] == 0 || tri[2] == 0;
    CHECK(from_first < 20);
}

TEST_CASE("random star-shaped polygons with collinear runs triangulate exactly") {
    std::mt19937 rng(29);
    for (int round = 0; round < 40; ++round) {
        const int n = 4 + int(rng() % 300);
        std::vector<P> poly;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * kPi * i / n;
            const double r = 0.2 + double(rng() % 1000) / 1000.0;
            poly.push_back({r * std::cos(a), r * std::sin(a)});
        }
        // A straight run: corners on the segment between two corners.
        if (n > 10) {
            const P a = poly[3], b = poly[7];
            for (int k = 4; k < 7; ++k) poly[k] = {a.x + (b.x - a.x) * (k - 3) / 4.0, a.y + (b.y - a.y) * (k - 3) / 4.0};
        }
        CAPTURE(round);
        CAPTURE(n);
        check_covers(poly, triangulate_polygon(place(poly)));
    }
}

TEST_CASE("a small polygon the fan from its first corner triangulates keeps that fan") {
    const std::vector<P> quad = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    auto t = triangulate_polygon(place(quad));
    CHECK(t.simple);
    CHECK(t.triangles == std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
    // Concave at its second corner: the fan would cover area outside, so the other diagonal.
    const std::vector<P> dart = {{0, 0}, {1, 0.8}, {2, 0}, {1, 2}};
    t = triangulate_polygon(place(dart));
    check_covers(dart, t);
    for (const auto& tri : t.triangles) CHECK((std::count(tri.begin(), tri.end(), 1u) == 1 && std::count(tri.begin(), tri.end(), 3u) == 1));
}

TEST_CASE("polygons that are not simple or have no area fall back to the fan, without crashing") {
    const std::vector<std::vector<P>> bad = {
        {{0, 0}, {1, 1}, {1, 0}, {0, 1}},                          // bow-tie, no area
        {{0, 0}, {2, 2}, {2, 0}, {0, 1}},                          // bow-tie with area
        {{0, 0}, {1, 0}, {1, 0}, {1, 1}, {0, 1}},                  // a corner twice
        {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}},                  // a line
        {{1, 1}, {1, 1}, {1, 1}, {1, 1}},                          // one point
        {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}, {4, 0}, {4, 4}, {0, 4}},  // around twice
    };
    for (const auto& poly : bad) {
        CAPTURE(poly.size());
        const auto t = triangulate_polygon(place(poly));
        CHECK(!t.simple);
        CHECK(t.triangles.size() == poly.size() - 2);
        CHECK(t.triangles[0] == std::array<uint32_t, 3>{0, 1, 2});
    }
    // Not a number anywhere: the fan, not simple.
    Corners nan = place(l_shape());
    nan[2][1] = std::nanf("");
    CHECK(!triangulate_polygon(nan).simple);
    // A pentagram-like self-crossing polygon of many corners is found out in bounded time.
    std::vector<P> crossing;
    for (int i = 0; i < 5001; ++i) {
        const double a = 2 * kPi * ((2 * i) % 5001) / 5001;
        crossing.push_back({std::cos(a), std::sin(a)});
    }
    CHECK(!triangulate_polygon(place(crossing)).simple);
    CHECK(triangulate_polygon(Corners{}).triangles.empty());
}

TEST_CASE("an OBJ with a concave polygon face loads as triangles covering it without overlap") {
    const auto path = write_obj("polygon_concave_obj", obj_of({l_shape(), comb(5)}));
    LoadResult r = load_meshes(path.string());
    REQUIRE(r.meshes.size() == 1);
    const Mesh& m = r.meshes[0];
    CHECK(m.triangles.size() == (6 - 2) + (comb(5).size() - 2));
    CHECK(loaded_area(m) == doctest::Approx(signed_area(l_shape()) + signed_area(comb(5))).epsilon(1e-6));
    for (const auto& t : m.triangles) {
        const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
        CHECK((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0);
    }
    for (const auto& w : r.warnings) CHECK(w.find("not simple") == std::string::npos);
}

TEST_CASE("an OBJ polygon keeps each corner's texture coordinate") {
    std::string text = "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\n";
    for (int i = 0; i < 6; ++i) text += "vt " + std::to_string(0.1 * i) + " " + std::to_string(0.05 * i) + "\n";
    text += "f 1/1 2/2 3/3 4/4 5/5 6/6\n";
    LoadResult r = load_meshes(write_obj("polygon_uv_obj", text).string());
    const Mesh& m = r.meshes[0];
    REQUIRE(m.texcoords.size() == m.positions.size());
    CHECK(m.triangles.size() == 4);
    const float xs[6] = {0, 3, 3, 1, 1, 0}, ys[6] = {0, 0, 1, 1, 3, 3};
    for (size_t v = 0; v < m.positions.size(); ++v) {
        int corner = -1;
        for (int k = 0; k < 6; ++k)
            if (m.positions[v][0] == xs[k] && m.positions[v][1] == ys[k]) corner = k;
        REQUIRE(corner >= 0);
        CHECK(m.texcoords[v][0] == doctest::Approx(0.1 * corner));
        CHECK(m.texcoords[v][1] == doctest::Approx(0.05 * corner));
    }
}

TEST_CASE("OBJ faces that are not simple polygons are fanned with one warning for the file") {
    const std::vector<P> bowtie = {{0, 0}, {2, 2}, {2, 0}, {0, 1}};
    const std::vector<P> other = {{5, 0}, {7, 2}, {7, 0}, {5, 1}, {4, 0.5}};
    LoadResult r = load_meshes(write_obj("polygon_bowtie_obj", obj_of({bowtie, other, l_shape()})).string());
    size_t warnings = 0;
    for (const auto& w : r.warnings)
        if (w.find("not simple") != std::string::npos) {
            ++warnings;
            CHECK(w.find("2 polygon faces") != std::string::npos);
        }
    CHECK(warnings == 1);
    CHECK(r.meshes[0].triangles.size() >= 2 + 3 + 4 - 1);  // a fan triangle may be degenerate and dropped
}

TEST_CASE("a self-crossing OBJ polygon of more than 4,096 corners is refused, naming the face and its corners") {
    std::vector<P> crossing;
    for (int i = 0; i < 5001; ++i) {
        const double a = 2 * kPi * ((2 * i) % 5001) / 5001;
        crossing.push_back({std::cos(a), std::sin(a)});
    }
    const auto path = write_obj("polygon_refused_obj", obj_of({l_shape(), crossing}));
    std::string message;
    try {
        load_meshes(path.string());
    } catch (const InputError& e) {
        message = e.what();
    }
    CHECK(message.find(path.string()) != std::string::npos);
    CHECK(message.find("face 2 ") != std::string::npos);
    CHECK(message.find("5001 corners") != std::string::npos);
    CHECK(message.find("not a simple polygon") != std::string::npos);
}

TEST_CASE("a 20,000-corner star polygon face loads as its 19,998 triangles") {
    const auto path = write_obj("polygon_star_obj", obj_of({star(20000)}));
    LoadResult r = load_meshes(path.string());
    const Mesh& m = r.meshes[0];
    CHECK(m.triangles.size() == 19998);
    CHECK(loaded_area(m) == doctest::Approx(signed_area(star(20000))).epsilon(1e-5));
    for (const auto& w : r.warnings) CHECK(w.find("not simple") == std::string::npos);
}
