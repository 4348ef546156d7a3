// Further texture-coordinate sets (format 1.14, spec 30): an asset whose occlusion map or lightmap is
// on TEXCOORD_1 comes back with that set and the texture on it, through a stream, through `ellicast
// convert` and in every output storage; a receiver that lost the set's packets shows the material
// without that texture and says so; a reconstruction gives each vertex its own point's set; points
// that differ only in a further set stay apart. The packet-level rules are pinned by the texcoords*
// conformance vectors; these cases check what a user relies on.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <cmath>
#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

fs::path multiuv_box() { return source_dir() / "samples" / "multiuv" / "MultiUVBox.gltf"; }

// A packet of the exact layer (format 1.3 or 1.11) or of its repair.
bool exact_layer_packet(const std::vector<uint8_t>& p) {
    return is_packet_type(p, PacketType::Connectivity) || is_packet_type(p, PacketType::ConnectivityRepair) ||
           is_packet_type(p, PacketType::ExactMesh) || is_packet_type(p, PacketType::ExactMeshRepair);
}

size_t warnings_with(const std::vector<std::string>& warnings, const std::string& text) {
    return size_t(std::count_if(warnings.begin(), warnings.end(),
                                [&](const std::string& w) { return w.find(text) != std::string::npos; }));
}

EncodedAsset encoded(const Asset& in, EncodeOptions options = {}) {
    options.max_ellipsoids = 40;
    options.coverage = 0.8;
    EncodedAsset out;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, options, 1, !in.scene.nodes.empty(), out, error), error);
    return out;
}

// Every vertex of `out` that is at a vertex of `in` (positions within `eps`) has the TEXCOORD_0 and
// TEXCOORD_1 of one vertex of `in` there (a pair, not a mix of two vertices' sets), within `tol`.
void check_pairs_of_sets(const Mesh& in, const Mesh& out, double eps, double tol, size_t& matched) {
    REQUIRE(in.texcoord_sets.size() == 1);
    REQUIRE(out.texcoord_sets.size() == 1);
    REQUIRE(out.texcoord_sets[0].size() == out.positions.size());
    matched = 0;
    for (size_t v = 0; v < out.positions.size(); ++v) {
        bool at_vertex = false, pair = false;
        for (size_t i = 0; i < in.positions.size(); ++i) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d = std::max(d, double(std::abs(in.positions[i][k] - out.positions[v][k])));
            if (d > eps) continue;
            at_vertex = true;
            bool same = true;
            for (int k = 0; k < 2; ++k)
                same = same && std::abs(in.texcoords[i][k] - out.texcoords[v][k]) <= tol &&
                       std::abs(in.texcoord_sets[0][i][k] - out.texcoord_sets[0][v][k]) <= tol;
            pair = pair || same;
        }
        if (!at_vertex) continue;
        ++matched;
        CHECK_MESSAGE(pair, "vertex " << v << " has TEXCOORD_0 (" << out.texcoords[v][0] << ", " << out.texcoords[v][1]
                                      << ") and TEXCOORD_1 (" << out.texcoord_sets[0][v][0] << ", "
                                      << out.texcoord_sets[0][v][1] << "), a pair no input vertex there has");
    }
}

}  // namespace

TEST_CASE("a lightmapped box comes back with TEXCOORD_1 and its occlusion texture on it, vertex for vertex") {
    const Asset in = load_asset(multiuv_box().string());
    REQUIRE(in.objects.size() == 1);
    REQUIRE(in.objects[0].texcoord_sets.size() == 1);
    CHECK(in.scene.materials[0].occlusion_texture.texcoord == 1);
    CHECK(in.scene.materials[0].occlusion_texture.texture != kNone);
    CHECK(warnings_with(in.warnings, "TEXCOORD") == 0);

    const EncodedAsset e = encoded(in);
    CHECK(e.texcoord_packets == 1);
    CHECK(e.encoded.contents[0].carried.empty());  // every vertex a point (spec 30.3)
    const Asset out = received_without(e.packets, [](size_t) { return false; }, 24);
    check_same_scene(in, out);
    CHECK(out.scene.materials[0].occlusion_texture.texcoord == 1);
    REQUIRE(out.objects.size() == 1);
    // The exact object: every vertex its own pair of sets, within the 12-bit step of each range.
    size_t matched = 0;
    check_pairs_of_sets(in.objects[0], out.objects[0], 1e-4, 6.0 / 4095, matched);
    CHECK(matched == out.objects[0].positions.size());
    CHECK(out.objects[0].positions.size() == 24);
    CHECK(warnings_with(out.warnings, "TEXCOORD") == 0);
}

