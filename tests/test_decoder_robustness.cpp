// Streams a sender can make without breaking a checksum, which once crashed the decoder.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/format.h"
#include "encode_options.h"
#include "shapes.h"
#include "support.h"

#include <cmath>
#include <fstream>

#include <doctest/doctest.h>

using namespace ellicast;
using namespace ellicast::test;

namespace {

ReceivedStream every_packet(const EncodedAsset& encoded) {
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i) REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
    return stream;
}

}  // namespace

TEST_CASE("the milk truck decodes on the coarsest grids, where cutting tunnels adds edges while rims are walked") {
    // Filling a tunnel's rim adds edges whose halfedges lay past the marks taken before: a heap
    // write past the end (SIGSEGV at --grid 4, "free(): invalid next size" at --grid 8).
    if (!have_sample("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf")) return;
    const Asset truck = load_asset((shared_samples() / "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf").string());
    EncodeOptions encode;
    encode.max_ellipsoids = 40;
    encode.max_samples = 5000;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(truck, encode, 1, true, encoded, error), error);
    const ReceivedStream stream = every_packet(encoded);
    for (int grid : {4, 5, 8}) {
        CAPTURE(grid);
        DecodeOptions options;
        options.grid_resolution = grid;
        Asset decoded;
        StreamDecodeReport report;
        REQUIRE_MESSAGE(decode_asset(stream, options, decoded, report, error), error);
        size_t faces = 0;
        for (const auto& o : decoded.objects) faces += o.triangles.size();
        CHECK(faces > 0);
        for (const auto& o : decoded.objects)
            for (const auto& t : o.triangles)
                for (uint32_t v : t) REQUIRE(v < o.positions.size());
    }
}

TEST_CASE("ellipsoids whose stored rotations are all zero or all identity decode without touching memory they do not own") {
    // A sender can set every stored quaternion component of every ellipsoid (CRCs recomputed): the
    // rotations dequantize to valid ones (spec 6.1 normalizes), but the base they give is unlike any
    // an encoder makes; decoding the milk truck this way once read and wrote past the end of the
    // heap (tunnels cut at the end of the complete stream).
    if (!have_sample("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf")) return;
    const std::vector<Mesh> meshes = load_meshes((shared_samples() / "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf").string()).meshes;
    EncodeOptions encode;
    encode.max_ellipsoids = 40;
    encode.max_samples = 5000;
    const EncodeResult encoded = encode_meshes(meshes, encode);
    for (uint16_t stored : {uint16_t(0), uint16_t(8192)}) {
        CAPTURE(stored);
        EncodeResult tampered = encoded;
        for (auto& c : tampered.contents)
            for (auto& e : c.ellipsoids) e.rotation = {stored, stored, stored};
        const ReceivedStream stream = test::receive_every_packet(tampered);
        std::vector<Mesh> out;
        DecodeOptions options;
        std::string error;
        StreamDecodeReport report;
        REQUIRE_MESSAGE(decode_stream(stream, options, out, report, error), error);
        REQUIRE(out.size() == meshes.size());
        for (const auto& o : out) {
            CHECK(!o.triangles.empty());
            for (const auto& t : o.triangles)
                for (uint32_t v : t) REQUIRE(v < o.positions.size());
        }
    }
}

TEST_CASE("a stream whose points all stand at one position decodes in bounded time") {
    // Every point of a 20,000-vertex ball moved onto one position, each keeping its own normal: the
    // output's attribute choice once compared every pair of sets at that vertex (33 s for a small
    // model); now at most 16 of each.
    Mesh ball = samples::uv_ellipsoid(100, {0, 0, 0}, {1, 1, 1});
    for (const auto& p : ball.positions) {
        const double l = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
        ball.normals.push_back({float(p[0] / l), float(p[1] / l), float(p[2] / l)});
    }
    EncodeOptions encode = test::fast_options();
    encode.sample_spacing = 0;
    EncodeResult encoded = encode_meshes({ball}, encode);
    auto& points = encoded.contents[0].points;
    REQUIRE(points.size() > 15000);
    for (auto& q : points) q.position = points[0].position;
    const ReceivedStream stream = test::receive_every_packet(encoded);
    std::vector<Mesh> out;
    StreamDecodeReport report;
    std::string error;
    DecodeOptions options;
    options.grid_resolution = 24;
    REQUIRE_MESSAGE(decode_stream(stream, options, out, report, error), error);
    REQUIRE(out.size() == 1);
    for (const auto& t : out[0].triangles)
        for (uint32_t v : t) REQUIRE(v < out[0].positions.size());
}

