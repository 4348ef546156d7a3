// Reading a glTF as a scene (load_asset): nodes, meshes, materials and textures as the asset has
// them, each distinct primitive once in its mesh's own frame, texture files byte for byte, and a
// warning for everything that is not carried.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "jpeg_images.h"
#include "support.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <tuple>

using namespace ellicast;
using ellicast::test::have_sample;
using ellicast::test::shared_samples;
using ellicast::test::base64;

namespace {

std::string sample(const std::string& rel) { return (shared_samples() / rel).string(); }

void spit(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

bool any_warning(const Asset& a, const std::string& needle) {
    return std::any_of(a.warnings.begin(), a.warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

// A one-triangle glTF with a material using an image given by `image_json`.
std::string triangle_gltf(const std::string& image_json) {
    // positions (0,0,0) (1,0,0) (0,1,0) and uv; 3 * 12 + 3 * 8 = 60 bytes
    std::vector<uint8_t> bin(60, 0);
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    float uv[6] = {0, 0, 1, 0, 0, 1};
    std::memcpy(bin.data(), pos, 36);
    std::memcpy(bin.data() + 36, uv, 24);
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"name":"tri"}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
"textures":[{"source":0}],"images":[)" +
           image_json + R"(],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],
"buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)" +
           base64(bin) + R"("}]})";
}

}  // namespace

TEST_CASE("the Duck keeps its three nodes, its material and its texture file byte for byte") {
    for (const char* f : {"gltf/Duck/Duck.gltf", "gltf/Duck-glb/Duck.glb"}) {
        if (!have_sample(f) || !have_sample("gltf/Duck/DuckCM.png")) continue;
        CAPTURE(f);
        Asset a = load_asset(sample(f));
        REQUIRE(a.scene.nodes.size() == 3);
        CHECK(a.scene.nodes[0].parent == kNone);
        CHECK(a.scene.nodes[0].has_matrix);
        CHECK(a.scene.nodes[0].matrix[0] == doctest::Approx(0.01));
        CHECK(a.scene.nodes[1].parent == 0);
        CHECK(a.scene.nodes[2].parent == 0);
        CHECK(a.scene.nodes[2].mesh == 0);
        CHECK(a.scene.nodes[1].mesh == kNone);
        REQUIRE(a.objects.size() == 1);
        CHECK(a.objects[0].positions.size() == 2399);
        CHECK(a.objects[0].has_texcoords());
        REQUIRE(a.scene.meshes.size() == 1);
        REQUIRE(a.scene.meshes[0].primitives.size() == 1);
        CHECK(a.scene.meshes[0].primitives[0].object == 0);
        CHECK(a.scene.meshes[0].primitives[0].material == 0);
        REQUIRE(a.scene.materials.size() == 1);
        CHECK(a.scene.materials[0].metallic == 0);
        CHECK(a.scene.materials[0].base_color_texture.texture == 0);
        REQUIRE(a.scene.textures.size() == 1);
        CHECK(a.scene.textures[0].info.image_type == ImageType::Png);
        CHECK(a.scene.textures[0].info.mag_filter == 9729);
        CHECK(a.scene.textures[0].info.min_filter == 9986);
        CHECK(a.scene.textures[0].image == test::read_bytes(shared_samples() / "gltf/Duck/DuckCM.png"));
        // Format 1.10: its camera travels, on its node, with no warning.
        CHECK_FALSE(any_warning(a, "camera"));
        REQUIRE(a.scene.cameras.size() == 1);
        CHECK(std::count_if(a.scene.nodes.begin(), a.scene.nodes.end(), [](const SceneNode& n) { return n.camera == 0; }) == 1);
    }
}

TEST_CASE("objects stay in their mesh's frame: the flattened reader equals them under the node transforms") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    Asset a = load_asset(sample("gltf/Duck/Duck.gltf"));
    LoadResult flat = load_gltf(sample("gltf/Duck/Duck.gltf"));
    REQUIRE(flat.meshes.size() == 1);
    REQUIRE(a.objects[0].positions.size() == flat.meshes[0].positions.size());
    // The Duck's root scales by 0.01; the mesh node has no transform.
    for (size_t i = 0; i < flat.meshes[0].positions.size(); i += 97)
        for (int k = 0; k < 3; ++k)
            CHECK(flat.meshes[0].positions[i][k] == doctest::Approx(a.objects[0].positions[i][k] * 0.01).epsilon(1e-4));
}