TEST_CASE("ellicast convert keeps TEXCOORD_1 plain, quantized and Draco-compressed, and the files validate") {
    const Asset in = load_asset(multiuv_box().string());
    for (const std::string storage : {"", "--quantize", "--draco"}) {
        CAPTURE(storage);
        const fs::path out = scratch_dir("texcoord_sets_cli") / ("box" + storage + ".glb");
        int status = 0;
        const std::string log = run_command(shell_quoted(ellicast_exe().string()) + " convert " + storage + " " +
                                                shell_quoted(multiuv_box().string()) + " " + shell_quoted(out.string()) + " 2>&1",
                                            status);
        REQUIRE_MESSAGE(status == 0, log);
        CHECK_MESSAGE(log.find("TEXCOORD") == std::string::npos, log);
        CHECK_MESSAGE(log.find("1 further texture coordinates") != std::string::npos, log);
        check_gltf_clean(out);
        const nlohmann::json doc = gltf_document(out);
        const nlohmann::json& prim = doc["meshes"][0]["primitives"][0];
        CHECK(prim["attributes"].contains("TEXCOORD_1"));
        CHECK(doc["materials"][prim["material"].get<size_t>()]["occlusionTexture"]["texCoord"] == 1);
        if (storage == "--draco")
            CHECK(prim["extensions"]["KHR_draco_mesh_compression"]["attributes"].contains("TEXCOORD_1"));
        // And back: the output read as an input has the same pairs of sets (quantized positions are in
        // the quantization's frame: there, the pairs are compared whatever the position).
        const Asset back = load_asset(out.string());
        REQUIRE(back.objects.size() == 1);
        size_t matched = 0;
        const double eps = storage == "--quantize" ? INFINITY : 2e-4;
        check_pairs_of_sets(in.objects[0], back.objects[0], eps, 6.0 / 4095 + 1e-4, matched);
        CHECK(matched == back.objects[0].positions.size());
    }
}

TEST_CASE("a receiver that lost every TEXCOORDS packet shows the material without the texture on TEXCOORD_1 and says so") {
    const Asset in = load_asset(multiuv_box().string());
    const EncodedAsset e = encoded(in);
    ReceivedStream held;
    const Asset out = received_without(
        e.packets, [&](size_t i) { return is_packet_type(e.packets[i], PacketType::Texcoords); }, 24, &held);
    REQUIRE(out.objects.size() == 1);
    CHECK(out.objects[0].texcoord_sets.empty());
    CHECK(out.objects[0].has_texcoords());
    CHECK(out.scene.materials[0].occlusion_texture.texture == kNone);
    CHECK(out.scene.materials[0].base_color_texture.texture != kNone);  // the TEXCOORD_0 texture stays
    CHECK(warnings_with(out.warnings, "occlusionTexture uses TEXCOORD_1") == 1);
    CHECK(held.objects()[0].texcoords_complete());  // nothing announced the set: nothing to wait for

    // Written, the file is valid glTF without the set or a reference to it.
    std::vector<std::string> warnings;
    std::string error;
    const fs::path file = scratch_dir("texcoord_sets_lost") / "out.gltf";
    REQUIRE_MESSAGE(write_asset(file.string(), out, {}, warnings, error), error);
    check_gltf_clean(file);
    const nlohmann::json doc = gltf_document(file);
    CHECK_FALSE(doc["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_1"));
    CHECK_FALSE(doc["materials"][0].contains("occlusionTexture"));

}

