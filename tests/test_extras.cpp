// Extras (format 1.12, spec 28): a glTF asset's `extras` on the asset, its scene and every element
// of the stream's tables come back where they were, as the same JSON values (nulls too), also a
// mesh's morph target names; what is lost or hostile costs the extras and never the file. The
// packet-level rules are pinned by the extras* conformance vectors; these cases check what a user of
// the converters and a receiver under attack rely on.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <fstream>
#include <map>
#include <random>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

// A value for element `i` of `table` with the JSON types and nulls tinygltf's own values lose.
nlohmann::json tag(const std::string& table, size_t i) {
    return {{"ellicast_test", table + " " + std::to_string(i)}, {"list", {1, nullptr, {{"x", nullptr}}}}, {"pi", 3.25}};
}

// The glTF at `source` with extras on the asset, its scenes and every element of `tables` (including
// the KHR_lights_punctual lights), written to `dir` with its .bin and images beside it.
fs::path tagged(const fs::path& source, const fs::path& dir, const std::vector<std::string>& tables,
                const std::function<void(nlohmann::json&)>& edit = {}) {
    return edited_gltf(
        source, dir,
        [&](nlohmann::json& doc) {
            doc["asset"]["extras"] = {{"copyright", "ellicast tests"}, {"empty", nlohmann::json::object()}};
            for (size_t s = 0; s < doc["scenes"].size(); ++s) doc["scenes"][s]["extras"] = tag("scene", s);
            for (const std::string& table : tables) {
                nlohmann::json& elements = table == "lights" ? doc["extensions"]["KHR_lights_punctual"]["lights"] : doc[table];
                for (size_t i = 0; i < elements.size(); ++i) elements[i]["extras"] = tag(table, i);
            }
            if (edit) edit(doc);
        },
        "Tagged_");
}

// The document of a written .gltf.
nlohmann::json gltf_json(const fs::path& path) { return nlohmann::json::parse(std::ifstream(path)); }

// Every extras value of a table of `doc`, as text, sorted.
std::vector<std::string> extras_of(const nlohmann::json& doc, const std::string& table) {
    const nlohmann::json* elements = &doc[table];
    if (table == "lights") {
        if (!doc.contains("extensions")) return {};
        elements = &doc["extensions"]["KHR_lights_punctual"]["lights"];
    }
    std::vector<std::string> out;
    if (!elements->is_array()) return out;
    for (const auto& e : *elements)
        if (e.contains("extras")) out.push_back(e["extras"].dump());
    std::sort(out.begin(), out.end());
    return out;
}

// `in` through encode, with every packet but those of `lost_type` (0: none), decode and write to
// `dir`/out.gltf (checked by the Khronos validator when installed); the written document.
nlohmann::json extras_round_trip(const Asset& in, const fs::path& dir, uint8_t lost_type = 0, Asset* decoded = nullptr) {
    EncodeOptions coarse;
    coarse.max_ellipsoids = 60;
    coarse.coverage = 0.8;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse, 1, true, encoded, error), error);
    Asset out = received_without(encoded.packets, [&](size_t i) { return lost_type && encoded.packets[i][6] == lost_type; }, 24);
    std::vector<std::string> warnings;
    const fs::path file = dir / "out.gltf";
    REQUIRE_MESSAGE(write_asset(file.string(), out, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(file);
    if (decoded) *decoded = std::move(out);
    return gltf_json(file);
}

}  // namespace

TEST_CASE("glTF extras travel on the asset, its scene, nodes, meshes, materials, animations, skins, textures, cameras "
          "and lights, as the same JSON values with their nulls") {
    struct Case {
        const char* sample;  // under samples/khronos
        std::vector<std::string> tables;
    };
    const std::vector<Case> cases = {
        {"AnimatedMorphCube/AnimatedMorphCube.gltf", {"nodes", "meshes", "materials", "animations"}},  // weights only
        {"SimpleSkin/simple_skin.gltf", {"nodes", "meshes", "skins", "animations"}},
        {"TextureTransformTest/TextureTransformTest.gltf", {"nodes", "meshes", "materials", "textures"}},
        {"Cameras/Cameras.gltf", {"nodes", "meshes", "cameras"}},
    };
    for (const Case& c : cases) {
        CAPTURE(c.sample);
        const fs::path dir = scratch_dir(std::string("extras_") + fs::path(c.sample).stem().string());
        const fs::path input = tagged(source_dir() / "samples" / "khronos" / c.sample, dir, c.tables);
        const Asset in = load_asset(input.string());
        for (const std::string& w : in.warnings)
            CHECK_MESSAGE((w.find("extras of ") == std::string::npos && w.find("its extras") == std::string::npos), w);
        const nlohmann::json source = gltf_json(input);
        Asset decoded;
        const nlohmann::json out = extras_round_trip(in, dir, 0, &decoded);
        check_same_scene(in, decoded);  // the same texts on the same elements, and the rest of the scene
        CHECK(out["asset"]["extras"] == source["asset"]["extras"]);
        CHECK(out["scenes"][0]["extras"] == source["scenes"][source.value("scene", 0)]["extras"]);
        for (const std::string& table : c.tables) {
            CAPTURE(table);
            CHECK(extras_of(out, table) == extras_of(source, table));
        }
        // Each node's extras on the node of the same name.
        std::map<std::string, nlohmann::json> by_name;
        for (const auto& n : source["nodes"])
            if (n.contains("name")) by_name[n["name"]] = n["extras"];
        for (const auto& n : out["nodes"])
            if (n.contains("name") && by_name.count(n["name"])) CHECK(n["extras"] == by_name[n["name"]]);
    }
}

