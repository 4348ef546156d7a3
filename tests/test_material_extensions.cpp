// Format 1.3 (spec section 18): a material's extensions (KHR_materials_*) and texture transforms
// travel as a JSON patch in MATERIAL_EXTENSIONS packets. The patch checker (every malformed rule of
// 18.2, texture references in document order with their paths), the receiver (a material waits for
// its patch and the patch's textures; repeats, contradictions), and the converters: an asset per
// ratified material extension, made from the Duck sample, comes back from a stream with the same
// extension JSON, byte-identical images and a file the Khronos validator accepts.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"

#include <algorithm>
#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

bool patch_ok(const std::string& text) { return check_material_patch(text) == Error::Ok; }

// The Duck sample with `edit` applied to its glTF JSON, read as an asset (its .bin and PNG beside it).
Asset edited_duck(const fs::path& dir, const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
    for (const char* file : {"Duck0.bin", "DuckCM.png"})
        if (!fs::exists(dir / file)) fs::copy_file(shared_samples() / "gltf/Duck" / file, dir / file);
    auto json = nlohmann::json::parse(read_bytes(shared_samples() / "gltf/Duck/Duck.gltf"));
    edit(json);
    std::ofstream(dir / (name + ".gltf"), std::ios::binary) << json.dump();
    return load_asset((dir / (name + ".gltf")).string());
}

// The Duck whose material uses extension `name` with `value`.
Asset duck_with(const fs::path& dir, const std::string& name, const nlohmann::json& value) {
    return edited_duck(dir, name, [&](nlohmann::json& j) {
        j["extensionsUsed"] = {name};
        if (value.dump().find("KHR_texture_transform") != std::string::npos)
            j["extensionsUsed"].push_back("KHR_texture_transform");
        j["materials"][0]["extensions"][name] = value;
    });
}

std::vector<std::vector<uint8_t>> packets_of(const Asset& asset) {
    EncodeOptions options;
    options.max_ellipsoids = 40;
    options.coverage = 0.8;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, options, 7, true, encoded, error), error);
    return encoded.packets;
}

// What a receiver makes of `packets` (those for which keep(type) holds).
Asset received(const std::vector<std::vector<uint8_t>>& packets, const std::function<bool(uint8_t)>& keep,
               ReceivedStream* out = nullptr) {
    return received_without(packets, [&](size_t i) { return !keep(packets[i][6]); }, 32, out);
}

bool any_of(const std::vector<std::string>& warnings, const std::string& needle) {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

constexpr uint8_t kMaterialExtensionsType = uint8_t(PacketType::MaterialExtensions);

}  // namespace