TEST_CASE("a reconstruction gives each vertex the further set of the point it stands for") {
    // The exact layer lost: the box rebuilt from its ellipsoids and points. Every vertex at an original
    // vertex keeps that vertex's pair of sets (a seam's vertex takes one point's sets, not a mix).
    const Asset in = load_asset(multiuv_box().string());
    const EncodedAsset e = encoded(in);
    const Asset out = received_without(
        e.packets,
        [&](size_t i) { return exact_layer_packet(e.packets[i]); },
        24);
    REQUIRE(out.objects.size() == 1);
    const Mesh& m = out.objects[0];
    REQUIRE(m.texcoord_sets.size() == 1);
    REQUIRE(m.texcoord_sets[0].size() == m.positions.size());
    for (const auto& uv : m.texcoord_sets[0]) CHECK((std::isfinite(uv[0]) && std::isfinite(uv[1])));
    size_t matched = 0;
    check_pairs_of_sets(in.objects[0], m, 1e-4, 6.0 / 4095, matched);
    CHECK(matched >= 8);  // the box's corners, at least
    CHECK(out.scene.materials[0].occlusion_texture.texcoord == 1);
}

TEST_CASE("points that differ only in TEXCOORD_1 stay apart, and a lost TEXCOORDS packet is filled from the nearest point") {
    // A strip of quads whose middle vertices are split by a lightmap seam: the same position and
    // TEXCOORD_0 on both sides, another TEXCOORD_1 (as lightmap unwrapping makes them).
    Mesh strip;
    strip.name = "strip";
    const int columns = 40;
    for (int side = 0; side < 2; ++side)
        for (int x = 0; x <= columns; ++x)
            for (int y = 0; y <= 1; ++y) {
                const float px = float(x) / columns, py = float(y + side);
                strip.positions.push_back({px, py * 0.5f, 0.1f * std::sin(6 * px)});
                strip.texcoords.push_back({px, py * 0.5f});
            }
    strip.texcoord_sets.resize(1);
    for (size_t i = 0; i < strip.positions.size(); ++i) {
        const int side = int(i) / (2 * (columns + 1));
        strip.texcoord_sets[0].push_back({strip.texcoords[i][0] * 0.5f + 0.5f * float(side), strip.texcoords[i][1]});
    }
    auto at = [&](int side, int x, int y) { return uint32_t(side * 2 * (columns + 1) + x * 2 + y); };
    for (int side = 0; side < 2; ++side)
        for (int x = 0; x < columns; ++x) {
            strip.triangles.push_back({at(side, x, 0), at(side, x + 1, 0), at(side, x + 1, 1)});
            strip.triangles.push_back({at(side, x, 0), at(side, x + 1, 1), at(side, x, 1)});
        }
    Asset in;
    in.objects.push_back(strip);
    EncodeOptions options;
    options.sample_spacing = 0;
    options.packet_size = 128;  // many TEXCOORDS packets
    const EncodedAsset e = encoded(in, options);
    // Side 0's top row and side 1's bottom row share positions and TEXCOORD_0: 41 pairs of points.
    CHECK(e.encoded.info.objects[0].point_count == strip.positions.size());
    REQUIRE(e.texcoord_packets > 4);

    // Every packet: the exact strip, each vertex with its own TEXCOORD_1.
    const Asset all = received_without(e.packets, [](size_t) { return false; }, 24);
    REQUIRE(all.objects.size() == 1);
    const Mesh& exact = all.objects[0];
    REQUIRE(exact.positions.size() == strip.positions.size());
    REQUIRE(exact.texcoord_sets.size() == 1);
    auto expected_uv1 = [&](const Mesh& m, size_t v) {
        // Which side the vertex's triangles are on tells its set: the output keeps the input's faces.
        for (const auto& t : m.triangles)
            for (uint32_t c : t)
                if (c == v) {
                    float ymin = 10;
                    for (uint32_t d : t) ymin = std::min(ymin, m.positions[d][1]);
                    return std::array<float, 2>{m.texcoords[v][0] * 0.5f + (ymin >= 0.49f ? 0.5f : 0.0f),
                                                m.texcoords[v][1]};
                }
        return std::array<float, 2>{NAN, NAN};
    };
    for (size_t v = 0; v < exact.positions.size(); ++v) {
        const auto want = expected_uv1(exact, v);
        CHECK(std::abs(exact.texcoord_sets[0][v][0] - want[0]) < 1e-3);
        CHECK(std::abs(exact.texcoord_sets[0][v][1] - want[1]) < 1e-3);
    }

    // Every other TEXCOORDS packet lost: still exact geometry, every vertex a TEXCOORD_1 (those whose
    // record was lost take the nearest held point's), and the stream says it is not complete.
    size_t seen = 0;
    ReceivedStream held;
    const Asset half = received_without(
        e.packets, [&](size_t i) { return is_packet_type(e.packets[i], PacketType::Texcoords) && seen++ % 2 == 0; }, 24,
        &held);
    CHECK_FALSE(held.objects()[0].texcoords_complete());
    REQUIRE(half.objects.size() == 1);
    const Mesh& m = half.objects[0];
    REQUIRE(m.texcoord_sets.size() == 1);
    REQUIRE(m.texcoord_sets[0].size() == m.positions.size());
    size_t own = 0;
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const auto& uv = m.texcoord_sets[0][v];
        REQUIRE((std::isfinite(uv[0]) && std::isfinite(uv[1])));
        const auto want = expected_uv1(m, v);
        own += std::abs(uv[0] - want[0]) < 1e-3 && std::abs(uv[1] - want[1]) < 1e-3;
        // The nearest held point is at most a column away, or across the seam.
        CHECK(std::abs(uv[1] - want[1]) < 0.51);
    }
    CHECK(own >= m.positions.size() / 3);
    CHECK(own < m.positions.size());

    // The exact layer lost: a reconstruction. A face corner at the seam takes the point of its own side
    // (the sets are compared when a vertex has several, spec 30.2): its TEXCOORD_1 is its side's.
    const Asset rebuilt = received_without(
        e.packets,
        [&](size_t i) { return exact_layer_packet(e.packets[i]); },
        48);
    REQUIRE(rebuilt.objects.size() == 1);
    const Mesh& r = rebuilt.objects[0];
    REQUIRE(r.texcoord_sets.size() == 1);
    size_t seam_corners = 0, right = 0;
    for (const auto& t : r.triangles) {
        float y = 0;
        for (uint32_t v : t) y += r.positions[v][1] / 3;
        const float side = y > 0.5f ? 0.5f : 0.0f;
        for (uint32_t v : t) {
            if (std::abs(r.positions[v][1] - 0.5f) > 1e-4f) continue;  // only corners on the seam's row
            ++seam_corners;
            right += std::abs(r.texcoord_sets[0][v][0] - (r.texcoords[v][0] * 0.5f + side)) < 2e-3f;
        }
    }
    MESSAGE(right << " of " << seam_corners << " corners on the lightmap seam have their side's TEXCOORD_1");
    // 358 of 444 (81%); 247 (56%) when the further set is not compared. The rest are corners whose other
    // corners stand on the seam too or borrow their sets (marching-cubes vertices, spec 13 step 4).
    CHECK(seam_corners > 40);
    CHECK(right >= seam_corners * 3 / 4);
}