TEST_CASE("an instanced mesh is one set of objects: the milk truck's two wheel nodes share one object") {
    if (!have_sample("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf")) return;
    Asset a = load_asset(sample("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf"));
    REQUIRE(a.scene.nodes.size() == 5);
    REQUIRE(a.scene.meshes.size() == 2);
    CHECK(a.scene.meshes[0].primitives.size() == 3);
    CHECK(a.scene.meshes[1].primitives.size() == 1);
    CHECK(a.objects.size() == 4);  // 3 truck primitives + 1 wheel, though 2 nodes show the wheels
    CHECK(a.scene.nodes[2].mesh == 1);
    CHECK(a.scene.nodes[4].mesh == 1);
    CHECK(a.scene.nodes[1].has_matrix);
    CHECK(a.scene.nodes[1].matrix[12] == doctest::Approx(-1.35233));
    CHECK(a.scene.nodes[2].rotation[2] == doctest::Approx(0.0884859));
    REQUIRE(a.scene.materials.size() == 4);
    CHECK(a.scene.materials[1].name == "glass");
    CHECK(a.scene.materials[1].base_color[1] == doctest::Approx(0.0405063));
    // glTF textures 0 and 1 are the same image with the same sampler: sent once.
    REQUIRE(a.scene.textures.size() == 1);
    CHECK(a.scene.materials[0].base_color_texture.texture == 0);
    CHECK(a.scene.materials[3].base_color_texture.texture == 0);
    CHECK(a.scene.textures[0].image == test::read_bytes(shared_samples() / "gltf/CesiumMilkTruck/CesiumMilkTruck.png"));
    CHECK(a.scene.animations.size() == 1);  // its wheels turn (format 1.4)
    CHECK_FALSE(any_warning(a, "animation"));
}

TEST_CASE("the Fox comes with its whole node tree, its animations, its skin and the weights of every vertex") {
    if (!have_sample("gltf/Fox/Fox.gltf")) return;
    Asset a = load_asset(sample("gltf/Fox/Fox.gltf"));
    CHECK(a.scene.nodes.size() == 26);
    REQUIRE(a.objects.size() == 1);
    CHECK(a.objects[0].positions.size() == 1728);
    CHECK_FALSE(any_warning(a, "skin"));
    CHECK(a.scene.animations.size() == 3);
    CHECK_FALSE(any_warning(a, "JOINTS_0"));
    CHECK_FALSE(any_warning(a, "WEIGHTS_0"));
    // Format 1.5: the skin (24 joints, every one a node of the scene) and JOINTS_0 / WEIGHTS_0.
    REQUIRE(a.scene.skins.size() == 1);
    CHECK(a.scene.skins[0].joints.size() == 24);
    CHECK(std::count_if(a.scene.nodes.begin(), a.scene.nodes.end(), [](const SceneNode& n) { return n.skin == 0; }) == 1);
    REQUIRE(a.weights.size() == 1);
    CHECK(a.weights[0].joints.size() == 1728);
    CHECK(a.weights[0].weights.size() == 1728);
    REQUIRE(a.scene.materials.size() == 1);
    CHECK(a.scene.materials[0].roughness == doctest::Approx(0.58));
}

TEST_CASE("two materials on one mesh: a triangle object and a point object, four glTF textures sent as two") {
    const char* f = "gltf/SphereTwoMaterials/sphere_two_materials_mesh_and_point_cloud.gltf";
    if (!have_sample(f)) return;
    Asset a = load_asset(sample(f));
    REQUIRE(a.scene.meshes.size() == 1);
    REQUIRE(a.scene.meshes[0].primitives.size() == 2);
    REQUIRE(a.objects.size() == 2);
    CHECK(!a.objects[0].is_point_set);
    CHECK(a.objects[1].is_point_set);
    REQUIRE(a.scene.materials.size() == 2);
    CHECK(a.scene.materials[1].alpha_mode == AlphaMode::Blend);
    CHECK(a.scene.materials[0].normal_texture.texture != kNone);
    CHECK(a.scene.textures.size() == 2);
    CHECK(any_warning(a, "TANGENT"));
}

TEST_CASE("a Draco-compressed glTF gives the same object as the plain one") {
    if (!have_sample("gltf/Box-glb/Box.glb") || !have_sample("gltf/Box-glb/Box_Draco.glb")) return;
    Asset plain = load_asset(sample("gltf/Box-glb/Box.glb"));
    Asset draco = load_asset(sample("gltf/Box-glb/Box_Draco.glb"));
    REQUIRE(plain.objects.size() == 1);
    REQUIRE(draco.objects.size() == 1);
    CHECK(plain.objects[0].triangles.size() == draco.objects[0].triangles.size());
    CHECK(plain.scene.nodes.size() == draco.scene.nodes.size());
    CHECK(plain.scene.materials.size() == draco.scene.materials.size());
}

