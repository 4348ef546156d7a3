// Sheets: surface with no inside (a flat figure, a single-sided panel). The encoder lays flat
// ellipsoids across it and samples it at half the spacing; the decoder puts each of its points into
// both sides of the thin base, so the sheet comes back whole rather than as two halves full of gaps.
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"
#include "encode_options.h"
#include "support.h"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

using namespace ellicast;
using ellicast::test::have_sample;
using ellicast::test::shared_samples;

namespace {

struct Decoded {
    Mesh mesh;
    ObjectDecodeReport report;
};

// Encodes `original` (default options unless given) and decodes every packet, or the stream info,
// the ellipsoids and a seeded random half of the point packets; `base` receives the base mesh.
Decoded encode_decode(const std::vector<Mesh>& original, bool half_of_the_points, EncodeResult* encoded_out = nullptr,
                      const EncodeOptions& options = test::unbudgeted(), Mesh* base = nullptr) {
    EncodeResult encoded = encode_meshes(original, options);
    StreamPackets packets;
    REQUIRE(packetize_stream(encoded.info, encoded.contents, 1, packets) == Error::Ok);
    ReceivedStream stream;
    size_t where = 0;
    for (auto* group : {&packets.stream_info, &packets.ellipsoids, &packets.maps})  // the base, with its map (format 1.7)
        for (const auto& p : *group) REQUIRE(stream.add_packet(p, where++) == Error::Ok);
    std::mt19937 rng(100);
    for (const auto& p : packets.points)
        if (!half_of_the_points || (rng() & 1)) REQUIRE(stream.add_packet(p, where++) == Error::Ok);
    std::vector<Mesh> meshes;
    StreamDecodeReport report;
    std::string error;
    DecodeOptions decoding;
    if (base)
        decoding.snapshot = [&](size_t, size_t points, const Mesh& m) {
            if (points == 0) *base = m;
        };
    REQUIRE_MESSAGE(decode_stream(stream, decoding, meshes, report, error), error);
    REQUIRE(meshes.size() == 1);
    if (encoded_out) *encoded_out = encoded;
    return {meshes[0], report.objects[0]};
}

// A flat wavy-edged disc of radius 1 in the plane z = 0: rings of vertices, one-sided, no inside.
Mesh flat_disc() {
    Mesh m;
    m.name = "disc";
    const int rings = 12, sectors = 48;
    m.positions.push_back({0, 0, 0});
    for (int i = 1; i <= rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            const double a = 2 * M_PI * j / sectors, r = double(i) / rings * (1 + 0.08 * std::sin(5 * a));
            m.positions.push_back({float(r * std::cos(a)), float(r * std::sin(a)), 0.0f});
        }
    auto at = [&](int i, int j) { return uint32_t(1 + (i - 1) * sectors + (j % sectors)); };
    for (int j = 0; j < sectors; ++j) m.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

double rms_percent(const std::vector<Mesh>& a, const Mesh& b, bool back, double* far_fraction = nullptr) {
    SurfaceDistance d;
    std::string error;
    REQUIRE_MESSAGE(surface_distance(a, {b}, {}, d, error), error);
    if (far_fraction) *far_fraction = d.a_to_b.far_fraction;
    return d.percent(back ? d.b_to_a.rms : d.a_to_b.rms);
}

}  // namespace

TEST_CASE("a flat disc comes back as a whole sheet: its points go into both sides of the thin base") {
    const std::vector<Mesh> original{flat_disc()};
    EncodeResult encoded;
    Decoded full = encode_decode(original, false, &encoded);
    CHECK(encoded.reports[0].flat_ellipsoids > 0);
    CHECK(full.report.sheet_points > encoded.info.objects[0].point_count / 2);
    // Without the second side the disc came back at RMS 0.17% with 1.8% of its area farther than
    // 0.5% of the diagonal (half of its points on each side of the base); with it, 0.13% and 1.0%,
    // the holes of its base still open; with flat ellipsoids from points inside its faces (a base
    // without holes) and the base's leftovers round its rim removed, 0.017% / 0.0015% and none.
    double far = 1;
    CHECK(rms_percent(original, full.mesh, false, &far) <= 0.03);
    CHECK(rms_percent(original, full.mesh, true) <= 0.01);
    CHECK(far < 0.001);
    // Most points have a vertex on each side.
    CHECK(full.mesh.positions.size() >= size_t(1.5 * encoded.info.objects[0].point_count));
}

TEST_CASE("a flat disc's thin base is one closed shell without holes, and the complete disc keeps no base vertex") {
    // The disc's faces are several grid cells wide: flat ellipsoids fitted to its vertices alone
    // left gaps between them thinner than the grid, each a tunnel through the base (genus 55 and 32
    // loose bubbles) that no inserted point could close.
    Mesh base;
    Decoded full = encode_decode({flat_disc()}, false, nullptr, test::unbudgeted(), &base);
    REQUIRE(!base.triangles.empty());
    // Euler characteristic V - E + F of the base, vertices welded by position: 2 for one sphere.
    std::map<std::array<float, 3>, uint32_t> id;
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const auto& t : base.triangles)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = id.emplace(base.positions[t[k]], uint32_t(id.size())).first->second;
            const uint32_t b = id.emplace(base.positions[t[(k + 1) % 3]], uint32_t(id.size())).first->second;
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    CHECK(long(id.size()) - long(edges.size()) + long(base.triangles.size()) == 2);
    CHECK(full.report.mc_vertices_left == 0);
}