TEST_CASE("a patch is checked by every rule of spec 18.2") {
    // Well-formed: the shape, escapes, nesting, numbers, texture references with texCoord 0.
    for (const char* good :
         {R"({})", " \t\r\n{ } ", R"({"extensions":{}})",
          R"({"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":1,"clearcoatTexture":{"index":0,"texCoord":0}}}})",
          R"({"extensions":{"X":{"a":[1,-0.5e-3,2E+2,true,false,null,"\u00e9\ud83d\ude00\"\\\/\b\f\n\r\t"],"layerTexture":{"index":65534}}}})",
          R"({"pbrMetallicRoughness":{"baseColorTexture":{"extensions":{"KHR_texture_transform":{"scale":[2,2],"texCoord":0}}},"extensions":{}},"normalTexture":{"extensions":{}},"occlusionTexture":{"extensions":{}},"emissiveTexture":{}})",
          "{\"extensions\":{\"X\":{\"a\":\"\xc3\xa9\"}}}"})
        CHECK_MESSAGE(patch_ok(good), good);
    // Malformed, one rule at a time.
    // The patch is depth 1, extensions 2, X 3, the arrays from 4: 29 of them reach 32, 30 reach 33.
    const std::string deep_ok = R"({"extensions":{"X":{"a":)" + std::string(29, '[') + std::string(29, ']') + "}}}";
    const std::string deep = R"({"extensions":{"X":{"a":)" + std::string(30, '[') + std::string(30, ']') + "}}}";
    CHECK(patch_ok(deep_ok));
    for (const std::string& bad : std::vector<std::string>{
             "", "[]", "1", "\"x\"", "{", "{}}", "{} {}", "{},", "\xef\xbb\xbf{}",           // rule 3
             "{\"extensions\":{\"X\":{\"a\":\"\xc3\"}}}",                                  // rule 2
             R"({"extensions":{"X":{"a":NaN}}})", R"({"extensions":{"X":{"a":Infinity}}})",
             R"({"extensions":{"X":{"a":01}}})", R"({"extensions":{"X":{"a":1.}}})", R"({"extensions":{"X":{"a":.5}}})",
             R"({"extensions":{"X":{"a":[1,]}}})", R"({"extensions":{"X":{"a":1,}}})", R"({/*c*/})",
             R"({"extensions":{"X":{'a':1}}})", R"({"extensions":{"X":{"a":True}}})",
             "{\"extensions\":{\"X\":{\"a\":\"\t\"}}}",                                     // rule 4
             R"({"extensions":{"X":{"a":"\ud800"}}})", R"({"extensions":{"X":{"a":"\udc00"}}})",
             R"({"extensions":{"X":{"a":"\ud800\u0041"}}})", R"({"extensions":{"X":{"a":"\x"}}})",
             R"({"extensions":{"X":{"a":1e400}}})", R"({"extensions":{"X":{"a":-1e309}}})",  // rule 5
             R"({"extensions":{"X":{"a":1,"a":2}}})", R"({"extensions":{"X":{"a":1,"\u0061":2}}})",  // rule 6
             deep,                                                                          // rule 7
             R"({"name":"x"})", R"({"extensions":[]})", R"({"extensions":{"X":1}})",        // rule 8: shape
             R"({"normalTexture":{"index":0}})", R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1]}})",
             R"({"extras":{}})", R"({"emissiveTexture":{"extensions":{"X":[]}}})",
             R"({"extensions":{"X":{"tTexture":{"index":00}}}})",                          // rule 8: references
             R"({"extensions":{"X":{"tTexture":{"index":65535}}}})",
             R"({"extensions":{"X":{"tTexture":{"index":1.0}}}})",
             R"({"extensions":{"X":{"tTexture":{"index":-1}}}})",
             R"({"extensions":{"X":{"tTexture":{"index":"0"}}}})",
             R"({"extensions":{"X":{"tTexture":{"index":0,"texCoord":1}}}})",
             R"({"extensions":{"X":{"tTexture":{"index":0,"texCoord":0.0}}}})",
             R"({"extensions":{"X":{"KHR_texture_transform":{"texCoord":1}}}})"})
        CHECK_MESSAGE(!patch_ok(bad), bad);
    // Not a texture reference: no index, or a name not ending in "Texture".
    CHECK(patch_ok(R"({"extensions":{"X":{"tTexture":{"texCoord":1},"texture":{"index":-1}}}})"));
}

TEST_CASE("a patch's texture references come in document order with their paths, and move to another table") {
    const std::string patch =
        R"({"extensions":{"B":{"layers":[{"aTexture":{"index":3}},{"bTexture":{"index":10,"extensions":{"C":{"cTexture":{"index":0}}}}}]},)"
        R"("A":{"zTexture":{"index":7}}}})";
    std::vector<PatchTextureReference> refs;
    REQUIRE(check_material_patch(patch, &refs) == Error::Ok);
    REQUIRE(refs.size() == 4);
    CHECK(refs[0].path == "extensions/B/layers/0/aTexture");
    CHECK(refs[0].texture == 3);
    CHECK(refs[1].path == "extensions/B/layers/1/bTexture");
    CHECK(refs[1].texture == 10);
    CHECK(refs[2].path == "extensions/B/layers/1/bTexture/extensions/C/cTexture");
    CHECK(refs[3].path == "extensions/A/zTexture");
    const std::string moved = remap_patch_textures(patch, refs, [](uint16_t t) { return uint16_t(t * 100 + 1); });
    std::vector<PatchTextureReference> after;
    REQUIRE(check_material_patch(moved, &after) == Error::Ok);
    REQUIRE(after.size() == 4);
    CHECK(after[0].texture == 301);
    CHECK(after[1].texture == 1001);
    CHECK(after[2].texture == 1);
    CHECK(after[3].texture == 701);
}

