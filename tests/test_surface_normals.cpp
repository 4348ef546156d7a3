// Surface normals (format 1.8, spec 24): an object with normals and an exact layer sends only the
// normals that differ from its surface's. On a real asset (the Duck): fewer bytes; the exact model's
// normals within the tolerance of those sent in full; a receiver that lost the NORMALS packets still
// shows unit normals everywhere, exact or not; bad options are refused by name.
#include "support.h"

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"

#include <cmath>
#include <map>

using namespace ellicast;
using namespace ellicast::test;

namespace {

EncodeOptions quick(double tolerance) {
    EncodeOptions o;
    o.max_ellipsoids = 30;
    o.coverage = 0.7;
    o.normal_tolerance = tolerance;
    return o;
}

ReceivedStream receive(const std::vector<std::vector<uint8_t>>& packets, bool with_normals = true) {
    ReceivedStream rx;
    for (size_t i = 0; i < packets.size(); ++i) {
        PacketView view;
        REQUIRE(parse_packet(packets[i], view) == Error::Ok);
        if (!with_normals && view.header.type == uint8_t(PacketType::Normals)) continue;
        REQUIRE(rx.add_packet(packets[i], i) == Error::Ok);
    }
    return rx;
}

double angle_degrees(const std::array<float, 3>& a, const std::array<float, 3>& b) {
    const double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
    return std::acos(std::clamp(d, -1.0, 1.0)) * 180.0 / M_PI;
}

bool unit(const std::array<float, 3>& n) {
    return std::abs(std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]) - 1.0) < 1e-4;
}

// A vertex of an exact mesh by its position and texture coordinate (its identity across streams
// whose point order differs).
using Key = std::array<float, 5>;
Key key_of(const Mesh& m, size_t v) {
    return {m.positions[v][0], m.positions[v][1], m.positions[v][2], m.texcoords.empty() ? 0.f : m.texcoords[v][0],
            m.texcoords.empty() ? 0.f : m.texcoords[v][1]};
}

Mesh exact_of(const ReceivedStream& rx) {
    Mesh m;
    std::string why;
    bool unusable = false;
    REQUIRE_MESSAGE(exact_mesh(rx, 0, m, why, unusable), why);
    return m;
}

}  // namespace

TEST_CASE("the Duck sends its normals as surface normals: fewer bytes, and the exact model's normals within the tolerance") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const Asset asset = load_asset((shared_samples() / "gltf/Duck/Duck.gltf").string());
    EncodedAsset full, surface;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, quick(0), 1, false, full, error), error);
    REQUIRE_MESSAGE(encode_asset(asset, quick(2), 1, false, surface, error), error);
    const ObjectInfo& object = surface.encoded.info.objects.at(0);
    REQUIRE(object.surface_normals);
    CHECK_FALSE(object.has(kAttrNormal));
    CHECK(object.has_normals());
    CHECK_FALSE(full.encoded.info.objects.at(0).surface_normals);
    CHECK(full.normal_packets == 0);
    REQUIRE(surface.normal_packets > 0);
    const ObjectReport& report = surface.encoded.reports.at(0);
    CHECK(report.surface_normals);
    CHECK(report.normals_sent > 0);
    CHECK(report.normals_sent < report.points);
    // The points and their normals: 8.4 against 9.6 bytes a point when measured (Duck, 14 bits).
    const double full_bytes = double(full.point_bytes + full.map_bytes);
    const double surface_bytes = double(surface.point_bytes + surface.map_bytes + surface.normal_bytes);
    MESSAGE("Duck: " << surface_bytes / report.points << " bytes a point with surface normals, " << full_bytes / report.points
                     << " with every normal in the records; " << report.normals_sent << " of " << report.points << " sent");
    CHECK(surface_bytes < 0.95 * full_bytes);

    const ReceivedStream a = receive(full.packets), b = receive(surface.packets);
    CHECK(b.objects()[0].normals_complete());
    const Mesh ma = exact_of(a), mb = exact_of(b);
    REQUIRE(ma.positions.size() == mb.positions.size());
    REQUIRE(mb.normals.size() == mb.positions.size());
    std::map<Key, std::array<float, 3>> sent;
    // Vertices are matched by position and texture coordinate; a hard edge whose sides share their
    // texture coordinates makes two vertices with one key, which are left out.
    std::map<Key, int> seen;
    for (size_t v = 0; v < ma.positions.size(); ++v) ++seen[key_of(ma, v)];
    for (size_t v = 0; v < ma.positions.size(); ++v)
        if (seen[key_of(ma, v)] == 1) sent[key_of(ma, v)] = ma.normals[v];
    double worst = 0;
    size_t matched = 0;
    for (size_t v = 0; v < mb.positions.size(); ++v) {
        CHECK(unit(mb.normals[v]));
        auto it = sent.find(key_of(mb, v));
        if (it == sent.end()) continue;
        ++matched;
        worst = std::max(worst, angle_degrees(it->second, mb.normals[v]));
    }
    MESSAGE("exact Duck: largest angle to the normal sent in full " << worst << " degrees over " << matched << " vertices");
    CHECK(matched > mb.positions.size() * 8 / 10);
    // 2 degrees of tolerance, measured against the quantized normal; rounding on top.
    CHECK(worst <= 2.05);
}

TEST_CASE("without its NORMALS packets the Duck still shows a unit normal at every vertex, exact or rebuilt") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const Asset asset = load_asset((shared_samples() / "gltf/Duck/Duck.gltf").string());
    EncodedAsset surface;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, quick(2), 1, false, surface, error), error);
    const ReceivedStream rx = receive(surface.packets, false);
    CHECK_FALSE(rx.objects()[0].normals_complete());
    CHECK(rx.objects()[0].normal_entries.empty());
    // Exact: every normal is the surface's (those that would have been sent too).
    const Mesh exact = exact_of(rx);
    REQUIRE(exact.normals.size() == exact.positions.size());
    for (const auto& n : exact.normals) CHECK(unit(n));
    // Rebuilt from ellipsoids and points (what a receiver shows before the exact layer is complete).
    std::vector<Mesh> meshes;
    StreamDecodeReport report;
    REQUIRE(decode_stream(rx, DecodeOptions{}, meshes, report, error));
    REQUIRE(meshes.size() == 1);
    REQUIRE(meshes[0].normals.size() == meshes[0].positions.size());
    size_t bad = 0;
    for (const auto& n : meshes[0].normals) bad += !unit(n);
    CHECK(bad == 0);
}

TEST_CASE("the normal tolerance is checked: out of range or not a number is refused by name") {
    EncodeOptions o;
    o.normal_tolerance = 91;
    CHECK(check_encode_options(o).find("normal tolerance") != std::string::npos);
    o.normal_tolerance = -1;
    CHECK(check_encode_options(o).find("normal tolerance") != std::string::npos);
    o.normal_tolerance = std::nan("");
    CHECK(check_encode_options(o).find("normal tolerance") != std::string::npos);
    o.normal_tolerance = 0;
    CHECK(check_encode_options(o).empty());
}

TEST_CASE("an object without an exact layer keeps its normals in its records") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const Asset asset = load_asset((shared_samples() / "gltf/Duck/Duck.gltf").string());
    EncodeOptions o = quick(2);
    o.exact_layer = false;
    EncodedAsset out;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, o, 1, false, out, error), error);
    CHECK_FALSE(out.encoded.info.objects.at(0).surface_normals);
    CHECK(out.encoded.info.objects.at(0).has(kAttrNormal));
    CHECK(out.normal_packets == 0);
}