TEST_CASE("a low-poly sheet (two triangles) gets flat ellipsoids over its whole area, not only at its corners") {
    // A square of two triangles, larger than many grid cells: its four vertices alone gave four
    // small blobs at its corners, and the points of its middle had no base to go into.
    Mesh square;
    square.name = "square";
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    EncodeResult encoded;
    Decoded full = encode_decode({square}, false, &encoded);
    CHECK(encoded.reports[0].flat_ellipsoids > 8);
    CHECK(full.report.sheet_points > encoded.info.objects[0].point_count / 2);
    double far = 1;
    CHECK(rms_percent({square}, full.mesh, false, &far) <= 0.05);
    CHECK(rms_percent({square}, full.mesh, true) <= 0.05);
    CHECK(far < 0.001);
}

TEST_CASE("a sheet gets flat ellipsoids over its whole area when the budget is short: fewer, wider discs") {
    // 60 ellipsoids where four voxels wide discs would need about 250: wider ones instead, rather
    // than a base over the first quarter of the sheet (RMS 0.12% from the original, 0.8% of the
    // area far, before).
    Mesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    EncodeOptions options = test::unbudgeted();
    options.max_ellipsoids = 60;
    EncodeResult encoded;
    Decoded full = encode_decode({square}, false, &encoded, options);
    CHECK(encoded.reports[0].flat_ellipsoids <= 60);
    double far = 1;
    CHECK(rms_percent({square}, full.mesh, false, &far) <= 0.03);
    CHECK(rms_percent({square}, full.mesh, true) <= 0.03);
    CHECK(far < 0.001);
}

TEST_CASE("a closed model has no sheet points") {
    // A closed squashed box: no flat ellipsoid, so nothing goes into two sides.
    Mesh box;
    box.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0.3f}, {1, 0, 0.3f}, {1, 1, 0.3f}, {0, 1, 0.3f}};
    box.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    EncodeResult encoded;
    Decoded full = encode_decode({box}, false, &encoded);
    CHECK(encoded.reports[0].flat_ellipsoids == 0);
    CHECK(full.report.sheet_points == 0);
}

TEST_CASE("woody, a flat figure: every packet within 0.04% RMS (0.07% back), half of the points within 0.06%") {
    if (!have_sample("meshes/woody.obj")) return;
    const auto original = load_meshes((shared_samples() / "meshes/woody.obj").string()).meshes;
    // Measured: 0.020% / 0.047% with every packet, 0.033% with half of them (flat ellipsoids from
    // vertices alone: 0.046% / 0.045%, and 0.070% with half, its base holed).
    Decoded full = encode_decode(original, false);
    double far = 1;
    CHECK(rms_percent(original, full.mesh, false, &far) <= 0.04);
    CHECK(rms_percent(original, full.mesh, true) <= 0.07);
    CHECK(far < 0.001);
    // An open sheet is measured from the original to the reconstruction (the rule for open
    // models): with half of the points the base still stands where points are missing.
    Decoded half = encode_decode(original, true);
    CHECK(rms_percent(original, half.mesh, false) <= 0.06);
}

