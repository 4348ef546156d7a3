// Format 1.11, vertices carried by the exact layer (spec 27): what a user of `--point-share` relies
// on. The exact object is the same whatever share of its vertices travels as points; the stream gets
// smaller as the share goes down; loss and repair still bring it whole; the points still make a
// picture before it; hostile coded meshes end in bounded time; objects whose per-point data would be
// lost keep every vertex a point.
#include <doctest/doctest.h>

#include "corners.h"
#include "support.h"

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"

#include <algorithm>
#include <chrono>
#include <random>
#include <sstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

// What a receiver holding `stream` shows exact of object `i`: its triangles as quantized corners
// (points and carried vertices alike), sorted.
std::vector<CornerTriangle> exact_corners(const ReceivedStream& stream, size_t i, size_t* carried_out = nullptr) {
    std::vector<Triangle> triangles;
    std::vector<QuantizedPoint> carried;
    std::string why;
    REQUIRE_MESSAGE(exact_layer(stream, i, triangles, carried, why) == Error::Ok, why);
    const auto& points = stream.objects()[i].points;
    const uint32_t n = stream.objects()[i].info->point_count;
    auto vertex = [&](uint32_t v) { return v < n ? points.at(v) : carried.at(v - n); };
    std::vector<CornerTriangle> out;
    for (const Triangle& t : triangles) out.push_back(canonical({corner_of(vertex(t[0])), corner_of(vertex(t[1])), corner_of(vertex(t[2]))}));
    std::sort(out.begin(), out.end());
    if (carried_out) *carried_out = carried.size();
    return out;
}

EncodeOptions quick(double share) {
    EncodeOptions o;
    o.max_ellipsoids = 30;
    o.coverage = 0.7;
    o.point_share = share;
    return o;
}

struct Encoded {
    EncodedAsset asset;
    size_t content_bytes = 0;  // every packet but repair packets
};

Encoded encode(const Asset& asset, double share, double repair = 1.0) {
    Encoded e;
    EncodeOptions o = quick(share);
    o.repair_ratio = repair;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, o, 5, true, e.asset, error), error);
    for (const auto& p : e.asset.packets) {
        const uint8_t type = p[6];
        if (type != uint8_t(PacketType::PointsRepair) && !is_exact_layer_repair_type(type)) e.content_bytes += p.size();
    }
    return e;
}

ReceivedStream receive_all(const EncodedAsset& encoded) {
    ReceivedStream stream;
    uint64_t ordinal = 0;
    for (const auto& p : encoded.packets) stream.add_packet(p, ordinal++);
    return stream;
}

// The bundled trefoil (no ../shared needed), and the shared scans when they are there; the Duck has
// normals, left to the surface (format 1.8) where it gives them back: those vertices may be carried.
std::vector<fs::path> carrying_models() {
    std::vector<fs::path> out = {source_dir() / "samples" / "trefoil.obj"};
    for (const char* f : {"meshes/spot.obj", "meshes/fandisk.obj", "gltf/Duck/Duck.gltf"})
        if (have_sample(f)) out.push_back(shared_samples() / f);
    return out;
}

}  // namespace

TEST_CASE("carried vertices: the exact object is the same at every point share, and the stream is smaller the "
          "lower the share") {
    for (const fs::path& file : carrying_models()) {
        CAPTURE(file.string());
        const Asset asset = load_asset(file.string());
        REQUIRE(!asset.objects.empty());
        const Encoded all = encode(asset, 1.0);
        const ReceivedStream whole = receive_all(all.asset);
        const auto expected = exact_corners(whole, 0);
        size_t previous_bytes = all.content_bytes;
        for (const double share : {0.5, 0.25, 0.0}) {
            CAPTURE(share);
            const Encoded e = encode(asset, share);
            const ReceivedStream stream = receive_all(e.asset);
            CHECK(stream.rejections().empty());
            size_t carried = 0;
            CHECK(exact_corners(stream, 0, &carried) == expected);
            const uint32_t points = stream.objects()[0].info->point_count;
            CHECK(carried > 0);
            CHECK(points + carried >= whole.objects()[0].info->point_count);  // samples stay points
            // The codec's exact mesh: every carried vertex in it, with its position.
            Mesh mesh;
            std::string why;
            bool unusable = false;
            REQUIRE_MESSAGE(exact_mesh(stream, 0, mesh, why, unusable), why);
            CHECK(mesh.triangles.size() == expected.size());
            if (stream.objects()[0].info->surface_normals) {
                // Every vertex shown with a unit normal: the carried ones with their surface normal.
                for (const auto& n : mesh.normals)
                    CHECK(std::abs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0f) < 1e-3f);
            }
            MESSAGE(file.filename().string() << " at point share " << share << ": " << points << " points, " << carried
                                             << " carried, " << e.content_bytes << " bytes without repair (share 1: "
                                             << all.content_bytes << ")");
            if (share == 0.0) CHECK(e.content_bytes < all.content_bytes);
            previous_bytes = e.content_bytes;
        }
        (void)previous_bytes;
    }
}

