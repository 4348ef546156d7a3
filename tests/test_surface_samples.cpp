// Surface samples: the points the encoder adds to a low-poly model's vertices so that the decoder
// has enough of its surface to rebuild it.
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"
#include "encode_options.h"
#include "shapes.h"
#include "support.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

using namespace ellicast;
using ellicast::test::have_sample;
using ellicast::test::fast_options;
using ellicast::test::receive_every_packet;
using ellicast::test::unbudgeted;
using ellicast::test::shared_samples;

namespace {

// A unit cube centred on the origin as glTF has it: 24 vertices (four per face, each with its
// face's normal), 12 triangles, outward.
Mesh cube() {
    Mesh m = ellicast::samples::box({1, 1, 1});
    m.name = "cube";
    return m;
}

// The stream's points of object 0, dequantized, with their normals.
std::vector<SurfacePoint> points_of(const EncodeResult& r) {
    std::vector<SurfacePoint> out;
    for (const QuantizedPoint& q : r.contents[0].points) out.push_back(dequantize_point(q, r.info, r.info.objects[0]));
    return out;
}

}  // namespace

TEST_CASE("surface samples lie on the faces of a cube, carry their face's normal and fill every face") {
    const Mesh box = cube();
    EncodeOptions o = unbudgeted(fast_options());
    EncodeResult r = encode_meshes({box}, o);
    REQUIRE(r.reports[0].samples > 100);
    const auto pts = points_of(r);
    const double step = r.info.objects[0].frame.scale / ((1 << r.info.position_bits) - 1);
    const double spacing = o.sample_spacing * std::sqrt(3.0);
    size_t on_edges = 0;
    for (const SurfacePoint& p : pts) {
        double far = 0;
        int axis = 0;
        for (int k = 0; k < 3; ++k)
            if (std::abs(p.position[k]) > far) far = std::abs(p.position[k]), axis = k;
        CHECK(far == doctest::Approx(0.5).epsilon(step));
        int faces = 0;
        for (int k = 0; k < 3; ++k) faces += std::abs(std::abs(p.position[k]) - 0.5) <= step;
        if (faces > 1) {
            ++on_edges;
            continue;  // on an edge: one attribute set per face, checked below
        }
        // Inside a face: its normal is that face's, to the normal quantization.
        CHECK(std::abs(p.normal[axis]) > 0.999);
        CHECK((p.normal[axis] > 0) == (p.position[axis] > 0));
    }
    // Along the 12 edges, a point per crease spacing (half the face spacing), with both faces' normals.
    CHECK(on_edges >= size_t(2 * 12 * (1.0 / (spacing / 2) - 1)));
    // Every spot of every face is near a point.
    for (int axis = 0; axis < 3; ++axis)
        for (double a = -0.45; a <= 0.45; a += 0.1)
            for (double b = -0.45; b <= 0.45; b += 0.1) {
                std::array<double, 3> q{};
                q[axis] = 0.5, q[(axis + 1) % 3] = a, q[(axis + 2) % 3] = b;
                double best = 1e9;
                for (const SurfacePoint& p : pts) {
                    double d = 0;
                    for (int k = 0; k < 3; ++k) d += (q[k] - p.position[k]) * (q[k] - p.position[k]);
                    best = std::min(best, std::sqrt(d));
                }
                CHECK(best <= spacing);
            }
}

TEST_CASE("an edge shared by two triangles is split at the same points from both sides") {
    // A square of two triangles, no attributes: every point of the stream has its own position.
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    EncodeResult r = encode_meshes({quad}, unbudgeted(fast_options()));
    REQUIRE(r.reports[0].samples > 0);
    std::set<std::array<uint32_t, 3>> positions;
    for (const QuantizedPoint& q : r.contents[0].points) positions.insert(q.position);
    CHECK(positions.size() == r.contents[0].points.size());
    // The diagonal's points are made by both triangles, bit for bit: each one is one sample, one point.
    CHECK(r.contents[0].points.size() == r.reports[0].samples + 4);
    // No two points closer than a tenth of the spacing: no near-duplicates from float rounding.
    const auto pts = points_of(r);
    const double spacing = fast_options().sample_spacing * std::sqrt(2.0);
    for (size_t i = 0; i < pts.size(); ++i)
        for (size_t j = i + 1; j < pts.size(); ++j) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d += (pts[i].position[k] - pts[j].position[k]) * (pts[i].position[k] - pts[j].position[k]);
            CHECK(std::sqrt(d) > spacing / 10);
        }
}

TEST_CASE("sample spacing 0 sends the original vertices only, and the sample budget bounds the points") {
    const Mesh box = cube();
    EncodeOptions o = unbudgeted(fast_options());
    o.sample_spacing = 0;
    EncodeResult plain = encode_meshes({box}, o);
    CHECK(plain.reports[0].samples == 0);
    CHECK(plain.info.objects[0].point_count == 24);  // 8 positions, 3 normals each
    o.sample_spacing = 0.001;  // would be millions of points
    o.max_samples = 5000;
    EncodeResult capped = encode_meshes({box}, o);
    CHECK(capped.reports[0].samples <= 5000);
    CHECK(capped.reports[0].samples > 1000);
    o.sample_spacing = -1;
    CHECK_THROWS_AS(encode_meshes({box}, o), std::invalid_argument);
    o.sample_spacing = 0.03;
    o.max_samples = 20000000;
    CHECK_THROWS_AS(encode_meshes({box}, o), std::invalid_argument);
}