TEST_CASE("the encoder refuses sets it cannot send, and the reader names what it leaves out") {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}};
    mesh.texcoord_sets.resize(1, std::vector<std::array<float, 2>>(3));
    CHECK_THROWS_WITH_AS(encode_meshes({mesh}, EncodeOptions{}), doctest::Contains("without TEXCOORD_0"),
                         std::invalid_argument);
    mesh.texcoords.resize(3);
    mesh.texcoord_sets.assign(8, std::vector<std::array<float, 2>>(3));
    CHECK_THROWS_WITH_AS(encode_meshes({mesh}, EncodeOptions{}), doctest::Contains("at most 8"), std::invalid_argument);
    mesh.texcoord_sets.assign(1, std::vector<std::array<float, 2>>(2));
    CHECK_THROWS_WITH_AS(encode_meshes({mesh}, EncodeOptions{}), doctest::Contains("TEXCOORD_1 array has 2 values"),
                         std::invalid_argument);

    // A material whose occlusion map is on TEXCOORD_1 drawn by a primitive without that set: the
    // texture is not sent, and the warning names the material slot and the primitive.
    const fs::path file = edited_gltf(multiuv_box(), scratch_dir("texcoord_sets_lacking"), [](nlohmann::json& doc) {
        doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
    });
    const Asset lacking = load_asset(file.string());
    CHECK(lacking.scene.materials[0].occlusion_texture.texture == kNone);
    CHECK(warnings_with(lacking.warnings, "occlusionTexture uses TEXCOORD_1 but mesh 0 primitive 0 has no TEXCOORD_1") == 1);
    // A set past TEXCOORD_7.
    const fs::path far = edited_gltf(multiuv_box(), scratch_dir("texcoord_sets_far"), [](nlohmann::json& doc) {
        doc["materials"][0]["occlusionTexture"]["texCoord"] = 9;
    });
    const Asset nine = load_asset(far.string());
    CHECK(nine.scene.materials[0].occlusion_texture.texture == kNone);
    CHECK(warnings_with(nine.warnings, "uses TEXCOORD_9; ellicast carries TEXCOORD_0 to TEXCOORD_7") == 1);
}