TEST_CASE("carried vertices under 50% loss: repair brings the coded mesh and the points, and the object comes "
          "back exact, and before that the points make the picture") {
    const Asset asset = load_asset((source_dir() / "samples" / "trefoil.obj").string());
    const Encoded e = encode(asset, 0.25);
    const auto expected = exact_corners(receive_all(e.asset), 0);
    std::mt19937 rng(11);
    ReceivedStream stream;
    uint64_t ordinal = 0;
    int cycles = 0;
    auto exact = [&] {
        std::vector<Triangle> t;
        std::vector<QuantizedPoint> c;
        std::string why;
        return !stream.objects().empty() && exact_layer(stream, 0, t, c, why) == Error::Ok;
    };
    bool pictured = false;
    while (!exact() && cycles < 12) {
        ++cycles;
        for (const auto& p : e.asset.packets)
            if (rng() % 2) stream.add_packet(p, ordinal++);
        if (!pictured && !exact() && !stream.objects().empty() && !stream.objects()[0].points.empty()) {
            // Not exact yet: the reconstruction from the points received, never the carried vertices.
            std::vector<Mesh> meshes;
            StreamDecodeReport report;
            std::string error;
            DecodeOptions options;
            REQUIRE_MESSAGE(decode_stream(stream, options, meshes, report, error), error);
            REQUIRE(meshes.size() == 1);
            CHECK(!report.objects[0].exact);
            CHECK(!meshes[0].triangles.empty());
            pictured = true;
        }
    }
    REQUIRE(exact());
    CHECK(exact_corners(stream, 0) == expected);
    MESSAGE("trefoil at point share 0.25: exact after " << cycles << " cycles at 50% loss");
}