TEST_CASE("a mesh's morph target names come back with its targets, and lights' extras on KHR_lights_punctual") {
    const fs::path dir = scratch_dir("extras_target_names");
    const fs::path input = tagged(source_dir() / "samples" / "khronos" / "AnimatedMorphCube" / "AnimatedMorphCube.gltf", dir, {},
                                  [](nlohmann::json& doc) { doc["meshes"][0]["extras"] = {{"targetNames", {"thin", "angle"}}}; });
    const nlohmann::json out = extras_round_trip(load_asset(input.string()), dir);
    REQUIRE(out["meshes"][0].contains("weights"));
    CHECK(out["meshes"][0]["extras"]["targetNames"] == nlohmann::json({"thin", "angle"}));
    CHECK(out["meshes"][0]["extras"]["targetNames"].size() == out["meshes"][0]["weights"].size());

    // Lights: Khronos Cameras with one spot light on node 1.
    const fs::path lit_dir = scratch_dir("extras_lights");
    const fs::path lit = tagged(source_dir() / "samples" / "khronos" / "Cameras" / "Cameras.gltf", lit_dir, {"lights"},
                                [](nlohmann::json& doc) {
                                    doc["extensionsUsed"] = {"KHR_lights_punctual"};
                                    doc["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::parse(
                                        R"([{"type": "spot", "intensity": 5, "spot": {"outerConeAngle": 0.7},
                                            "extras": {"gel": "blue", "dimmer": null}}])");
                                    doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0;
                                });
    const nlohmann::json lit_out = extras_round_trip(load_asset(lit.string()), lit_dir);
    CHECK(extras_of(lit_out, "lights") == std::vector<std::string>{R"({"dimmer":null,"gel":"blue"})"});
}

TEST_CASE("extras the stream has no table for are named in one warning, and a too large or absent text is not sent") {
    const fs::path dir = scratch_dir("extras_not_carried");
    const fs::path input = tagged(source_dir() / "samples" / "khronos" / "AnimatedMorphCube" / "AnimatedMorphCube.gltf", dir,
                                  {"accessors", "bufferViews"}, [](nlohmann::json& doc) {
                                      doc["meshes"][0]["primitives"][0]["extras"] = {{"a", 1}};
                                      doc["nodes"][0]["extras"] = {{"big", std::string(70000, 'x')}};
                                      doc["materials"][0]["extras"] = nullptr;  // null: as if absent
                                      doc["extras"] = {{"root", true}};
                                  });
    const Asset in = load_asset(input.string());
    size_t named = 0;
    for (const std::string& w : in.warnings) {
        if (w.find("extras of ") != std::string::npos) {
            ++named;
            CHECK(w.find("accessor") != std::string::npos);
            CHECK(w.find("buffer view") != std::string::npos);
            CHECK(w.find("1 primitive") != std::string::npos);
            CHECK(w.find("glTF root object") != std::string::npos);
        }
    }
    CHECK(named == 1);
    CHECK(std::any_of(in.warnings.begin(), in.warnings.end(), [](const std::string& w) {
        return w.find("node 0") != std::string::npos && w.find("larger than 65536 bytes; not sent") != std::string::npos;
    }));
    for (const SceneExtras& e : in.scene.extras) {
        CHECK_FALSE(e.kind == ExtrasTarget::Node);
        CHECK_FALSE(e.kind == ExtrasTarget::Material);
    }
    const nlohmann::json out = extras_round_trip(in, dir);
    CHECK_FALSE(out["nodes"][0].contains("extras"));
    CHECK(out["asset"]["extras"]["copyright"] == "ellicast tests");
}