TEST_CASE("a receiver keeps one patch per material: repeats are duplicates, other bytes or another table size a "
          "mismatch, and a MATERIAL is compared with the patches' table size") {
    auto packet = [](uint8_t type, std::vector<uint8_t> payload) {
        PacketHeader h;
        h.type = type;
        h.flags = kFlagSkippable;
        h.stream_id = 5;
        h.object_id = kStreamObjectId;
        return write_packet(h, payload);
    };
    auto patch_packet = [&](uint16_t index, uint16_t count, const std::string& text) {
        return packet(kMaterialExtensionsType, encode_material_extensions_payload({index, count, text}));
    };
    ReceivedStream stream;
    CHECK(stream.add_packet(patch_packet(0, 2, R"({"extensions":{"KHR_materials_unlit":{}}})"), 0) == Error::Ok);
    CHECK(stream.counters().accepted == 1);
    CHECK(stream.add_packet(patch_packet(0, 2, R"({"extensions":{"KHR_materials_unlit":{}}})"), 1) == Error::Ok);
    CHECK(stream.counters().duplicates == 1);
    CHECK(stream.add_packet(patch_packet(0, 2, R"({"extensions":{"KHR_materials_unlit": {}}})"), 2) ==
          Error::StreamMismatch);
    CHECK(stream.add_packet(patch_packet(1, 3, R"({})"), 3) == Error::StreamMismatch);
    CHECK(stream.add_packet(patch_packet(2, 2, R"({})"), 4) == Error::MalformedPayload);  // index >= count
    CHECK(stream.add_packet(patch_packet(1, 2, R"({"extras":1})"), 5) == Error::MalformedPayload);
    Material m;
    m.index = 1;
    m.material_count = 3;
    CHECK(stream.add_packet(packet(uint8_t(PacketType::Material), encode_material_payload(m)), 6) ==
          Error::StreamMismatch);
    m.material_count = 2;
    m.has_extensions = true;
    CHECK(stream.add_packet(packet(uint8_t(PacketType::Material), encode_material_payload(m)), 7) == Error::Ok);
    REQUIRE(stream.materials().count(1));
    CHECK(stream.materials().at(1).has_extensions);
    REQUIRE(stream.material_extensions().size() == 1);
    CHECK(stream.material_extensions().at(0).patch == R"({"extensions":{"KHR_materials_unlit":{}}})");
}

TEST_CASE("every ratified material extension comes back from a stream with the same JSON, the same image and a "
          "valid file") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const fs::path dir = scratch_dir("material_extensions");
    const std::vector<uint8_t> png = read_bytes(shared_samples() / "gltf/Duck/DuckCM.png");
    const nlohmann::json texture = {{"index", 0}};
    const nlohmann::json transformed = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 2}}}}}}};
    const std::vector<std::pair<std::string, nlohmann::json>> extensions = {
        {"KHR_materials_emissive_strength", {{"emissiveStrength", 5.5}}},
        {"KHR_materials_ior", {{"ior", 1.4}}},
        {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularTexture", texture}, {"specularColorFactor", {1, 0.5, 0.25}}}},
        {"KHR_materials_sheen", {{"sheenColorFactor", {0.5, 0.25, 0.125}}, {"sheenColorTexture", texture}, {"sheenRoughnessFactor", 0.3}}},
        {"KHR_materials_clearcoat", {{"clearcoatFactor", 1}, {"clearcoatTexture", transformed}, {"clearcoatRoughnessFactor", 0.1},
                                     {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}},
        {"KHR_materials_transmission", {{"transmissionFactor", 0.75}, {"transmissionTexture", texture}}},
        {"KHR_materials_volume", {{"thicknessFactor", 0.2}, {"attenuationDistance", 2.5}, {"attenuationColor", {0.875, 0.75, 0.625}}}},
        {"KHR_materials_iridescence", {{"iridescenceFactor", 1}, {"iridescenceIor", 1.3}, {"iridescenceThicknessMinimum", 100},
                                       {"iridescenceThicknessMaximum", 400}, {"iridescenceThicknessTexture", texture}}},
        {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}, {"anisotropyRotation", 1.25}, {"anisotropyTexture", texture}}},
        {"KHR_materials_unlit", nlohmann::json::object()},
    };
    for (const auto& [name, value] : extensions) {
        CAPTURE(name);
        Asset in = duck_with(dir, name, value);
        CHECK(!any_of(in.warnings, "extension " + name));  // (the file's name is the extension's)
        REQUIRE(in.scene.materials.size() == 1);
        const nlohmann::json expected = {{"extensions", {{name, value}}}};
        REQUIRE(!in.scene.materials[0].extensions.empty());
        CHECK(nlohmann::json::parse(in.scene.materials[0].extensions) == expected);
        const auto packets = packets_of(in);
        CHECK(std::count_if(packets.begin(), packets.end(), [](const auto& p) { return p[6] == kMaterialExtensionsType; }) == 1);
        Asset out = received(packets, [](uint8_t) { return true; });
        REQUIRE(out.scene.materials.size() == 1);
        CHECK(out.scene.materials[0].has_extensions);
        const fs::path file = dir / (name + "_out.glb");
        std::vector<std::string> warnings;
        std::string error;
        REQUIRE_MESSAGE(write_asset(file.string(), out, {}, warnings, error), error);
        CHECK_MESSAGE(warnings.empty(), warnings.front());
        int errors = -1;
        std::string report;
        if (validate_gltf(file, errors, report)) CHECK_MESSAGE(errors == 0, report);
        Asset back = load_asset(file.string());
        REQUIRE(back.scene.materials.size() == 1);
        CHECK(nlohmann::json::parse(back.scene.materials[0].extensions) == expected);
        REQUIRE(back.scene.textures.size() == 1);
        CHECK(back.scene.textures[0].image == png);
        CHECK(!any_of(back.warnings, "extension " + name));
    }
}