TEST_CASE("hostile coded meshes: random bytes with any carried count end in bounded time, as a valid mesh or "
          "unusable") {
    std::vector<QuantizedPoint> positions(120);
    for (uint32_t i = 0; i < 120; ++i) {
        positions[i].position = {(i * 7919) % 16000, (i * 104729) % 16001, (i * 31) % 16007};
        positions[i].texcoord = {i * 30, 4095 - i * 30};
    }
    StreamInfo info;
    info.position_bits = 14;
    ObjectInfo object;
    object.attributes = kAttrTexcoord | kAttrColor;
    std::mt19937 rng(3);
    size_t unusable = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int trial = 0; trial < 400; ++trial) {
        std::vector<uint8_t> coded(1 + rng() % 300);
        for (auto& b : coded) b = uint8_t(trial % 3 == 0 ? 0 : rng());  // zeros: every bit a cheap 0
        const uint32_t carried_count = rng() % 500;
        const uint32_t count = 1 + rng() % uint32_t(8 * (positions.size() + carried_count));
        std::vector<Triangle> out;
        std::vector<QuantizedPoint> carried;
        std::string why;
        if (decode_exact_mesh(coded, count, carried_count, positions, info, object, out, carried, why) != Error::Ok) {
            ++unusable;
            CHECK(!why.empty());
            continue;
        }
        REQUIRE(out.size() == count);
        CHECK(carried.size() == carried_count);
        const size_t total = positions.size() + carried_count;
        for (const Triangle& t : out) {
            CHECK((t[0] < total && t[1] < total && t[2] < total));
            CHECK((t[0] != t[1] && t[1] != t[2] && t[0] != t[2]));
        }
        for (const QuantizedPoint& q : carried) {
            for (uint32_t c : q.position) CHECK(c < (1u << 14));
            for (uint32_t c : q.texcoord) CHECK(c < (1u << info.texcoord_bits));
        }
    }
    MESSAGE(unusable << " of 400 random coded meshes unusable, in "
                     << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s");
    // A real coded mesh with bits flipped: decodes to some valid mesh or is unusable, never more.
    {
        std::vector<QuantizedPoint> vertices;
        const uint32_t side = 40;
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t x = 0; x < side; ++x) {
                QuantizedPoint q;
                q.position = {x * 300 + (y % 2) * 150, y * 260, (x * 7 + y * 13) % 50};
                q.texcoord = {x * 100, y * 100};
                q.color = {x, y, 7, 0};
                vertices.push_back(q);
            }
        std::vector<Triangle> grid;
        for (uint32_t y = 0; y + 1 < side; ++y)
            for (uint32_t x = 0; x + 1 < side; ++x) {
                const uint32_t a = y * side + x;
                grid.push_back({a, a + 1, a + side + 1});
                grid.push_back({a, a + side + 1, a + side});
            }
        const size_t n = 400;  // the first 400 points, the other 1,200 carried
        std::vector<uint8_t> coded;
        std::vector<Triangle> sent;
        std::vector<uint32_t> order;
        REQUIRE(encode_exact_mesh(vertices, n, grid, info, object, coded, sent, order) == Error::Ok);
        const std::vector<QuantizedPoint> points(vertices.begin(), vertices.begin() + long(n));
        std::vector<Triangle> back;
        std::vector<QuantizedPoint> carried;
        std::string why;
        REQUIRE_MESSAGE(decode_exact_mesh(coded, uint32_t(grid.size()), uint32_t(vertices.size() - n), points, info, object,
                                          back, carried, why) == Error::Ok,
                        why);
        CHECK(back == sent);
        for (size_t j = 0; j < carried.size(); ++j) CHECK(corner_of(carried[j]) == corner_of(vertices[order[j]]));
        size_t flipped_usable = 0;
        for (int trial = 0; trial < 200; ++trial) {
            std::vector<uint8_t> damaged = coded;
            damaged[rng() % damaged.size()] ^= uint8_t(1u << (rng() % 8));
            if (decode_exact_mesh(damaged, uint32_t(grid.size()), uint32_t(vertices.size() - n), points, info, object, back,
                                  carried, why) != Error::Ok)
                continue;
            ++flipped_usable;
            for (const Triangle& t : back) CHECK((t[0] < vertices.size() && t[1] < vertices.size() && t[2] < vertices.size()));
        }
        MESSAGE(coded.size() << " bytes for a 40 x 40 grid carrying 1,200 of its vertices; " << flipped_usable
                             << " of 200 one-bit flips still decode (to another mesh: the CRC-32C of the packets is what "
                                "catches damage)");
    }
    // A carried count the coded mesh cannot reach, over many triangles: ends, unusable.
    std::vector<Triangle> out;
    std::vector<QuantizedPoint> carried;
    std::string why;
    CHECK(decode_exact_mesh(std::vector<uint8_t>(64, 0), 8000, 1000, positions, info, object, out, carried, why) ==
          Error::MalformedPayload);
    CHECK(decode_exact_mesh(std::vector<uint8_t>{1}, 1, kMaxCarriedVertices + 1, positions, info, object, out, carried,
                            why) == Error::MalformedPayload);
}