namespace {

// A stream of `objects` objects of one ellipsoid each, filling its frame, and no point, with the
// given grid hint: a few hundred bytes that ask for a huge base per object.
ReceivedStream one_ellipsoid_objects(size_t objects, uint16_t grid_hint, float radius = 0.5f) {
    StreamInfo info;
    info.grid_hint = grid_hint;
    std::vector<ObjectContent> contents(objects);
    for (size_t i = 0; i < objects; ++i) {
        ObjectInfo o;
        o.frame = {{float(i), 0, 0}, 1};
        o.ellipsoid_count = 1;
        info.objects.push_back(o);
        Ellipsoid e;
        e.center = {float(i) + 0.5f, 0.5f, 0.5f};
        e.radii = {radius, radius, radius};
        contents[i].ellipsoids.push_back(quantize_ellipsoid(e, o.frame));
    }
    StreamPackets packets;
    REQUIRE(packetize_stream(info, contents, 1, packets) == Error::Ok);
    ReceivedStream stream;
    size_t where = 0;
    std::vector<std::vector<uint8_t>> all;
    for (auto* group : {&packets.stream_info, &packets.ellipsoids})
        for (const auto& p : *group) {
            REQUIRE(stream.add_packet(p, where++) == Error::Ok);
            all.push_back(p);
        }
    // Kept for the command-line tools (build/test-scratch/one_ellipsoid_objects/N.ellc).
    const auto bytes = write_container(all);
    std::ofstream(scratch_dir("one_ellipsoid_objects_" + std::to_string(objects)) / "stream.ellc", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return stream;
}

}  // namespace

TEST_CASE("a decoder's work follows what the stream carries: one-ellipsoid objects get small grids, however large the hint") {
    for (size_t objects : {size_t(1), size_t(10), size_t(2000)}) {
        CAPTURE(objects);
        const ReceivedStream stream = one_ellipsoid_objects(objects, 1000);
        std::vector<Mesh> out;
        StreamDecodeReport report;
        std::string error;
        REQUIRE_MESSAGE(decode_stream(stream, DecodeOptions{}, out, report, error), error);
        REQUIRE(out.size() == objects);
        size_t faces = 0;
        for (const auto& m : out) faces += m.triangles.size();
        // One object: at most 2^18 + 2048 nodes, a sphere about 64 cells across: some 10^4 faces
        // (at the hint of 1000 it would have been ~6 million). Many objects share 2^24 nodes, so the
        // faces of all stay within a quarter of the nodes.
        CHECK(faces <= objects * 60000);
        CHECK(faces <= ((size_t(1) << 24) + 2048 * objects) / 4);
        bool lowered = false;
        for (const auto& note : report.objects[0].notes) lowered |= note.find("lowered to") != std::string::npos;
        CHECK(lowered);
    }
}

TEST_CASE("an object whose grid cannot be built is named and the others are still decoded") {
    // The user asks for the finest grid: the object of radius 0.5 would exceed the grid node cap,
    // the small one fits.
    StreamInfo info;
    std::vector<ObjectContent> contents(2);
    for (int i = 0; i < 2; ++i) {
        ObjectInfo o;
        o.frame = {{float(2 * i), 0, 0}, 1};
        o.ellipsoid_count = 1;
        info.objects.push_back(o);
        Ellipsoid e;
        e.center = {float(2 * i) + 0.5f, 0.5f, 0.5f};
        e.radii = {i == 0 ? 0.5f : 0.05f, i == 0 ? 0.5f : 0.05f, i == 0 ? 0.5f : 0.05f};
        contents[size_t(i)].ellipsoids.push_back(quantize_ellipsoid(e, o.frame));
    }
    EncodeResult encoded;
    encoded.info = info;
    encoded.contents = contents;
    const ReceivedStream stream = test::receive_every_packet(encoded);
    DecodeOptions options;
    options.grid_resolution = 1024;
    std::vector<Mesh> out;
    std::vector<size_t> which;
    StreamDecodeReport report;
    std::string error;
    REQUIRE_MESSAGE(decode_stream(stream, options, out, report, error, &which), error);
    CHECK(report.objects_failed == 1);
    REQUIRE(which == std::vector<size_t>{1});
    CHECK(!out[0].triangles.empty());
    bool named = false;
    for (const auto& note : report.objects[0].notes) named |= note.find("not decoded") != std::string::npos;
    CHECK(named);
}

TEST_CASE("when every STREAM_INFO was rejected, the decoder says why instead of 'none arrived'") {
    StreamInfo info;
    ObjectInfo o;
    o.ellipsoid_count = 1;
    info.objects.push_back(o);
    std::vector<ObjectContent> contents(1);
    Ellipsoid e;
    e.center = {0.5f, 0.5f, 0.5f};
    e.radii = {0.3f, 0.3f, 0.3f};
    contents[0].ellipsoids.push_back(quantize_ellipsoid(e, o.frame));
    StreamPackets packets;
    REQUIRE(packetize_stream(info, contents, 1, packets) == Error::Ok);
    // The same stream info addressed to object 7 (valid CRC, wrong object id): rejected.
    PacketView view;
    REQUIRE(parse_packet(packets.stream_info[0], view) == Error::Ok);
    PacketHeader h = view.header;
    h.object_id = 7;
    ReceivedStream stream;
    CHECK(stream.add_packet(write_packet(h, view.payload), 0) == Error::MalformedPayload);
    CHECK(stream.add_packet(write_packet(h, view.payload), 1) == Error::MalformedPayload);
    REQUIRE(stream.add_packet(packets.ellipsoids[0], 2) == Error::Ok);  // held
    std::vector<Mesh> out;
    StreamDecodeReport report;
    std::string error;
    CHECK_FALSE(decode_stream(stream, DecodeOptions{}, out, report, error));
    CHECK_MESSAGE(error.find("2 STREAM_INFO packets were rejected; the first (at 0) as malformed payload: STREAM_INFO with "
                             "object id 7") != std::string::npos,
                  error);
    ReceivedStream nothing;
    CHECK_FALSE(decode_stream(nothing, DecodeOptions{}, out, report, error));
    CHECK(error.find("no STREAM_INFO packet arrived") != std::string::npos);
}

TEST_CASE("a collapse that OpenMesh allows but that leaves a face with a repeated vertex is refused (fuzz_decode)") {
    // 724 bytes found by fuzz_decode: the scene vector cut down to 6 ellipsoids and 15 points. At grids
    // 4 to 10 a marching-cubes collapse passed is_collapse_ok and left faces such as (26 26 4); the next
    // point inserted into one read an edge array at -1 (UBSan) and the release build aborted.
    const std::string hex =
        "89454c430d0a1a0a01000000e14c43530101010057ca110e00000000ffff780020002c00c8000e0a0c08000055abd3cf"
        "02000000020040003333733f07000000000080bf000080bf000080bf00000040060000001e0000000003000000000000"
        "000000000000803f0000803f000000bf000000bf000000bf0000803f0400000014000000000100000000000000000000"
        "0000803f0000803f69493a2ce14c43530101020057ca110e01000000000068000000000006000000474c5868935799dc"
        "89b3f1bdfe9015c66549f81254f54d3010c2b02298769df3a63c2b97ff6bcb24973263c0f3fe46170d4aced9f3f28670"
        "16e5c05066336f000000000000000c88093e224c0f953257cb2e6859750a7c608cc94191df43958630b512e1e14c4353"
        "0101030057ca110e030000000000aa00000000000f0000008d2600e88baff91f004645f1957826dc938dc9e14cc2139e"
        "475575843be5d0befca70b2d6c3f0000803f0000803f0000803f014c000100000000000104426f647900000040000000"
        "000000000000000000000000000000803f000000000000000000000000000000000000803f0000000000000000000000"
        "3f000000000000803f7a180ee9e14c43530101100157ca110e07000000ffff83000500020002000000018dc725100100"
        "0100000b576865656c2e46726f6e74cdcccc3e9a9999be000000000000000000000000000000000000803f0000003f00"
        "00803f0000803f013a00030001000100000a576865656c2e4261636bcdccbe9999cc9abe000000000000000000000000"
        "000000000000803f0000003f0000803f0000803fe987dfb4e14c43530101100157ca110e08000000ffff640005000200"
        "0300000001380004000000ffff00084c616d706520c3bc000000000000c03f0000000000000000000000000000000000"
        "0080bb0000803f0000803f0000803f020d00000004426f6479010000000000020e00010005576865656c010001000100"
        "4630cf2a";
    std::vector<uint8_t> bytes;
    for (size_t i = 0; i + 1 < hex.size(); i += 2) bytes.push_back(uint8_t(std::stoi(hex.substr(i, 2), nullptr, 16)));
    const ContainerContents contents = read_container(bytes);
    REQUIRE(contents.header_error == Error::Ok);
    ReceivedStream stream;
    for (const auto& p : contents.packets) stream.add_parsed(p.view, p.offset);
    for (int grid : {4, 5, 6, 8, 10}) {
        CAPTURE(grid);
        DecodeOptions options;
        options.grid_resolution = grid;
        std::vector<Mesh> meshes;
        StreamDecodeReport report;
        std::string error;
        decode_stream(stream, options, meshes, report, error);
        for (const Mesh& m : meshes)
            for (const auto& t : m.triangles) {
                CHECK((t[0] != t[1] && t[1] != t[2] && t[0] != t[2]));
                CHECK((t[0] < m.positions.size() && t[1] < m.positions.size() && t[2] < m.positions.size()));
            }
    }
}

TEST_CASE("the decoder's face index is sized by the mesh it holds, not by the frame or the declared point count") {
    // fuzz_decode: one tiny ellipsoid in a large frame with a million points declared made a 4M-cell
    // index (98 MB for a 203-byte stream), and points far from a tiny base walked its empty cells.
    DecoderTriMesh base;
    const double s = 1e-3;  // a tetrahedron a thousandth of the frame across
    auto a = base.add_vertex({0.5, 0.5, 0.5}), b = base.add_vertex({0.5 + s, 0.5, 0.5}),
         c = base.add_vertex({0.5, 0.5 + s, 0.5}), d = base.add_vertex({0.5, 0.5, 0.5 + s});
    base.add_face(a, c, b);
    base.add_face(a, b, d);
    base.add_face(a, d, c);
    base.add_face(b, c, d);
    Reconstruction r;
    start_reconstruction(r, std::move(base), Frame{{0, 0, 0}, 1}, 1.0 / 1024, 1000000, ReconstructionOptions{});
    CHECK(r.faces.cell_count() <= 4096);
    // Points spread over the whole frame: the index is laid out again, finer, as the mesh grows, and
    // never has more than 16 cells per face it had when laid out (at least 4,096).
    uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float((state >> 40) & 0xFFFFFF) / float(1 << 24);
    };
    const double first_cell = r.faces.cell_size();
    for (uint32_t i = 0; i < 20000; ++i) {
        OpenMesh::VertexHandle v;
        insert_point(r, i, {next(), next(), next()}, v);
        REQUIRE(r.faces.cell_count() <= std::max<size_t>(4096, 16 * r.index_built_for));
    }
    CHECK(r.mesh.n_faces() > 4 * 4096);
    CHECK(r.faces.cell_size() < first_cell);  // refined at least once
    CHECK(r.faces.cell_count() > 4096);
}