TEST_CASE("points on sheets are found through an index of the flat ellipsoids: the same answers, and a pile of discs is not quadratic") {
    // An oracle: every flat ellipsoid tried for every point (the test spec 13's decoder states).
    auto brute = [](const std::vector<Ellipsoid>& es, double cell, const std::vector<SurfacePoint>& ps) {
        std::vector<char> out(ps.size(), 0);
        for (size_t i = 0; i < ps.size(); ++i)
            for (const Ellipsoid& e : es) {
                const double lo = std::min({e.radii[0], e.radii[1], e.radii[2]});
                const double hi = std::max({e.radii[0], e.radii[1], e.radii[2]});
                const double mid = double(e.radii[0]) + e.radii[1] + e.radii[2] - lo - hi;
                if (!(lo <= 2 * cell) || !(mid >= 2 * lo)) continue;
                const double w = e.rotation[0], x = e.rotation[1], y = e.rotation[2], z = e.rotation[3];
                const double n = std::sqrt(w * w + x * x + y * y + z * z);
                const double a = w / n, b = x / n, c = y / n, d = z / n;
                const double axis[3][3] = {{1 - 2 * (c * c + d * d), 2 * (b * c + a * d), 2 * (b * d - a * c)},
                                           {2 * (b * c - a * d), 1 - 2 * (b * b + d * d), 2 * (c * d + a * b)},
                                           {2 * (b * d + a * c), 2 * (c * d - a * b), 1 - 2 * (b * b + c * c)}};
                double across = 0, along = 0, dist2 = 0, dd[3];
                for (int k = 0; k < 3; ++k) dd[k] = double(ps[i].position[k]) - e.center[k], dist2 += dd[k] * dd[k];
                if (dist2 > hi * hi) continue;
                for (int k = 0; k < 3; ++k) {
                    const double t = (dd[0] * axis[k][0] + dd[1] * axis[k][1] + dd[2] * axis[k][2]) / e.radii[k];
                    (e.radii[k] == lo ? across : along) += t * t;
                }
                if (across <= 0.25 && along <= 1) {
                    out[i] = 1;
                    break;
                }
            }
        return out;
    };
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    const double cell = 0.01;
    std::vector<Ellipsoid> es;
    for (int i = 0; i < 3000; ++i) {
        Ellipsoid e;
        e.center = {u(rng), u(rng), u(rng)};
        const float wide = 0.05f + 0.1f * std::abs(u(rng));
        e.radii = {wide, wide * (0.6f + 0.4f * std::abs(u(rng))), float(cell) * (0.5f + std::abs(u(rng)))};
        if (i % 5 == 0) e.radii[2] = 0.1f;  // not flat
        std::array<float, 4> q = {u(rng), u(rng), u(rng), u(rng)};
        e.rotation = q;
        es.push_back(e);
    }
    std::vector<SurfacePoint> ps(20000);
    for (auto& p : ps) p.position = {u(rng), u(rng), u(rng)};
    // Points on the discs' mid-planes too, so that some are on sheets.
    for (size_t i = 0; i < 5000; ++i) ps[i].position = es[i % es.size()].center;
    const auto expected = brute(es, cell, ps);
    const auto got = points_on_sheets(es, cell, ps);
    CHECK(got == expected);
    size_t on = 0;
    for (char c : got) on += c;
    MESSAGE(on << " of " << ps.size() << " points on sheets among " << es.size() << " ellipsoids");
    CHECK(on >= 4000);

    // A hostile pile: 200,000 copies of one disc and 50,000 points just off its plane (within its
    // reach, never on the sheet): every point would try every disc (10^10 tests); the index tries at
    // most a bounded number for each.
    std::vector<Ellipsoid> pile(200000);
    for (auto& e : pile) e.radii = {0.5f, 0.5f, float(cell)};
    std::vector<SurfacePoint> off(50000);
    for (size_t i = 0; i < off.size(); ++i) off[i].position = {0.3f * u(rng), 0.3f * u(rng), float(0.8 * cell)};
    const auto piled = points_on_sheets(pile, cell, off);
    CHECK(std::count(piled.begin(), piled.end(), 1) == 0);
}
