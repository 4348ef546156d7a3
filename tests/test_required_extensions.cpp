// Required extensions (format 1.13, spec 29): an asset that requires an extension (an unlit
// material, a texture transform, its lights) comes back requiring it, so a viewer that does not
// support it refuses the output as it refused the input instead of showing it wrongly; what the output
// lacks, or what has not arrived, is said once. The packet-level rules are pinned by the required_*
// conformance vectors; these cases check what a user of the converters relies on.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <fstream>
#include <sstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

// The Khronos sample `sample` (under samples/khronos) with `edit` made to its document, written to a
// scratch folder with the files beside it.
fs::path edited_sample(const std::string& sample, const std::string& scratch, const std::function<void(nlohmann::json&)>& edit) {
    return edited_gltf(source_dir() / "samples" / "khronos" / sample, scratch_dir(scratch), edit);
}

struct Written {
    nlohmann::json doc;
    Asset received;
    std::vector<std::string> warnings;  // the receiver's and the writer's
};

// `in` encoded, every packet for which `lost` is true dropped, received and written as .gltf under
// `dir` (checked by the Khronos validator when installed).
Written through_stream(const Asset& in, const fs::path& dir, const std::function<bool(const std::vector<uint8_t>&)>& lost = {},
                       AssetWriteOptions options = {}) {
    EncodeOptions coarse;
    coarse.max_ellipsoids = 40;
    coarse.coverage = 0.8;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse, 1, true, encoded, error), error);
    Written w;
    w.received = received_without(encoded.packets, [&](size_t i) { return lost && lost(encoded.packets[i]); }, 24);
    w.warnings = w.received.warnings;
    const fs::path file = dir / "out.gltf";
    REQUIRE_MESSAGE(write_asset(file.string(), w.received, options, w.warnings, error), error);
    check_gltf_clean(file);
    w.doc = nlohmann::json::parse(std::ifstream(file));
    return w;
}

nlohmann::json list(const nlohmann::json& doc, const char* key) { return doc.value(key, nlohmann::json::array()); }

size_t warnings_with(const std::vector<std::string>& warnings, const std::string& text) {
    return size_t(std::count_if(warnings.begin(), warnings.end(),
                                [&](const std::string& w) { return w.find(text) != std::string::npos; }));
}

}  // namespace

TEST_CASE("an asset that requires KHR_materials_unlit comes back requiring it, through a stream and through convert") {
    const fs::path input = source_dir() / "samples" / "khronos" / "UnlitTest" / "UnlitTest.gltf";
    const Asset in = load_asset(input.string());
    CHECK(in.scene.required_extensions == std::vector<std::string>{"KHR_materials_unlit"});
    const Written w = through_stream(in, scratch_dir("required_unlit"));
    check_same_scene(in, w.received);
    CHECK(list(w.doc, "extensionsRequired") == nlohmann::json({"KHR_materials_unlit"}));
    CHECK(list(w.doc, "extensionsUsed") == nlohmann::json({"KHR_materials_unlit"}));
    CHECK(warnings_with(w.warnings, "required") == 0);

    // The command a user runs.
    const fs::path out = scratch_dir("required_unlit_cli") / "unlit.gltf";
    int status = 0;
    const std::string log = run_command(shell_quoted(ellicast_exe().string()) + " convert -q " + shell_quoted(input.string()) +
                                            " " + shell_quoted(out.string()),
                                        status);
    REQUIRE_MESSAGE(status == 0, log);
    check_gltf_clean(out);
    CHECK(list(nlohmann::json::parse(std::ifstream(out)), "extensionsRequired") == nlohmann::json({"KHR_materials_unlit"}));
}

TEST_CASE("the output requires what the source required and it uses, after its own storage, and names the rest once") {
    // TextureTransformTest made to require its texture transforms, an extension ellicast does not carry
    // (KHR_materials_variants) and one of how it stored geometry (KHR_mesh_quantization, not sent:
    // the output's storage is the receiver's choice).
    const fs::path input = edited_sample("TextureTransformTest/TextureTransformTest.gltf", "required_transform", [](nlohmann::json& doc) {
        doc["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_variants", "KHR_mesh_quantization"};
        doc["extensionsRequired"] = {"KHR_mesh_quantization", "KHR_texture_transform", "KHR_materials_variants"};
    });
    const Asset in = load_asset(input.string());
    CHECK(in.scene.required_extensions == std::vector<std::string>{"KHR_texture_transform", "KHR_materials_variants"});
    CHECK(warnings_with(in.warnings, "KHR_materials_variants not sent (the input requires KHR_materials_variants") == 1);
    CHECK(warnings_with(in.warnings, "only changes appearance") == 0);  // said once, not twice

    const Written plain = through_stream(in, scratch_dir("required_transform_plain"));
    check_same_scene(in, plain.received);
    CHECK(list(plain.doc, "extensionsRequired") == nlohmann::json({"KHR_texture_transform"}));
    CHECK(warnings_with(plain.warnings, "the source required KHR_materials_variants, which this output does not use") == 1);

    // `ellicast convert` says it once: the encoder's warning names what is not sent.
    int status = 0;
    const std::string log = run_command(shell_quoted(ellicast_exe().string()) + " convert -q " + shell_quoted(input.string()) +
                                            " " + shell_quoted((scratch_dir("required_transform_cli") / "out.glb").string()),
                                        status);
    REQUIRE_MESSAGE(status == 0, log);
    size_t said = 0;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);)
        said += line.rfind("ellicast: warning: ", 0) == 0 && line.find("KHR_materials_variants") != std::string::npos;
    CHECK(said == 1);

    AssetWriteOptions quantized;
    quantized.quantize = true;
    const Written q = through_stream(in, scratch_dir("required_transform_quantized"), {}, quantized);
    CHECK(list(q.doc, "extensionsRequired") == nlohmann::json({"KHR_mesh_quantization", "KHR_texture_transform"}));
}