TEST_CASE("without its EXTRAS packets a receiver writes the same valid scene with no extras, and says what it waits for") {
    const fs::path dir = scratch_dir("extras_lost");
    const fs::path input = tagged(source_dir() / "samples" / "khronos" / "SimpleSkin" / "simple_skin.gltf", dir,
                                  {"nodes", "meshes", "skins", "animations"});
    Asset decoded;
    const nlohmann::json out = extras_round_trip(load_asset(input.string()), dir, uint8_t(PacketType::Extras), &decoded);
    CHECK_FALSE(out["asset"].contains("extras"));
    CHECK(extras_of(out, "nodes").empty());
    CHECK(out["skins"].size() == 1);
    CHECK(out["animations"].size() == 1);

    // Half of them: what arrived is written, the rest named in one warning.
    EncodedAsset encoded;
    std::string error;
    EncodeOptions coarse;
    coarse.max_ellipsoids = 60;
    REQUIRE(encode_asset(load_asset(input.string()), coarse, 1, true, encoded, error));
    size_t seen = 0;
    const Asset half = received_without(encoded.packets, [&](size_t i) {
        return is_packet_type(encoded.packets[i], PacketType::Extras) && (seen++ % 2 == 1);
    }, 24);
    CHECK(!half.scene.extras.empty());
    CHECK(std::count_if(half.warnings.begin(), half.warnings.end(), [](const std::string& w) {
              return w.find("extras texts have not arrived whole") != std::string::npos;
          }) == 1);
}

TEST_CASE("a hostile stream of EXTRAS fragments cannot take more memory than the receiver's cap, nor more texts than it announced") {
    // A 65536-byte text in 1-byte fragments, every other one: each costs its byte plus 64 toward the
    // cap, so a 1 MiB cap stops it after about 16,000 fragments with `malformed payload`.
    ReceivedStream::Limits limits;
    limits.max_texture_bytes = 1u << 20;
    ReceivedStream stream(limits);
    const std::string text(65536, ' ');
    ExtrasFragment f;
    f.kind = ExtrasTarget::Node;
    f.index = 7;
    f.text_count = 1;
    f.text_size = 65536;
    f.text_crc = crc32c(reinterpret_cast<const uint8_t*>(text.data()), text.size());
    const auto packet = [&](uint32_t sequence) {
        PacketHeader h;
        h.version_minor = kExtrasMinor;
        h.type = uint8_t(PacketType::Extras);
        h.flags = kFlagSkippable;
        h.stream_id = 5;
        h.sequence = sequence;
        h.object_id = kStreamObjectId;
        return write_packet(h, encode_extras_payload(f));
    };
    size_t accepted = 0, refused = 0;
    for (uint32_t at = 0; at < 65536; at += 2) {
        f.offset = at;
        f.data = {uint8_t(' ')};
        const Error e = stream.add_packet(packet(at), at);
        (e == Error::Ok ? accepted : refused) += 1;
        if (e != Error::Ok) CHECK(e == Error::MalformedPayload);
    }
    CHECK(accepted > 15000);
    CHECK(accepted < 16500);
    CHECK(refused == 32768 - accepted);
    REQUIRE(stream.extras().size() == 1);
    CHECK_FALSE(stream.extras().begin()->second.complete);
    CHECK(stream.extras().begin()->second.memory <= limits.max_texture_bytes);

    // A second target in a stream that announced one text: refused, nothing kept of it.
    f.kind = ExtrasTarget::Asset;
    f.index = 0;
    f.offset = 0;
    CHECK(stream.add_packet(packet(70000), 1) == Error::StreamMismatch);
    CHECK(stream.extras().size() == 1);
}

TEST_CASE("packetize_scene refuses extras it cannot send: a target twice, past its table, empty, too long or not JSON") {
    SceneDescription scene;
    SceneNode node;
    scene.nodes.push_back(node);
    ScenePackets packets;
    auto refused = [&](std::vector<SceneExtras> extras) {
        scene.extras = std::move(extras);
        return packetize_scene(scene, 1200, 1, 0, packets) == Error::MalformedPayload;
    };
    CHECK(refused({{ExtrasTarget::Node, 0, "1"}, {ExtrasTarget::Node, 0, "2"}}));
    CHECK(refused({{ExtrasTarget::Node, 1, "{}"}}));
    CHECK(refused({{ExtrasTarget::Material, 0, "{}"}}));
    CHECK(refused({{ExtrasTarget::Asset, 1, "{}"}}));
    CHECK(refused({{ExtrasTarget::Node, 0, ""}}));
    CHECK(refused({{ExtrasTarget::Node, 0, "[" + std::string(65535, ' ') + "]"}}));
    CHECK(refused({{ExtrasTarget::Node, 0, "{\"a\":1,\"a\":2}"}}));
    CHECK(refused({{ExtrasTarget::Node, 0, "NaN"}}));
    CHECK(refused({{ExtrasTarget::MorphAnimation, 0, "{}"}}));
    CHECK_FALSE(refused({{ExtrasTarget::Node, 0, "{\"a\":1}"}, {ExtrasTarget::Asset, 0, "[]"}, {ExtrasTarget::Scene, 0, "null"}}));
    CHECK(packets.extras.size() == 3);
}