TEST_CASE("the writer never draws an object with a material on a set it lacks: an untextured copy, named in a warning") {
    // What the receiver's asset makes sure of (spec 30.2), checked again where the file is written.
    Asset a;
    Mesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    tri.triangles = {{0, 1, 2}};
    Mesh with_set = tri;
    with_set.texcoord_sets = {{{0.5f, 0.5f}, {1, 0.5f}, {0.5f, 1}}};
    a.objects = {tri, with_set};
    a.scene.meshes = {SceneMesh{0, "lacking", {{0, 0}}, {}}, SceneMesh{1, "with", {{1, 0}}, {}}};
    for (uint16_t i = 0; i < 2; ++i) {
        SceneNode n;
        n.index = i;
        n.mesh = i;
        n.name = i ? "with" : "lacking";
        a.scene.nodes.push_back(n);
    }
    Material mat;
    mat.occlusion_texture.texture = 0;
    mat.occlusion_texture.texcoord = 1;
    a.scene.materials = {mat};
    SceneDescription::Texture png;
    png.image = load_asset(multiuv_box().string()).scene.textures[0].image;  // a committed PNG
    png.info.image_type = ImageType::Png;
    a.scene.textures = {png};
    std::vector<std::string> warnings;
    std::string error;
    const fs::path file = scratch_dir("texcoord_sets_writer") / "out.gltf";
    REQUIRE_MESSAGE(write_asset(file.string(), a, {}, warnings, error), error);
    check_gltf_clean(file);
    const nlohmann::json doc = gltf_document(file);
    CHECK(warnings_with(warnings, "has no TEXCOORD_1 but material 0 has textures on it") == 1);
    const size_t lacking = doc["meshes"][0]["primitives"][0]["material"], with = doc["meshes"][1]["primitives"][0]["material"];
    CHECK(with == 0);
    CHECK(lacking != 0);
    CHECK_FALSE(doc["materials"][lacking].contains("occlusionTexture"));
    CHECK(doc["materials"][0]["occlusionTexture"]["texCoord"] == 1);
}