TEST_CASE("required KHR_lights_punctual comes back required with the lights") {
    const fs::path input = edited_sample("Cameras/Cameras.gltf", "required_lights", [](nlohmann::json& doc) {
        doc["extensionsUsed"] = {"KHR_lights_punctual"};
        doc["extensionsRequired"] = {"KHR_lights_punctual"};
        doc["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::parse(R"([{"type": "point", "intensity": 2}])");
        doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    });
    const Written w = through_stream(load_asset(input.string()), scratch_dir("required_lights_out"));
    CHECK(list(w.doc, "extensionsRequired") == nlohmann::json({"KHR_lights_punctual"}));
    CHECK(list(w.doc, "extensionsUsed") == nlohmann::json({"KHR_lights_punctual"}));
}

TEST_CASE("without its REQUIRED_EXTENSION packets a receiver writes the extensions as used only, and says when some are missing") {
    const fs::path input = edited_sample("TextureTransformTest/TextureTransformTest.gltf", "required_lost", [](nlohmann::json& doc) {
        doc["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_unlit"};
        doc["extensionsRequired"] = {"KHR_texture_transform", "KHR_materials_unlit"};
        doc["materials"][0]["extensions"]["KHR_materials_unlit"] = nlohmann::json::object();
    });
    const Asset in = load_asset(input.string());
    REQUIRE(in.scene.required_extensions.size() == 2);
    const Written none = through_stream(in, scratch_dir("required_lost_all"), [](const std::vector<uint8_t>& p) {
        return is_packet_type(p, PacketType::RequiredExtension);
    });
    CHECK_FALSE(none.doc.contains("extensionsRequired"));
    CHECK(list(none.doc, "extensionsUsed").size() == 2);
    CHECK(warnings_with(none.warnings, "required extensions have not arrived") == 0);  // nothing announced them

    size_t seen = 0;
    const Written half = through_stream(in, scratch_dir("required_lost_half"), [&](const std::vector<uint8_t>& p) {
        return is_packet_type(p, PacketType::RequiredExtension) && seen++ == 0;
    });
    CHECK(list(half.doc, "extensionsRequired") == nlohmann::json({"KHR_materials_unlit"}));
    CHECK(warnings_with(half.warnings, "1 of the source's 2 required extensions have not arrived") == 1);
}

TEST_CASE("packetize_scene refuses required extensions it cannot send, and a receiver keeps one name per index") {
    SceneDescription scene;
    ScenePackets packets;
    auto refused = [&](std::vector<std::string> names) {
        scene.required_extensions = std::move(names);
        return packetize_scene(scene, 128, 1, 0, packets) == Error::MalformedPayload;
    };
    CHECK(refused({""}));
    CHECK(refused({"KHR-materials_unlit"}));
    CHECK(refused({std::string(65, 'A')}));
    CHECK(refused({"KHR_a", "KHR_b", "KHR_a"}));
    std::vector<std::string> many;
    for (int i = 0; i < 256; ++i) many.push_back("EXT_" + std::to_string(i));
    CHECK(refused(many));
    many.pop_back();
    many.back() = std::string(64, 'z');  // the longest name, in the smallest packet
    REQUIRE_FALSE(refused(many));
    REQUIRE(packets.required_extensions.size() == 255);
    CHECK(packets.required_extensions.back().size() == 24 + 4 + 64);  // framing, fixed fields, name: within 128

    ReceivedStream stream;
    uint64_t at = 0;
    for (auto it = packets.required_extensions.rbegin(); it != packets.required_extensions.rend(); ++it)
        CHECK(stream.add_packet(*it, at++) == Error::Ok);
    CHECK(stream.required_extensions().size() == 255);
    CHECK(stream.required_extension_count() == std::optional<uint8_t>(255));
    // Every packet again: duplicates, nothing changes.
    for (const auto& p : packets.required_extensions) CHECK(stream.add_packet(p, at++) == Error::Ok);
    CHECK(stream.counters().duplicates == 255);

    // Another stream's list of another length: refused, not mixed in.
    scene.required_extensions = {"KHR_materials_unlit"};
    REQUIRE(packetize_scene(scene, 128, 1, 0, packets) == Error::Ok);
    CHECK(stream.add_packet(packets.required_extensions[0], at++) == Error::StreamMismatch);
    CHECK(stream.required_extensions().at(0) == "EXT_0");
}
