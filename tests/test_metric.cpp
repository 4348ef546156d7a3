// The surface distance metric behind `ellicast diff`.
#include "support.h"

#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"

#include <cmath>
#include <cstdio>

using namespace ellicast;

namespace {

// An n x n square of side `size` in the plane z = `z`, starting at (x0, 0).
Mesh square(float x0, float z, float size = 1, int n = 10) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back({x0 + size * i / n, size * j / n, z});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            m.triangles.push_back({a, b, d});
            m.triangles.push_back({a, d, c});
        }
    return m;
}

// A UV sphere of radius r with `rings` x `segments` quads, triangulated.
Mesh sphere(double r, int rings = 64, int segments = 128) {
    Mesh m;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            double t = M_PI * i / rings, p = 2 * M_PI * j / segments;
            m.positions.push_back({float(r * std::sin(t) * std::cos(p)), float(r * std::cos(t)),
                                   float(r * std::sin(t) * std::sin(p))});
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments, c = a + segments, d = b + segments;
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({b, c, d});
        }
    return m;
}

}  // namespace

TEST_CASE("a model is at distance zero from itself") {
    Mesh s = sphere(1, 16, 32);
    SurfaceDistance d;
    std::string error;
    REQUIRE(surface_distance({s}, {s}, {}, d, error));
    CHECK(d.a_to_b.max < 1e-6);
    CHECK(d.b_to_a.rms < 1e-6);
    CHECK(d.a_to_b.far_fraction == 0);
    CHECK(d.a_to_b.samples >= 100000);
}

TEST_CASE("parallel planes are exactly their offset apart, and the far fraction follows the threshold") {
    SurfaceDistance d;
    std::string error;
    SurfaceDistanceOptions options;
    options.samples = 5000;
    options.threshold_percent = 100.0 * 0.05 / std::sqrt(2.0);  // 0.05 of the diagonal sqrt(2)
    REQUIRE(surface_distance({square(0, 0)}, {square(0, 0.1f)}, options, d, error));
    CHECK(d.diagonal == doctest::Approx(std::sqrt(2.0)));
    CHECK(d.a_to_b.max == doctest::Approx(0.1).epsilon(1e-5));
    CHECK(d.a_to_b.mean == doctest::Approx(0.1).epsilon(1e-5));
    CHECK(d.a_to_b.rms == doctest::Approx(0.1).epsilon(1e-5));
    CHECK(d.a_to_b.far_fraction == 1.0);
    CHECK(d.percent(d.a_to_b.rms) == doctest::Approx(100 * 0.1 / std::sqrt(2.0)).epsilon(1e-4));
    options.threshold_percent = 100.0 * 0.2 / std::sqrt(2.0);
    REQUIRE(surface_distance({square(0, 0)}, {square(0, 0.1f)}, options, d, error));
    CHECK(d.a_to_b.far_fraction == 0.0);
}

TEST_CASE("a missing part shows as far area from the complete side only") {
    // A: two unit squares side by side; B: only the first. Half of A is far from B.
    SurfaceDistance d;
    std::string error;
    SurfaceDistanceOptions options;
    options.samples = 20000;
    options.threshold_percent = 1;
    REQUIRE(surface_distance({square(0, 0), square(1, 0)}, {square(0, 0)}, options, d, error));
    CHECK(d.a_to_b.far_fraction == doctest::Approx(0.5 - 0.01 * d.diagonal).epsilon(0.05));
    CHECK(d.a_to_b.max == doctest::Approx(1.0).epsilon(1e-4));
    CHECK(d.b_to_a.max < 1e-6);
    CHECK(d.b_to_a.far_fraction == 0);
}

TEST_CASE("two concentric spheres are their radius difference apart in both directions") {
    SurfaceDistance d;
    std::string error;
    REQUIRE(surface_distance({sphere(1.0)}, {sphere(1.02)}, {}, d, error));
    CHECK(d.a_to_b.mean == doctest::Approx(0.02).epsilon(0.02));
    CHECK(d.b_to_a.mean == doctest::Approx(0.02).epsilon(0.02));
    CHECK(d.hausdorff() == doctest::Approx(0.02).epsilon(0.05));
}

TEST_CASE("samples are deterministic for a seed and spread by area") {
    Mesh big = square(0, 0, 3, 1), small = square(10, 0, 1, 1);
    auto s1 = sample_surface({big, small}, 10000, 42);
    auto s2 = sample_surface({big, small}, 10000, 42);
    CHECK(s1 == s2);
    size_t on_big = 0;
    for (const auto& p : s1) on_big += p[0] < 5 ? 1 : 0;
    CHECK(double(on_big) / s1.size() == doctest::Approx(0.9).epsilon(0.02));
    CHECK(sample_surface({big, small}, 10000, 43) != s1);
}

TEST_CASE("a point set has no surface to measure: a clear error") {
    Mesh points;
    points.is_point_set = true;
    points.positions = {{0, 0, 0}, {1, 0, 0}};
    SurfaceDistance d;
    std::string error;
    CHECK_FALSE(surface_distance({points}, {square(0, 0)}, {}, d, error));
    CHECK(error.find("first") != std::string::npos);
    CHECK_FALSE(surface_distance({square(0, 0)}, {points}, {}, d, error));
    CHECK(error.find("second") != std::string::npos);
}

TEST_CASE("ellicast diff prints both directions for two sample meshes") {
    if (!test::have_sample("meshes/woody.obj")) return;
    auto woody = (test::shared_samples() / "meshes/woody.obj").string();
    std::string cmd = test::ellicast_exe().string() + " diff '" + woody + "' '" + woody + "' --samples 20000 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    REQUIRE(pipe);
    std::string out;
    char buffer[4096];
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    int status = pclose(pipe);
    CHECK(status == 0);
    CHECK(out.find("A -> B") != std::string::npos);
    CHECK(out.find("B -> A") != std::string::npos);
    auto line = out.find("Hausdorff distance (symmetric): ");
    REQUIRE(line != std::string::npos);
    CHECK(out.substr(line, out.find('\n', line) - line).find("(0.0000%)") != std::string::npos);
    cmd = test::ellicast_exe().string() + " diff '" + woody + "' /nonexistent/x.obj 2>&1";
    pipe = popen(cmd.c_str(), "r");
    out.clear();
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    CHECK(pclose(pipe) != 0);
    CHECK(out.find("/nonexistent/x.obj") != std::string::npos);
}