TEST_CASE("a low-poly model comes back closer with surface samples than from its vertices alone") {
    if (!have_sample("gltf/Fox/Fox.gltf")) return;
    LoadResult loaded = load_meshes((shared_samples() / "gltf/Fox/Fox.gltf").string());
    REQUIRE(loaded.meshes.size() == 1);
    auto rms_both_ways = [&](double spacing) {
        EncodeOptions o;
        o.sample_spacing = spacing;
        EncodeResult r = encode_meshes(loaded.meshes, o);
        const ReceivedStream rx = receive_every_packet(r);
        std::vector<Mesh> decoded;
        StreamDecodeReport report;
        std::string error;
        REQUIRE_MESSAGE(decode_stream(rx, DecodeOptions{}, decoded, report, error), error);
        REQUIRE(decoded.size() == 1);
        SurfaceDistance dist;
        SurfaceDistanceOptions so;
        so.samples = 30000;
        REQUIRE_MESSAGE(surface_distance(loaded.meshes, decoded, so, dist, error), error);
        MESSAGE("sample spacing " << spacing << ": RMS " << dist.percent(dist.a_to_b.rms) << "% / "
                                  << dist.percent(dist.b_to_a.rms) << "% of the diagonal");
        return std::max(dist.percent(dist.a_to_b.rms), dist.percent(dist.b_to_a.rms));
    };
    const double vertices_only = rms_both_ways(0);
    const double sampled = rms_both_ways(EncodeOptions{}.sample_spacing);
    CHECK(sampled < vertices_only / 2);
    CHECK(sampled <= 0.2);  // 0.6% from the 1,728 vertices alone
}

TEST_CASE("a capped model gets nearly the whole sample budget, not a spacing step coarser") {
    if (!have_sample("gltf/Fox/Fox.gltf")) return;
    LoadResult loaded = load_meshes((shared_samples() / "gltf/Fox/Fox.gltf").string());
    REQUIRE(loaded.meshes.size() == 1);
    EncodeOptions o = unbudgeted(fast_options());
    o.sample_spacing = 0.003;  // far more samples than any budget below
    for (uint32_t budget : {5000u, 8000u, 12000u}) {
        o.max_samples = budget;
        EncodeResult r = encode_meshes(loaded.meshes, o);
        CAPTURE(budget);
        MESSAGE("budget " << budget << ": " << r.reports[0].samples << " samples");
        CHECK(r.reports[0].samples <= budget);
        CHECK(r.reports[0].samples >= 0.93 * budget);
    }
}

TEST_CASE("samples follow the vertices' bytes: none on a box, at most the budget per vertex") {
    // Samples serve a receiver only until the exact layer is whole, and lengthen every cycle: the
    // 24-vertex Box sample got 9,522 of them (a 127 KB stream for a 1 KB asset).
    const Mesh box = cube();
    EncodeOptions o = fast_options();
    CHECK(encode_meshes({box}, o).reports[0].samples == 0);
    CHECK(encode_meshes({box}, o).info.objects[0].point_count == 24);
    o.sample_budget = 2;  // samples per vertex at most
    const EncodeResult two = encode_meshes({box}, o);
    CHECK(two.reports[0].samples <= 48);
    CHECK(two.reports[0].samples > 24);
    o.sample_budget = -1;  // the spacing's alone
    CHECK(encode_meshes({box}, o).reports[0].samples > 1000);
    o.sample_budget = -2;
    CHECK_THROWS_AS(encode_meshes({box}, o), std::invalid_argument);
    o.sample_budget = 1e6;
    CHECK_THROWS_AS(encode_meshes({box}, o), std::invalid_argument);
}

TEST_CASE("the Box sample's whole stream, repair included, is under 2 KB and every packet brings the box back exactly") {
    if (!have_sample("gltf/Box-glb/Box.glb")) return;
    const Asset asset = load_asset((shared_samples() / "gltf/Box-glb/Box.glb").string());
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, EncodeOptions{}, 1, true, encoded, error), error);
    size_t bytes = 0;
    ReceivedStream stream;
    size_t where = 0;
    for (const auto& p : encoded.packets) {
        bytes += p.size();
        REQUIRE(stream.add_packet(p, where++) == Error::Ok);
    }
    MESSAGE("the Box: " << encoded.packets.size() << " packets, " << bytes << " bytes");
    CHECK(bytes < 2000);  // 1,789: 50 ellipsoids, 24 points, 12 triangles, a repair packet each (127,097 before)
    std::vector<Mesh> decoded;
    StreamDecodeReport report;
    REQUIRE_MESSAGE(decode_stream(stream, DecodeOptions{}, decoded, report, error), error);
    REQUIRE(decoded.size() == 1);
    CHECK(decoded[0].triangles.size() == 12);  // the exact layer: the box itself
}

TEST_CASE("spot keeps the samples its large triangles need: fewer than a quarter of its vertices") {
    if (!have_sample("meshes/spot.obj")) return;
    LoadResult loaded = load_meshes((shared_samples() / "meshes/spot.obj").string());
    REQUIRE(loaded.meshes.size() == 1);
    EncodeOptions o = fast_options();
    const EncodeResult r = encode_meshes(loaded.meshes, o);
    const EncodeResult unbounded = encode_meshes(loaded.meshes, unbudgeted(o));
    MESSAGE("spot: " << r.reports[0].samples << " samples, " << unbounded.reports[0].samples << " without the budget");
    CHECK(r.reports[0].samples == unbounded.reports[0].samples);
    CHECK(r.reports[0].samples > 500);
}