TEST_CASE("a material waits for its patch and for the patch's textures, and is shown whole once they arrived") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const fs::path dir = scratch_dir("material_extensions_waiting");
    Asset in = duck_with(dir, "KHR_materials_clearcoat", {{"clearcoatFactor", 1}, {"clearcoatTexture", {{"index", 0}}}});
    const auto packets = packets_of(in);
    // The patch lost: the flag says there is one, so the material is not shown.
    Asset without_patch = received(packets, [](uint8_t type) { return type != kMaterialExtensionsType; });
    CHECK(without_patch.scene.materials.empty());
    CHECK(any_of(without_patch.warnings, "material 0 (blinn3-fx) is waiting for its extensions"));
    // The texture lost: neither the core material nor the patch can be shown.
    Asset without_texture = received(packets, [](uint8_t type) { return type != uint8_t(PacketType::TextureFragment); });
    CHECK(without_texture.scene.materials.empty());
    CHECK(any_of(without_texture.warnings, "extensions/KHR_materials_clearcoat/clearcoatTexture texture 0 (none of it arrived)"));
    // Everything: shown with its patch.
    Asset whole = received(packets, [](uint8_t) { return true; });
    REQUIRE(whole.scene.materials.size() == 1);
    CHECK(nlohmann::json::parse(whole.scene.materials[0].extensions)["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"] == 1);
}

TEST_CASE("what is not carried is named: a vendor extension, a texture on TEXCOORD_1 inside an extension, a patch "
          "larger than a packet") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const fs::path dir = scratch_dir("material_extensions_not_carried");
    Asset vendor = edited_duck(dir, "vendor", [](nlohmann::json& j) {
        j["extensionsUsed"] = {"ADOBE_materials_thin_transparency", "KHR_materials_ior"};
        j["materials"][0]["extensions"]["ADOBE_materials_thin_transparency"] = {{"transmissionFactor", 0.5}};
        j["materials"][0]["extensions"]["KHR_materials_ior"] = {{"ior", 1.2}};
    });
    CHECK(any_of(vendor.warnings, "extension ADOBE_materials_thin_transparency is not sent"));
    CHECK(nlohmann::json::parse(vendor.scene.materials[0].extensions) ==
          nlohmann::json{{"extensions", {{"KHR_materials_ior", {{"ior", 1.2}}}}}});

    Asset set1 = duck_with(dir, "KHR_materials_sheen",
                           {{"sheenColorFactor", {1, 1, 1}}, {"sheenColorTexture", {{"index", 0}, {"texCoord", 1}}}});
    CHECK(any_of(set1.warnings, "sheenColorTexture: it uses another texture-coordinate set than TEXCOORD_0"));
    CHECK(nlohmann::json::parse(set1.scene.materials[0].extensions) ==
          nlohmann::json{{"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1, 1, 1}}}}}}});

    Asset large = duck_with(dir, "KHR_materials_large", {{"note", std::string(2000, 'x')}});
    EncodeOptions options;
    options.max_ellipsoids = 40;
    options.coverage = 0.8;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(large, options, 7, true, encoded, error), error);
    CHECK(any_of(encoded.encoded.warnings, "material 0: its extensions"));
    CHECK(std::none_of(encoded.packets.begin(), encoded.packets.end(),
                       [](const auto& p) { return p[6] == kMaterialExtensionsType; }));
    Asset out = received(encoded.packets, [](uint8_t) { return true; });
    REQUIRE(out.scene.materials.size() == 1);  // shown without its patch: the flag is not set
    CHECK(out.scene.materials[0].extensions.empty());
}