TEST_CASE("a Draco glTF whose extension disagrees with its Draco data or accessors is refused, not a crash") {
    if (!have_sample("gltf/Box-glb/Box_Draco.glb")) return;
    // tinygltf's Draco path dereferenced a missing attribute as a null pointer (found by fuzz_readers).
    const auto raw = test::read_bytes(shared_samples() / "gltf/Box-glb/Box_Draco.glb");
    const std::string original(raw.begin(), raw.end());
    uint32_t json_length = 0;
    std::memcpy(&json_length, original.data() + 12, 4);
    const auto doc = nlohmann::json::parse(original.substr(20, json_length));
    const std::string rest = original.substr(20 + json_length);
    auto dir = test::scratch_dir("draco_checks");
    auto with = [&](const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
        nlohmann::json j = doc;
        edit(j);
        std::string text = j.dump();
        while (text.size() % 4) text.push_back(' ');
        std::string glb = original.substr(0, 12);
        const uint32_t length = uint32_t(text.size()), type = 0x4E4F534Au;
        glb.append(reinterpret_cast<const char*>(&length), 4).append(reinterpret_cast<const char*>(&type), 4);
        glb += text + rest;
        const uint32_t total = uint32_t(glb.size());
        std::memcpy(glb.data() + 8, &total, 4);
        const auto path = dir / (name + ".glb");
        std::ofstream(path, std::ios::binary) << glb;
        try {
            load_asset(path.string());
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(with("same", [](nlohmann::json&) {}).empty());
    CHECK(with("missing_id", [](nlohmann::json& j) {
              j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 5;
          }).find("Draco attribute \"NORMAL\" (id 5): its Draco data has no attribute with that id") != std::string::npos);
    CHECK(with("no_accessor", [](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL"); })
              .find("\"NORMAL\": the primitive has no accessor for it") != std::string::npos);
    CHECK(with("bad_indices", [](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["indices"] = 40; })
              .find("its indices are not an accessor") != std::string::npos);
    CHECK(with("bad_type", [](nlohmann::json& j) { j["accessors"][1]["componentType"] = 1234; })
              .find("its accessor has no valid componentType") != std::string::npos);
}

TEST_CASE("an OBJ becomes one node with one mesh and no material") {
    if (!have_sample("meshes/woody.obj")) return;
    Asset a = load_asset(sample("meshes/woody.obj"));
    REQUIRE(a.scene.nodes.size() == 1);
    CHECK(a.scene.nodes[0].name == "woody");
    CHECK(a.scene.nodes[0].mesh == 0);
    REQUIRE(a.scene.meshes.size() == 1);
    CHECK(a.scene.meshes[0].primitives.size() == a.objects.size());
    CHECK(a.scene.materials.empty());
}

TEST_CASE("an image in a data: URI is kept byte for byte, a GIF is dropped with a warning") {
    auto dir = ellicast::test::scratch_dir("asset_input_images");
    // The smallest valid PNG signature + IHDR is enough: images are carried, not decoded.
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0, 0, 0, 0x90, 0x77, 0x53, 0xDE};
    spit(dir / "png.gltf", triangle_gltf(R"({"uri":"data:image/png;base64,)" + base64(png) + R"("})"));
    Asset a = load_asset((dir / "png.gltf").string());
    REQUIRE(a.scene.textures.size() == 1);
    CHECK(a.scene.textures[0].image == png);
    CHECK(a.scene.materials[0].base_color_texture.texture == 0);

    std::vector<uint8_t> gif = {'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0, 0, 0, 0, ';'};
    spit(dir / "pic.gif", std::string(gif.begin(), gif.end()));
    spit(dir / "gif.gltf", triangle_gltf(R"({"uri":"pic.gif"})"));
    Asset g = load_asset((dir / "gif.gltf").string());
    CHECK(g.scene.textures.empty());
    CHECK(g.scene.materials[0].base_color_texture.texture == kNone);
    CHECK(any_warning(g, "neither PNG nor JPEG"));

    spit(dir / "missing.gltf", triangle_gltf(R"({"uri":"nowhere.png"})"));
    Asset m = load_asset((dir / "missing.gltf").string());
    CHECK(m.scene.textures.empty());
    CHECK(any_warning(m, "could not be read"));
}

TEST_CASE("an image whose declared type (mimeType, data: URI, file name) is not what its bytes are is sent as "
          "what its bytes are, with a warning naming the image") {
    auto dir = ellicast::test::scratch_dir("asset_input_image_types");
    const std::vector<uint8_t>& jpeg = ellicast::samples::kJpegBaseline16;
    const std::vector<uint8_t> png = {  // a whole 1x1 PNG: IHDR, IDAT, IEND
        0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xDE, 0x00, 0x00, 0x00,
        0x0C, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0xC9,
        0xFE, 0x92, 0xEF, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
    struct Case {
        const char* file;
        std::string image_json;
        const std::vector<uint8_t>& bytes;
        ImageType type;
        const char* warning;  // nullptr: none
    };
    spit(dir / "really_jpeg.png", std::string(jpeg.begin(), jpeg.end()));
    spit(dir / "really_png.jpg", std::string(png.begin(), png.end()));
    spit(dir / "picture.jpg", std::string(jpeg.begin(), jpeg.end()));
    const Case cases[] = {
        {"jpeg_as_png.gltf", R"({"uri":"data:image/png;base64,)" + base64(jpeg) + R"("})", jpeg, ImageType::Jpeg,
         "image 0 is declared image/png but its bytes are a JPEG file; sent as JPEG (image/jpeg)"},
        {"png_as_jpeg.gltf", R"({"uri":"data:image/jpeg;base64,)" + base64(png) + R"("})", png, ImageType::Png,
         "image 0 is declared image/jpeg but its bytes are a PNG file; sent as PNG (image/png)"},
        {"named_png.gltf", R"({"uri":"really_jpeg.png"})", jpeg, ImageType::Jpeg,
         "image 0 (really_jpeg.png) is named like a PNG file but its bytes are a JPEG file; sent as JPEG (image/jpeg)"},
        {"named_jpeg.gltf", R"({"uri":"really_png.jpg"})", png, ImageType::Png,
         "image 0 (really_png.jpg) is named like a JPEG file but its bytes are a PNG file; sent as PNG (image/png)"},
        {"external_declared_png.gltf", R"({"uri":"picture.jpg","mimeType":"image/png"})", jpeg, ImageType::Jpeg,
         "image 0 (picture.jpg) is declared image/png but its bytes are a JPEG file; sent as JPEG (image/jpeg)"},
        {"declared_mime_wins.gltf", R"({"uri":"really_jpeg.png","mimeType":"image/jpeg"})", jpeg, ImageType::Jpeg, nullptr},
        {"jpeg.gltf", R"({"uri":"picture.jpg"})", jpeg, ImageType::Jpeg, nullptr},
    };
    for (const Case& c : cases) {
        const std::string file = c.file;
        CAPTURE(file);
        spit(dir / file, triangle_gltf(c.image_json));
        Asset a = load_asset((dir / file).string());
        REQUIRE(a.scene.textures.size() == 1);
        CHECK(a.scene.textures[0].image == c.bytes);
        CHECK(a.scene.textures[0].info.image_type == c.type);
        CHECK(a.scene.materials[0].base_color_texture.texture == 0);
        if (c.warning) {
            REQUIRE(a.warnings.size() == 1);
            CHECK(a.warnings[0] == (dir / file).string() + ": " + c.warning);
        } else {
            CHECK(a.warnings.empty());
        }
    }
}

TEST_CASE("a JPEG cut off anywhere never crashes: cut in its header it is not sent, cut in its image data it is "
          "sent as it is, each time with a warning naming the image and the byte") {
    auto dir = ellicast::test::scratch_dir("asset_input_truncated_jpeg");
    for (const std::vector<uint8_t>* jpeg : {&ellicast::samples::kJpegBaseline16, &ellicast::samples::kJpegProgressive16}) {
        // The first scan's data starts after its SOS segment: from there on a viewer can show something.
        size_t data_start = 0;
        for (size_t i = 2; i + 3 < jpeg->size() && !data_start; ++i)
            if ((*jpeg)[i] == 0xFF && (*jpeg)[i + 1] == 0xDA) data_start = i + 2 + ((*jpeg)[i + 2] << 8 | (*jpeg)[i + 3]);
        REQUIRE(data_start > 100);
        for (size_t n = 1; n < jpeg->size(); ++n) {
            CAPTURE(n);
            const std::vector<uint8_t> cut(jpeg->begin(), jpeg->begin() + long(n));
            spit(dir / "cut.jpg", std::string(cut.begin(), cut.end()));
            spit(dir / "cut.gltf", triangle_gltf(R"({"uri":"cut.jpg"})"));
            Asset a = load_asset((dir / "cut.gltf").string());
            REQUIRE(a.warnings.size() == 1);
            const std::string& w = a.warnings[0];
            CHECK(w.rfind((dir / "cut.gltf").string() + ": image 0 (cut.jpg)", 0) == 0);
            if (n < 3) {
                CHECK(w.find("neither PNG nor JPEG") != std::string::npos);
                CHECK(a.scene.textures.empty());
            } else if (n < data_start) {
                CHECK_MESSAGE(w.find("is truncated at byte " + std::to_string(n)) != std::string::npos, w);
                CHECK(w.find("no viewer can open it, so its texture is not sent") != std::string::npos);
                CHECK(a.scene.textures.empty());
                CHECK(a.scene.materials[0].base_color_texture.texture == kNone);  // the factors alone
            } else {
                CHECK(w.find("sent as it is") != std::string::npos);
                REQUIRE(a.scene.textures.size() == 1);
                CHECK(a.scene.textures[0].image == cut);
            }
        }
    }
}

TEST_CASE("a PNG cut off in its signature or IHDR chunk is not sent, one cut off after it is sent as it is, with a "
          "warning naming the image") {
    auto dir = ellicast::test::scratch_dir("asset_input_truncated_png");
    const std::vector<uint8_t> png = {  // a whole 1x1 PNG: IHDR (bytes 8..32), IDAT, IEND
        0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xDE, 0x00, 0x00, 0x00,
        0x0C, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0xC9,
        0xFE, 0x92, 0xEF, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
    for (size_t n = 1; n <= png.size(); ++n) {
        CAPTURE(n);
        const std::vector<uint8_t> cut(png.begin(), png.begin() + long(n));
        spit(dir / "cut.gltf", triangle_gltf(R"({"uri":"data:image/png;base64,)" + base64(cut) + R"("})"));
        Asset a = load_asset((dir / "cut.gltf").string());
        if (n == png.size()) {
            CHECK(a.warnings.empty());
            CHECK(a.scene.textures.size() == 1);
            continue;
        }
        REQUIRE(a.warnings.size() == 1);
        const std::string& w = a.warnings[0];
        CHECK(w.rfind((dir / "cut.gltf").string() + ": image 0", 0) == 0);
        if (n < 8) {
            CHECK(w.find("neither PNG nor JPEG") != std::string::npos);
            CHECK(a.scene.textures.empty());
        } else if (n < 33) {
            CHECK_MESSAGE(w.find("no viewer can open it, so its texture is not sent") != std::string::npos, w);
            CHECK(a.scene.textures.empty());
        } else {
            CHECK_MESSAGE(w.find("sent as it is") != std::string::npos, w);
            REQUIRE(a.scene.textures.size() == 1);
            CHECK(a.scene.textures[0].image == cut);
        }
    }
}

TEST_CASE("load_asset refuses missing, empty and broken files with a message naming them") {
    auto dir = ellicast::test::scratch_dir("asset_input_errors");
    auto message = [](const std::string& path) -> std::string {
        try {
            load_asset(path);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    CHECK(message((dir / "absent.glb").string()).find("no such file") != std::string::npos);
    spit(dir / "empty.gltf", "");
    CHECK(message((dir / "empty.gltf").string()).find("empty") != std::string::npos);
    spit(dir / "broken.gltf", "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[");
    CHECK(message((dir / "broken.gltf").string()).find("broken.gltf") != std::string::npos);
    if (have_sample("gltf/Box-glb/Box.glb")) {
        auto bytes = test::read_bytes(shared_samples() / "gltf/Box-glb/Box.glb");
        bytes.resize(bytes.size() / 2);
        spit(dir / "half.glb", std::string(bytes.begin(), bytes.end()));
        CHECK(message((dir / "half.glb").string()).find("half.glb") != std::string::npos);
    }
}

namespace {

// The Duck's glTF (with its .bin and texture next to it in `dir`) changed by `edit`, loaded.
Asset edited_duck(const std::filesystem::path& dir, const std::string& name,
                  const std::function<void(nlohmann::json&)>& edit) {
    for (const char* file : {"Duck0.bin", "DuckCM.png"})
        if (!std::filesystem::exists(dir / file)) std::filesystem::copy_file(shared_samples() / "gltf/Duck" / file, dir / file);
    auto json = nlohmann::json::parse(test::read_bytes(shared_samples() / "gltf/Duck/Duck.gltf"));
    edit(json);
    spit(dir / (name + ".gltf"), json.dump());
    return load_asset((dir / (name + ".gltf")).string());
}

TEST_CASE("indices that are negative or not integers are refused, not cast (found by fuzz_readers)") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    auto dir = test::scratch_dir("signed_indices");
    // The indices read as signed shorts from the positions' bytes: float bit patterns, many negative.
    std::string error;
    try {
        edited_duck(dir, "signed", [](nlohmann::json& j) {
            auto& prim = j["meshes"][0]["primitives"][0];
            const int indices = prim["indices"], position = prim["attributes"]["POSITION"];
            j["accessors"][indices]["bufferView"] = j["accessors"][position]["bufferView"];
            j["accessors"][indices]["byteOffset"] = 0;
            j["accessors"][indices]["componentType"] = 5122;
            j["accessors"][indices]["count"] = 300;
        });
    } catch (const InputError& e) {
        error = e.what();
    }
    CHECK(error.find("is not a vertex number (indices must be unsigned integers)") != std::string::npos);
}

// What a receiver writes of `a` (write_asset), checked by the Khronos validator, read back.
Asset written_and_read(const Asset& a, const std::filesystem::path& path) {
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(path.string(), a, {}, warnings, error), error);
    CHECK(warnings.empty());
    int errors = -1;
    std::string report;
    if (ellicast::test::validate_gltf(path, errors, report)) CHECK_MESSAGE(errors == 0, report);
    return load_asset(path.string());
}

}  // namespace

TEST_CASE("a texture on TEXCOORD_1 travels with the set (format 1.14), one selected by a texture transform's texCoord "
          "is not sent: the warning names the material and slot, the material keeps its factors, and the file is valid") {
    const char* f = "gltf/Duck/Duck.gltf";
    if (!have_sample(f)) return;
    auto dir = ellicast::test::scratch_dir("asset_input_texcoord1");
    Asset plain = load_asset(sample(f));
    REQUIRE(plain.scene.textures.size() == 1);
    auto to_set1 = [](nlohmann::json& j) {  // the same coordinates as TEXCOORD_1, which the texture uses
        auto& attributes = j["meshes"][0]["primitives"][0]["attributes"];
        attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
        j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
    };
    auto through_transform = [](nlohmann::json& j) {  // TEXCOORD_1 selected by the transform's texCoord
        auto& attributes = j["meshes"][0]["primitives"][0]["attributes"];
        attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
        j["extensionsUsed"] = {"KHR_texture_transform"};
        j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = {
            {"texCoord", 1}};
    };
    {
        // Format 1.14: the set travels, and the texture with it.
        Asset a = edited_duck(dir, "set1", to_set1);
        CHECK_FALSE(any_warning(a, "TEXCOORD_1"));
        REQUIRE(a.scene.textures.size() == 1);
        CHECK(a.scene.materials[0].base_color_texture.texture == 0);
        CHECK(a.scene.materials[0].base_color_texture.texcoord == 1);
        REQUIRE(a.objects[0].texcoord_sets.size() == 1);
        CHECK(a.objects[0].texcoord_sets[0] == a.objects[0].texcoords);
        Asset back = written_and_read(a, dir / "set1_out.glb");
        REQUIRE(back.scene.textures.size() == 1);
        CHECK(back.scene.materials[0].base_color_texture.texcoord == 1);
        REQUIRE(back.objects[0].texcoord_sets.size() == 1);
    }
    for (const auto& [name, edit, needle] :
         {std::tuple{std::string("transform_set1"), std::function<void(nlohmann::json&)>(through_transform),
                     ": its KHR_texture_transform selects another texture-coordinate set"}}) {
        CAPTURE(name);
        Asset a = edited_duck(dir, name, edit);
        CHECK(any_warning(a, "material 0 (blinn3-fx) baseColorTexture" + std::string(needle)));
        CHECK(any_warning(a, "this texture is not sent (the material keeps its factors and its other textures)"));
        CHECK(a.scene.textures.empty());  // its only use was this reference: the image is not sent either
        REQUIRE(a.scene.materials.size() == 1);
        CHECK(a.scene.materials[0].base_color_texture.texture == kNone);
        CHECK(a.scene.materials[0].base_color == plain.scene.materials[0].base_color);
        CHECK(a.scene.materials[0].roughness == plain.scene.materials[0].roughness);
        CHECK(a.scene.meshes[0].primitives[0].material == 0);
        Asset back = written_and_read(a, dir / (std::string(name) + "_out.glb"));
        REQUIRE(back.scene.materials.size() == 1);
        CHECK(back.scene.meshes[0].primitives[0].material == 0);
        CHECK(back.scene.textures.empty());
    }
}

TEST_CASE("a material's KHR_texture_transform travels in its patch (format 1.3): the texture coordinates are sent as "
          "they are, each texture keeps its own transform, and the receiver's file has them") {
    const char* f = "gltf/Duck/Duck.gltf";
    if (!have_sample(f)) return;
    auto dir = ellicast::test::scratch_dir("asset_input_texture_transform");
    Asset plain = load_asset(sample(f));
    REQUIRE(plain.objects.size() == 1);
    REQUIRE(plain.objects[0].has_texcoords());
    CHECK(plain.scene.materials[0].extensions.empty());
    const double pi = std::acos(-1.0);
    const nlohmann::json base_transform = {{"offset", {0, 1}}, {"rotation", pi / 2}, {"scale", {0.5, 0.5}}};
    const nlohmann::json emissive_transform = {{"scale", {3, 3}}};
    Asset a = edited_duck(dir, "transform", [&](nlohmann::json& j) {
        j["extensionsUsed"] = {"KHR_texture_transform"};
        auto& material = j["materials"][0];
        // The extension's own example (the lower left quadrant, turned a quarter), and another
        // transform on another texture of the same material.
        material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = base_transform;
        material["emissiveTexture"] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", emissive_transform}}}};
    });
    CHECK(!any_warning(a, "KHR_texture_transform"));
    REQUIRE(a.scene.textures.size() == 1);
    CHECK(a.scene.textures[0].image == plain.scene.textures[0].image);
    CHECK(a.scene.materials[0].base_color_texture.texture == 0);
    CHECK(a.scene.materials[0].emissive_texture.texture == 0);
    REQUIRE(a.objects.size() == 1);
    CHECK(a.objects[0].texcoords == plain.objects[0].texcoords);
    CHECK(a.objects[0].positions == plain.objects[0].positions);
    const nlohmann::json patch = nlohmann::json::parse(a.scene.materials[0].extensions);
    const nlohmann::json expected = {
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"extensions", {{"KHR_texture_transform", base_transform}}}}}}},
        {"emissiveTexture", {{"extensions", {{"KHR_texture_transform", emissive_transform}}}}}};
    CHECK(patch == expected);
    // The receiver's file: the same coordinates, both transforms, the extension declared; valid.
    Asset back = written_and_read(a, dir / "transform_out.glb");
    REQUIRE(back.scene.textures.size() == 1);
    CHECK(back.scene.materials[0].base_color_texture.texture == 0);
    CHECK(back.objects[0].texcoords == a.objects[0].texcoords);
    CHECK(nlohmann::json::parse(back.scene.materials[0].extensions) == expected);
}

TEST_CASE("glTF animation channels: every interpolation and a normalized rotation travel, and the channels the format cannot carry are named") {
    // One triangle at node 0, animated by six channels over one buffer:
    //   0 translation STEP (2 keys)          1 scale CUBICSPLINE (2 keys: 6 outputs)
    //   2 translation again (glTF forbids)   3 morph target weights (of a mesh without targets)
    //   4 rotation LINEAR, outputs as normalized shorts (KHR_mesh_quantization allows)
    //   5 scale with times that go back
    std::vector<uint8_t> bin;
    auto put = [&](const void* p, size_t n) {  // resize + memcpy: GCC 12 warns falsely on insert here
        const size_t at = bin.size();
        bin.resize(at + n);
        std::memcpy(bin.data() + at, p, n);
        while (bin.size() % 4) bin.push_back(0);
    };
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float times[2] = {0, 1}, back[2] = {1, 0.5f};
    const float moves[6] = {0, 0, 0, 1, 2, 3};
    float cubic[18] = {};
    for (int i = 0; i < 18; ++i) cubic[i] = float(i % 3 == 1) + 0.5f * float(i / 9);
    const int16_t quat[8] = {0, 0, 0, 32767, 0, 23170, 0, 23170};
    put(pos, 36);     // 0
    put(times, 8);    // 36
    put(moves, 24);   // 44
    put(cubic, 72);   // 68
    put(quat, 16);    // 140
    put(back, 8);     // 156 .. 164
    const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"name":"tri"}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},
{"bufferView":2,"componentType":5126,"count":2,"type":"VEC3"},
{"bufferView":3,"componentType":5126,"count":6,"type":"VEC3"},
{"bufferView":4,"componentType":5122,"normalized":true,"count":2,"type":"VEC4"},
{"bufferView":5,"componentType":5126,"count":2,"type":"SCALAR","min":[0.5],"max":[1]}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":8},
{"buffer":0,"byteOffset":44,"byteLength":24},{"buffer":0,"byteOffset":68,"byteLength":72},
{"buffer":0,"byteOffset":140,"byteLength":16},{"buffer":0,"byteOffset":156,"byteLength":8}],
"animations":[{"name":"Everything","samplers":[
{"input":1,"output":2,"interpolation":"STEP"},{"input":1,"output":3,"interpolation":"CUBICSPLINE"},
{"input":1,"output":4},{"input":5,"output":2}],
"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}},{"sampler":1,"target":{"node":0,"path":"scale"}},
{"sampler":0,"target":{"node":0,"path":"translation"}},{"sampler":0,"target":{"node":0,"path":"weights"}},
{"sampler":2,"target":{"node":0,"path":"rotation"}},{"sampler":3,"target":{"node":0,"path":"scale"}}]}],
"buffers":[{"byteLength":)" + std::to_string(bin.size()) + R"(,"uri":"data:application/octet-stream;base64,)" +
                             base64(bin) + R"("}]})";
    const auto dir = test::scratch_dir("animation_channels");
    spit(dir / "animated.gltf", gltf);
    const Asset a = load_asset((dir / "animated.gltf").string());
    REQUIRE(a.scene.animations.size() == 1);
    const SceneAnimation& anim = a.scene.animations[0];
    CHECK(anim.name == "Everything");
    REQUIRE(anim.tracks.size() == 3);
    CHECK(anim.tracks[0].path == AnimationPath::Translation);
    CHECK(anim.tracks[0].interpolation == Interpolation::Step);
    CHECK(anim.tracks[0].values == std::vector<float>(moves, moves + 6));
    CHECK(anim.tracks[1].path == AnimationPath::Scale);
    CHECK(anim.tracks[1].interpolation == Interpolation::CubicSpline);
    CHECK(anim.tracks[1].values.size() == 18);
    CHECK(anim.tracks[2].path == AnimationPath::Rotation);
    REQUIRE(anim.tracks[2].values.size() == 8);
    CHECK(anim.tracks[2].values[3] == doctest::Approx(1.0));
    CHECK(anim.tracks[2].values[5] == doctest::Approx(0.70710678).epsilon(1e-4));
    CHECK(any_warning(a, "channel 2 (a second channel on the same node and path)"));
    // The mesh has no morph targets: a channel on its weights has nothing to move (format 1.6 carries
    // weights channels of meshes with targets, tests/test_morph_assets.cpp).
    CHECK(any_warning(a, "channel 3: it moves morph target weights of a node whose mesh's morph targets are not sent"));
    CHECK(any_warning(a, "channel 5: its key times are not finite, non-negative and strictly increasing"));
}