TEST_CASE("an exact layer of the other kind, a contradicting carried count or a bad EXACT_MESH payload is "
          "rejected and the object still comes back exact") {
    const Asset asset = load_asset((source_dir() / "samples" / "trefoil.obj").string());
    const Encoded e = encode(asset, 0.5, 0.0);
    std::vector<std::vector<uint8_t>> layer;
    for (const auto& p : e.asset.packets)
        if (p[6] == uint8_t(PacketType::ExactMesh)) layer.push_back(p);
    REQUIRE(!layer.empty());
    ReceivedStream stream = receive_all(e.asset);
    const auto expected = exact_corners(stream, 0);
    // A CONNECTIVITY packet for the object: the other kind.
    ConnectivityPiece piece;
    PacketView view;
    REQUIRE(parse_packet(layer[0], view) == Error::Ok);
    REQUIRE(decode_connectivity_payload(view.payload, piece, true) == Error::Ok);
    PacketHeader h = view.header;
    h.type = uint8_t(PacketType::Connectivity);
    h.version_minor = kConnectivityMinor;
    h.sequence = 9000;
    CHECK(stream.add_packet(write_packet(h, encode_connectivity_payload(piece, false)), 9000) == Error::StreamMismatch);
    // Another carried count.
    ConnectivityPiece other = piece;
    other.carried_count += 1;
    h = view.header;
    h.sequence = 9001;
    CHECK(stream.add_packet(write_packet(h, encode_connectivity_payload(other, true)), 9001) == Error::StreamMismatch);
    // A carried count of 0, and a triangle count past 8 a vertex.
    other = piece;
    other.carried_count = 0;
    CHECK(stream.add_packet(write_packet(h, encode_connectivity_payload(other, true)), 9002) == Error::MalformedPayload);
    other = piece;
    other.triangle_count = 8 * (stream.objects()[0].info->point_count + piece.carried_count) + 1;
    CHECK(stream.add_packet(write_packet(h, encode_connectivity_payload(other, true)), 9003) == Error::MalformedPayload);
    CHECK(exact_corners(stream, 0) == expected);
    // A receiver with a small element limit refuses the carried vertices and keeps no description.
    ReceivedStream::Limits limits;
    limits.max_elements = stream.objects()[0].info->point_count + stream.objects()[0].info->ellipsoid_count + 1;
    ReceivedStream small(limits);
    uint64_t ordinal = 0;
    size_t refused = 0;
    for (const auto& p : e.asset.packets)
        if (small.add_packet(p, ordinal++) == Error::MalformedPayload && p[6] == uint8_t(PacketType::ExactMesh)) ++refused;
    CHECK(refused == layer.size());
    CHECK(!small.objects()[0].connectivity);
}

TEST_CASE("objects whose vertices carry per-point data keep every vertex a point") {
    if (!have_sample("gltf/Fox/Fox.gltf")) {
        MESSAGE("skipped: ../shared/samples/gltf/Fox is absent");
        return;
    }
    // The Fox: skinned (JOINT_WEIGHTS name points by index), with normals.
    const Asset fox = load_asset((shared_samples() / "gltf/Fox/Fox.gltf").string());
    const Encoded e = encode(fox, 0.0);
    for (const auto& r : e.asset.encoded.reports) CHECK(r.carried == 0);
    for (const auto& p : e.asset.packets) CHECK(p[6] != uint8_t(PacketType::ExactMesh));
}

// `ellicast ARGS` with every argument quoted for the shell.
std::string ellicast_command(const std::vector<std::string>& args) {
    std::ostringstream command;
    command << "'" << ellicast_exe().string() << "'";
    for (const std::string& a : args) command << " '" << a << "'";
    return command.str();
}

TEST_CASE("ellicast encode --point-share: a stream that validates and decodes exact, and an absurd share refused "
          "with a message") {
    const fs::path dir = binary_dir() / "test-scratch-exact-mesh";
    fs::create_directories(dir);
    const std::string input = (source_dir() / "samples" / "trefoil.obj").string();
    const std::string stream = (dir / "trefoil.ellc").string();
    int status = 0;
    std::string out = run_command(ellicast_command({"encode", "-q", "--point-share", "0.3", input, "-o", stream}), status);
    REQUIRE_MESSAGE(status == 0, out);
    CHECK(out.find("carried by the exact layer (format 1.11)") != std::string::npos);
    out = run_command(ellicast_command({"validate", stream}), status);
    CHECK_MESSAGE(status == 0, out);
    out = run_command(ellicast_command({"decode", "-q", stream, "-o", (dir / "trefoil.glb").string()}), status);
    CHECK_MESSAGE(status == 0, out);
    CHECK_MESSAGE(out.find("exact") != std::string::npos, out);
    const std::string bad_output = (dir / "bad.ellc").string();
    for (const std::string bad : {"1.5", "-0.1", "nan"}) {
        out = run_command(ellicast_command({"encode", "-q", "--point-share", bad, input, "-o", bad_output}), status);
        CHECK(status != 0);
        CHECK_MESSAGE((out.find("point-share") != std::string::npos || out.find("point share") != std::string::npos), out);
        CHECK(!fs::exists(bad_output));
    }
}