TEST_CASE("the command line says a warning of one kind once, naming the first part and counting the others, and --verbose lists each") {
    using namespace ellicast::test;
    namespace fs = std::filesystem;
    // Five meshes, each with one zero-area triangle the reader drops (one warning a primitive).
    Asset asset = load_asset((source_dir() / "samples" / "trefoil.obj").string());
    REQUIRE(asset.objects.size() == 1);
    Mesh part = asset.objects[0];
    const uint32_t base = uint32_t(part.positions.size());
    for (float x : {0.0f, 0.5f, 1.0f}) part.positions.push_back({x, x, x});  // three points on a line
    if (part.has_normals()) part.normals.resize(part.positions.size(), {0, 0, 1});
    if (part.has_texcoords()) part.texcoords.resize(part.positions.size(), {0, 0});
    part.triangles.push_back({base, base + 1, base + 2});
    asset = Asset{};
    for (uint16_t i = 0; i < 5; ++i) {
        asset.objects.push_back(part);
        SceneMesh mesh;
        mesh.index = i;
        mesh.name = "part" + std::to_string(i);
        mesh.primitives.push_back({i, kNone});
        asset.scene.meshes.push_back(mesh);
        SceneNode node;
        node.index = i;
        node.mesh = i;
        node.name = mesh.name;
        node.translation = {3.0f * i, 0, 0};
        asset.scene.nodes.push_back(node);
    }
    const fs::path dir = scratch_dir("grouped_warnings");
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset((dir / "parts.glb").string(), asset, AssetWriteOptions{}, warnings, error), error);
    int status = 0;
    const std::string exe = shell_quoted(ellicast_exe().string()) + " encode -q " + shell_quoted((dir / "parts.glb").string()) +
                            " -o " + shell_quoted((dir / "parts.ellc").string());
    std::string log = run_command(exe, status);
    REQUIRE_MESSAGE(status == 0, log);
    auto count = [](const std::string& text, const std::string& needle) {
        size_t n = 0;
        for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
        return n;
    };
    CHECK(count(log, "degenerate (zero-area) triangles dropped") == 1);
    CHECK(log.find("(and 4 more like it: part1 primitive 0, part2 primitive 0, part3 primitive 0, part4 primitive 0; "
                   "--verbose lists each)") != std::string::npos);
    log = run_command(exe + " --verbose", status);
    REQUIRE_MESSAGE(status == 0, log);
    CHECK(count(log, "degenerate (zero-area) triangles dropped") == 5);
    CHECK(log.find("more like it") == std::string::npos);
}

TEST_CASE("each committed Khronos sample says exactly the warnings a user can act on, and nothing false") {
    using namespace ellicast::test;
    // Reading and encoding at the command line's defaults; the file's path is left out of each line.
    // UnlitTest requires KHR_materials_unlit, which travels: no "ignored" warning (there was one).
    const std::vector<std::pair<std::string, std::vector<std::string>>> expected = {
        {"AnimatedMorphCube/AnimatedMorphCube.gltf",
         {"Cube primitive 0: the TANGENT displacements of its morph targets are not sent",
          "vertex attribute(s) TANGENT not sent (ellicast carries POSITION, NORMAL, TEXCOORD_0 to TEXCOORD_7 and COLOR_0; "
          "TANGENT is rebuilt on output for normal-mapped materials from the normals and texture coordinates)"}},
        {"Cameras/Cameras.gltf", {}},  // format 1.10: both cameras travel
        {"SimpleMorph/SimpleMorph.gltf", {}},
        {"SimpleSkin/simple_skin.gltf", {}},
        {"SimpleSparseAccessor/SimpleSparseAccessor.gltf", {}},
        {"TextureTransformTest/TextureTransformTest.gltf", {}},
        {"UnlitTest/UnlitTest.gltf", {}},
    };
    for (const auto& [name, want] : expected) {
        CAPTURE(name);
        const std::string path = (source_dir() / "samples" / "khronos" / name).string();
        Asset asset = load_asset(path);
        EncodedAsset encoded;
        std::string error;
        REQUIRE_MESSAGE(encode_asset(asset, EncodeOptions{}, 1, true, encoded, error), error);
        std::vector<std::string> said = asset.warnings;
        said.insert(said.end(), encoded.encoded.warnings.begin(), encoded.encoded.warnings.end());
        for (auto& w : said)
            if (w.rfind(path + ": ", 0) == 0) w = w.substr(path.size() + 2);
        CHECK(said == want);
    }
}
