// Writing scenes (write_asset) and rebuilding them from what a receiver has (received_asset): the
// real samples come back with their scene graph, materials and texture files; Draco and quantized
// output is read by the Khronos validator, glTF-Transform and Draco's own decoder; whatever is
// missing or inconsistent is left out with a warning and the file stays valid.
#include "jpeg_images.h"
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_input.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <regex>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

bool any_of(const std::vector<std::string>& warnings, const std::string& needle) {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

void write_ok(const fs::path& path, const Asset& asset, const AssetWriteOptions& options,
              std::vector<std::string>* warnings_out = nullptr) {
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(path.string(), asset, options, warnings, error), error);
    if (warnings_out) *warnings_out = warnings;
}

void check_valid(const fs::path& path) {
    int errors = -1;
    std::string report;
    if (validate_gltf(path, errors, report)) CHECK_MESSAGE(errors == 0, path.string() << ": " << report);
}

// The JSON and BIN chunks of a GLB.
struct Glb {
    nlohmann::json json;
    std::vector<uint8_t> bin;
};

Glb read_glb(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> b{std::istreambuf_iterator<char>(in), {}};
    REQUIRE(b.size() >= 20);
    uint32_t json_length;
    std::memcpy(&json_length, b.data() + 12, 4);
    REQUIRE(20 + json_length <= b.size());
    Glb glb;
    glb.json = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + json_length);
    size_t bin_at = 20 + json_length;
    if (bin_at + 8 <= b.size()) {
        uint32_t bin_length;
        std::memcpy(&bin_length, b.data() + bin_at, 4);
        REQUIRE(bin_at + 8 + bin_length <= b.size());
        glb.bin.assign(b.begin() + long(bin_at + 8), b.begin() + long(bin_at + 8 + bin_length));
    }
    return glb;
}

// For each mesh primitive of `in`, the object of `out` at the same place has the same geometry.
void check_same_objects(const Asset& in, const Asset& out) {
    for (size_t n = 0; n < in.scene.nodes.size(); ++n) {
        if (in.scene.nodes[n].mesh == kNone) continue;
        const auto& pa = in.scene.meshes[in.scene.nodes[n].mesh].primitives;
        const auto& pb = out.scene.meshes[out.scene.nodes[n].mesh].primitives;
        REQUIRE(pa.size() == pb.size());
        for (size_t p = 0; p < pa.size(); ++p) {
            const Mesh& a = in.objects[pa[p].object];
            const Mesh& b = out.objects[pb[p].object];
            CAPTURE(a.name);
            REQUIRE(a.positions.size() == b.positions.size());
            CHECK(a.triangles == b.triangles);
            CHECK(a.positions == b.positions);
            CHECK(a.is_point_set == b.is_point_set);
            CHECK(a.has_texcoords() == b.has_texcoords());
            CHECK(a.has_colors() == b.has_colors());
        }
    }
}

// A valid 1x1 PNG file.
std::vector<uint8_t> one_pixel_png() {
    return {0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00,
            0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xDE, 0x00,
            0x00, 0x00, 0x0C, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xCF, 0xC0, 0x00, 0x00, 0x03, 0x01,
            0x01, 0x00, 0xC9, 0xFE, 0x92, 0xEF, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60,
            0x82};
}

double diagonal(const std::vector<Mesh>& meshes) {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& m : meshes)
        for (const auto& p : m.positions)
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

}  // namespace

TEST_CASE("every glTF sample written back keeps its scene, its texture files and its geometry, and is valid") {
    auto dir = scratch_dir("asset_output_plain");
    for (const char* f : kGltfSamples) {
        if (!have_sample(f)) continue;
        CAPTURE(f);
        Asset in = load_asset(sample(f));
        for (const char* ext : {".glb", ".gltf"}) {
            fs::path out = dir / (fs::path(f).stem().string() + ext);
            write_ok(out, in, {});
            check_valid(out);
            Asset back = load_asset(out.string());
            check_same_scene(in, back);
            check_same_objects(in, back);
        }
    }
}

TEST_CASE("--quantize writes KHR_mesh_quantization: valid, same world-space geometry within 16-bit steps") {
    auto dir = scratch_dir("asset_output_quantize");
    AssetWriteOptions options;
    options.quantize = true;
    for (const char* f : kGltfSamples) {
        if (!have_sample(f)) continue;
        CAPTURE(f);
        Asset in = load_asset(sample(f));
        fs::path out = dir / (fs::path(f).stem().string() + ".glb");
        write_ok(out, in, options);
        check_valid(out);
        Glb glb = read_glb(out);
        // Every POSITION is a normalized SHORT accessor, but for a skinned mesh's (the Fox's): written
        // plain, since the dequantizing wrapper node would not follow the skeleton.
        bool quantized = false;
        for (const auto& mesh : glb.json["meshes"])
            for (const auto& prim : mesh["primitives"]) {
                const auto& acc = glb.json["accessors"][prim["attributes"]["POSITION"].get<int>()];
                if (prim["attributes"].contains("JOINTS_0")) {
                    CHECK(acc["componentType"] == 5126);
                    continue;
                }
                quantized = true;
                CHECK(acc["componentType"] == 5122);
                CHECK(acc["normalized"] == true);
            }
        if (quantized) CHECK(glb.json["extensionsRequired"].dump().find("KHR_mesh_quantization") != std::string::npos);
        // The flattened world-space meshes agree with the input's, vertex for vertex.
        LoadResult a = load_gltf(sample(f));
        LoadResult b = load_gltf(out.string());
        REQUIRE(a.meshes.size() == b.meshes.size());
        const double tolerance = diagonal(a.meshes) * 2.0 / 32767.0;
        std::vector<bool> used(b.meshes.size(), false);
        for (const Mesh& ma : a.meshes) {
            double best = 1e300;
            size_t best_j = 0;
            for (size_t j = 0; j < b.meshes.size(); ++j) {
                const Mesh& mb = b.meshes[j];
                if (used[j] || mb.positions.size() != ma.positions.size() || mb.triangles != ma.triangles) continue;
                double worst = 0;
                for (size_t v = 0; v < ma.positions.size(); ++v)
                    for (int k = 0; k < 3; ++k)
                        worst = std::max(worst, std::abs(double(ma.positions[v][k]) - mb.positions[v][k]));
                if (worst < best) best = worst, best_j = j;
            }
            CAPTURE(ma.name);
            CHECK(best <= tolerance);
            used[best_j] = true;
        }
    }
}

// `in` through the stream with every packet, decoded at a coarse grid: what a receiver writes.
Asset decoded(const Asset& in) {
    EncodeOptions encoding;
    encoding.max_ellipsoids = 60;
    encoding.coverage = 0.8;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, encoding, 1, true, encoded, error), error);
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i) REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
    DecodeOptions decoding;
    decoding.grid_resolution = 24;
    Asset out;
    StreamDecodeReport report;
    REQUIRE_MESSAGE(decode_asset(stream, decoding, out, report, error), error);
    return out;
}

TEST_CASE("--draco output, of a sample and of a decoded stream, is read by the validator, glTF-Transform and "
          "draco_decoder with the counts it declares") {
    const char* f = "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf";
    const char* points = "gltf/SphereTwoMaterials/sphere_two_materials_mesh_and_point_cloud.gltf";
    const char* duck = "gltf/Duck/Duck.gltf";
    if (!have_sample(f) || !have_sample(points) || !have_sample(duck)) return;
    auto dir = scratch_dir("asset_output_draco");
    AssetWriteOptions options;
    options.draco = true;
    for (const char* file : {f, points, duck}) {
        CAPTURE(file);
        const bool through_stream = file == duck;  // what `ellicast decode --draco` writes
        Asset in = through_stream ? decoded(load_asset(sample(file))) : load_asset(sample(file));
        fs::path out = dir / (fs::path(file).stem().string() + ".glb");
        write_ok(out, in, options);
        check_valid(out);
        Glb glb = read_glb(out);
        CHECK(glb.json["extensionsUsed"].dump().find("KHR_draco_mesh_compression") != std::string::npos);
        CHECK(glb.json["extensionsRequired"].dump().find("KHR_draco_mesh_compression") != std::string::npos);
        // Our own reader decodes it (tinygltf + Draco): same scene, same number of triangles.
        Asset back = load_asset(out.string());
        check_same_scene(in, back);
        size_t tri_in = 0, tri_out = 0;
        for (const auto& m : in.objects) tri_in += m.triangles.size();
        for (const auto& m : back.objects) tri_out += m.triangles.size();
        CHECK(tri_in == tri_out);

        // Every compressed primitive, cut out of the GLB, decodes with draco_decoder to the point and
        // face counts of its accessors; point primitives stay uncompressed (the extension is for triangles).
        int compressed = 0;
        for (const auto& mesh : glb.json["meshes"])
            for (const auto& prim : mesh["primitives"]) {
                if (!prim.contains("extensions")) {
                    CHECK(prim["mode"] == 0);
                    continue;
                }
                const auto& ext = prim["extensions"]["KHR_draco_mesh_compression"];
                const auto& view = glb.json["bufferViews"][ext["bufferView"].get<int>()];
                size_t offset = view.value("byteOffset", 0), length = view["byteLength"];
                REQUIRE(offset + length <= glb.bin.size());
                fs::path drc = dir / ("prim" + std::to_string(compressed++) + ".drc");
                fs::path ply = drc;
                ply.replace_extension(".ply");
                {
                    std::ofstream o(drc, std::ios::binary);
                    o.write(reinterpret_cast<const char*>(glb.bin.data() + offset), long(length));
                }
                if (std::system("command -v draco_decoder > /dev/null 2>&1") != 0) {
                    MESSAGE("skipped: draco_decoder is not installed (Debian package draco)");
                    continue;
                }
                int status = 0;
                std::string log = run_command("draco_decoder -i '" + drc.string() + "' -o '" + ply.string() + "'", status);
                REQUIRE_MESSAGE(status == 0, log);
                std::ifstream header(ply, std::ios::binary);
                size_t vertices = 0, faces = 0;
                for (std::string line; std::getline(header, line) && line != "end_header";) {
                    std::sscanf(line.c_str(), "element vertex %zu", &vertices);
                    std::sscanf(line.c_str(), "element face %zu", &faces);
                }
                const auto& pos = glb.json["accessors"][prim["attributes"]["POSITION"].get<int>()];
                const auto& idx = glb.json["accessors"][prim["indices"].get<int>()];
                CHECK(vertices == pos["count"].get<size_t>());
                CHECK(faces * 3 == idx["count"].get<size_t>());
            }
        CHECK(compressed > 0);

        if (have_node_package("@gltf-transform/cli")) {
            int status = 0;
            std::string report = run_command(
                "'" + (node_modules() / ".bin" / "gltf-transform").string() + "' inspect --format csv '" + out.string() + "'",
                status);
            REQUIRE_MESSAGE(status == 0, report);
            CHECK(report.find("KHR_draco_mesh_compression") != std::string::npos);
            // glTF-Transform decodes the Draco data: its vertex counts are those of our accessors.
            for (const auto& mesh : glb.json["meshes"]) {
                size_t count = 0;
                for (const auto& prim : mesh["primitives"])
                    count += glb.json["accessors"][prim["attributes"]["POSITION"].get<int>()]["count"].get<size_t>();
                std::string name = mesh.value("name", "");
                std::regex row("(^|\\n)[0-9]+," + std::regex_replace(name, std::regex("[.^$|()\\[\\]{}*+?\\\\]"), "\\$&") +
                               ",(\"[^\"]*\"|[A-Z_]+),[0-9]+,[0-9]+," + std::to_string(count) + ",");
                CHECK_MESSAGE(std::regex_search(report, row), name << " with " << count << " vertices not in\n" << report);
            }
        }
    }
}

TEST_CASE("a receiver writes what arrived: lost textures, materials, objects and scene packets give a valid glTF") {
    const char* f = "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf";
    if (!have_sample(f)) return;
    auto dir = scratch_dir("asset_output_loss");
    Asset in = load_asset(sample(f));
    ScenePackets packets;
    REQUIRE(packetize_scene(in.scene, 1200, 7, 0, packets) == Error::Ok);
    REQUIRE(packets.textures.size() > 2);

    auto receive = [&](bool scene, bool materials, size_t texture_fragments_lost, size_t lost_material) {
        ReceivedStream stream;
        if (scene)
            for (const auto& p : packets.scene) REQUIRE(stream.add_packet(p, 0) == Error::Ok);
        if (materials)
            for (size_t i = 0; i < packets.materials.size(); ++i)
                if (i != lost_material) REQUIRE(stream.add_packet(packets.materials[i], 0) == Error::Ok);
        for (size_t i = texture_fragments_lost; i < packets.textures.size(); ++i)
            REQUIRE(stream.add_packet(packets.textures[i], 0) == Error::Ok);
        for (const auto& p : packets.animations) REQUIRE(stream.add_packet(p, 0) == Error::Ok);
        return stream;
    };

    SUBCASE("everything arrived: the same scene") {
        Asset got = received_asset(receive(true, true, 0, 99), in.objects);
        CHECK(got.warnings.empty());
        fs::path out = dir / "all.glb";
        write_ok(out, got, {});
        check_valid(out);
        check_same_scene(in, load_asset(out.string()));
    }
    SUBCASE("a texture fragment lost: the materials using the texture are not shown, their primitives get the "
            "default material, the other materials are unchanged") {
        Asset got = received_asset(receive(true, true, 1, 99), in.objects);
        // The truck's body and wheels share the one texture: both wait for it, named with what arrived.
        CHECK(any_of(got.warnings, "material 0 (truck) is waiting for its baseColorTexture texture 0 ("));
        CHECK(any_of(got.warnings, "material 3 (wheels) is waiting for its baseColorTexture texture 0 ("));
        CHECK(any_of(got.warnings, " bytes arrived); its primitives get the default material"));
        CHECK(!any_of(got.warnings, "did not arrive"));  // the materials did arrive
        CHECK(got.scene.textures.empty());
        REQUIRE(got.scene.materials.size() == 2);
        CHECK(got.scene.materials[0].name == "glass");
        CHECK(got.scene.materials[1].name == "window_trim");
        fs::path out = dir / "no_texture.glb";
        write_ok(out, got, {});
        check_valid(out);
        Glb glb = read_glb(out);
        CHECK(!glb.json.contains("textures"));
        CHECK(!glb.json.contains("images"));
        REQUIRE(glb.json["meshes"].size() == 2);
        const auto& truck = glb.json["meshes"][0]["primitives"];
        REQUIRE(truck.size() == 3);
        CHECK(!truck[0].contains("material"));  // the body: default material
        CHECK(truck[1]["material"] == 0);        // glass
        CHECK(truck[2]["material"] == 1);        // window trim
        CHECK(!glb.json["meshes"][1]["primitives"][0].contains("material"));  // the wheels
        const auto& glass = glb.json["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"];
        for (int k = 0; k < 4; ++k) CHECK(glass[k].get<double>() == doctest::Approx(in.scene.materials[1].base_color[k]));
    }
    SUBCASE("a texture complete: the materials waiting for it are shown") {
        Asset got = received_asset(receive(true, true, 0, 99), in.objects);
        REQUIRE(got.scene.materials.size() == 4);
        CHECK(got.scene.materials[0].base_color_texture.texture == 0);
        CHECK(got.scene.materials[3].base_color_texture.texture == 0);
    }
    SUBCASE("a material lost: its primitives get the default material") {
        Asset got = received_asset(receive(true, true, 0, 1), in.objects);
        CHECK(any_of(got.warnings, "did not arrive"));
        CHECK(got.scene.materials.size() == 3);
        fs::path out = dir / "no_material.glb";
        write_ok(out, got, {});
        check_valid(out);
        Glb glb = read_glb(out);
        CHECK(!glb.json["meshes"][0]["primitives"][1].contains("material"));
    }
    SUBCASE("an object lost: it is left out; a mesh left without objects leaves its nodes") {
        std::vector<Mesh> objects = in.objects;
        objects[3] = Mesh{};  // the wheels: the only object of mesh 1, shown by two nodes
        objects[1] = Mesh{};  // one of the truck's three primitives
        Asset got = received_asset(receive(true, true, 0, 99), objects);
        fs::path out = dir / "no_object.glb";
        std::vector<std::string> warnings;
        write_ok(out, got, {}, &warnings);
        CHECK(any_of(warnings, "object 3) has not arrived"));
        CHECK(any_of(warnings, "nodes showing it are written without it"));
        check_valid(out);
        Glb glb = read_glb(out);
        CHECK(glb.json["nodes"].size() == 5);
        CHECK(glb.json["meshes"].size() == 1);
        CHECK(glb.json["meshes"][0]["primitives"].size() == 2);
        CHECK(!glb.json["nodes"][2].contains("mesh"));
        CHECK(!glb.json["nodes"][4].contains("mesh"));
    }
    SUBCASE("no SCENE packet: each object gets a node of its own, the file is still valid") {
        Asset got = received_asset(receive(false, true, 0, 99), in.objects);
        CHECK(any_of(got.warnings, "no SCENE packet"));
        fs::path out = dir / "no_scene.glb";
        write_ok(out, got, {});
        check_valid(out);
        Glb glb = read_glb(out);
        CHECK(glb.json["nodes"].size() == in.objects.size());
    }
}

TEST_CASE("write_asset leaves out what does not hold together and still writes a valid file") {
    auto dir = scratch_dir("asset_output_broken");
    Asset a;
    Mesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.triangles = {{0, 1, 2}};
    Mesh bad = tri;
    bad.triangles = {{0, 1, 7}};  // index beyond the vertices
    Mesh wrong_normals = tri;
    wrong_normals.normals = {{0, 0, 1}};  // one normal for three vertices
    a.objects = {tri, bad, wrong_normals, Mesh{}};
    SceneMesh m0{0, "ok", {{0, 0}, {1, kNone}, {2, 5}, {3, kNone}, {9, kNone}}, {}};
    SceneMesh m1{1, "empty", {{3, kNone}}, {}};
    a.scene.meshes = {m0, m1};
    SceneNode root;
    root.index = 0;
    root.mesh = 0;
    root.name = "root";
    SceneNode bad_mesh = root;
    bad_mesh.index = 1;
    bad_mesh.parent = 0;
    bad_mesh.mesh = 42;
    SceneNode loop_a = root, loop_b = root;
    loop_a.index = 2, loop_a.parent = 3, loop_a.mesh = 1;
    loop_b.index = 3, loop_b.parent = 2, loop_b.mesh = kNone;
    SceneNode bad_parent = root;
    bad_parent.index = 4;
    bad_parent.parent = 77;
    bad_parent.mesh = 1;
    SceneNode bad_rotation = root;
    bad_rotation.index = 5;
    bad_rotation.parent = 0;
    bad_rotation.rotation = {0, 0, 0, 0};
    a.scene.nodes = {root, bad_mesh, loop_a, loop_b, bad_parent, bad_rotation};
    Material mat;
    mat.base_color = {2, -1, 0.5f, 1};  // out of range: clamped
    mat.base_color_texture.texture = 0;
    mat.normal_texture.texture = 2;
    mat.normal_texture.texcoord = 1;  // format 1.14: a further set (the material is not whole anyway)
    mat.emissive_texture.texture = 1;
    a.scene.materials = {mat};
    SceneDescription::Texture garbage;
    garbage.image = {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'};
    SceneDescription::Texture empty;
    SceneDescription::Texture png;  // a valid 1x1 PNG
    png.image = one_pixel_png();
    a.scene.textures = {garbage, empty, png};

    for (AssetWriteOptions options : {AssetWriteOptions{}, AssetWriteOptions{.draco = true},
                                      AssetWriteOptions{.quantize = true}}) {
        fs::path out = dir / (options.draco ? "draco.glb" : options.quantize ? "quantize.glb" : "plain.glb");
        std::vector<std::string> warnings;
        write_ok(out, a, options, &warnings);
        check_valid(out);
        CHECK(any_of(warnings, "triangle index beyond its vertices"));
        CHECK(any_of(warnings, "NORMAL count differs"));
        CHECK(any_of(warnings, "material 5 is not available"));
        CHECK(any_of(warnings, "object 3) has not arrived"));
        CHECK(any_of(warnings, "object 9) does not exist"));
        CHECK(any_of(warnings, "names mesh 42"));
        CHECK(any_of(warnings, "parent cycle"));
        CHECK(any_of(warnings, "written as a root"));
        CHECK(any_of(warnings, "zero rotation"));
        CHECK(any_of(warnings, "neither PNG nor JPEG"));
        CHECK(any_of(warnings, "has no image"));
        // The material is kept in the table with its reference to TEXCOORD_1 (no primitive uses it).
        CHECK(read_glb(out).json["materials"][0]["normalTexture"]["texCoord"] == 1);
        // The material's base colour texture is garbage: object 0, drawn with it, gets the default material.
        CHECK(any_of(warnings, "texture 0 is not available; primitives using the material get the default material"));
        Glb glb = read_glb(out);
        CHECK(!glb.json["meshes"][0]["primitives"][0].contains("material"));
    }
}

TEST_CASE("an unnamed node with nothing but the default transform is written as a node, never as JSON null") {
    auto dir = scratch_dir("asset_output_empty_node");
    Asset a;
    Mesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.triangles = {{0, 1, 2}};
    a.objects = {tri};
    a.scene.meshes = {SceneMesh{0, "m", {{0, kNone}}, {}}};
    SceneNode root;
    root.index = 0;
    root.mesh = 0;
    root.name = "root";
    SceneNode leaf;  // Khronos SimpleSkin has one: no name, no mesh, no transform
    leaf.index = 1;
    leaf.parent = 0;
    a.scene.nodes = {root, leaf};
    for (const char* name : {"leaf.glb", "leaf.gltf"}) {
        CAPTURE(name);
        const fs::path out = dir / name;
        write_ok(out, a, {});
        check_valid(out);
        nlohmann::json json;
        if (fs::path(name).extension() == ".glb") {
            json = read_glb(out).json;
        } else {
            std::ifstream in(out);
            json = nlohmann::json::parse(in);
        }
        REQUIRE(json["nodes"].size() == 2);
        for (const auto& node : json["nodes"]) CHECK(node.is_object());
        CHECK(json["nodes"][0]["children"] == nlohmann::json::array({1}));
    }
}

namespace {

// A triangle at node 0 skinned by skin 0 over joints at nodes 1 and 2 (children of node 0), with a
// rotation track on node 1: what a conforming stream may carry, before the case breaks it.
Asset skinned_triangle() {
    Asset a;
    Mesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.triangles = {{0, 1, 2}};
    a.objects = {tri};
    VertexWeights w;
    w.joints.assign(3, {0, 1, 0, 0});
    w.weights.assign(3, {0.5f, 0.5f, 0, 0});
    a.weights = {w};
    a.scene.meshes = {SceneMesh{0, "m", {{0, kNone}}, {}}};
    SceneNode root, j1, j2;
    root.index = 0, root.mesh = 0, root.skin = 0, root.name = "root";
    j1.index = 1, j1.parent = 0, j1.name = "j1";
    j2.index = 2, j2.parent = 0, j2.name = "j2";
    a.scene.nodes = {root, j1, j2};
    SceneSkin skin;
    SkinJoint first, second;  // identity inverse bind matrices
    first.node = 1, second.node = 2;
    skin.joints = {first, second};
    a.scene.skins = {skin};
    return a;
}

}  // namespace

TEST_CASE("a conforming stream's skin or rotation keys that glTF forbids are normalized or left out with a "
          "warning, and the file is valid (issue 29, row 6)") {
    auto dir = scratch_dir("asset_output_skins");
    auto write = [&](const Asset& a, const std::string& name, std::vector<std::string>& warnings) {
        const fs::path out = dir / name;
        write_ok(out, a, {}, &warnings);
        check_valid(out);
        return read_glb(out).json;
    };
    std::vector<std::string> warnings;
    SUBCASE("as it is: skinned, with its skeleton") {
        Asset a = skinned_triangle();
        a.scene.skins[0].skeleton = 0;
        auto json = write(a, "plain.glb", warnings);
        CHECK(json["skins"].size() == 1);
        CHECK(json["skins"][0]["skeleton"] == 0);
        CHECK_MESSAGE(warnings.empty(), (warnings.empty() ? "" : warnings.front()));
    }
    SUBCASE("a node twice among the joints") {
        Asset a = skinned_triangle();
        a.scene.skins[0].joints[1].node = 1;
        auto json = write(a, "twice.glb", warnings);
        CHECK(!json.contains("skins"));
        CHECK(any_of(warnings, "node 1 is more than one of its joints"));
        CHECK(any_of(warnings, "written without skinning"));
    }
    SUBCASE("a zero inverse bind matrix") {
        Asset a = skinned_triangle();
        a.scene.skins[0].joints[0].inverse_bind.fill(0);
        auto json = write(a, "zero_ibm.glb", warnings);
        CHECK(!json.contains("skins"));
        CHECK(any_of(warnings, "inverse bind matrix of joint 0 is not an affine transform"));
    }
    SUBCASE("an inverse bind matrix whose last row is off by rounding is snapped") {
        Asset a = skinned_triangle();
        a.scene.skins[0].joints[1].inverse_bind[15] = 0.9999999f;
        a.scene.skins[0].joints[1].inverse_bind[3] = 1e-7f;
        auto json = write(a, "rounded_ibm.glb", warnings);
        CHECK(json["skins"].size() == 1);
    }
    SUBCASE("a huge inverse bind matrix (not finite)") {
        Asset a = skinned_triangle();
        a.scene.skins[0].joints[0].inverse_bind[12] = std::numeric_limits<float>::infinity();
        auto json = write(a, "huge_ibm.glb", warnings);
        CHECK(!json.contains("skins"));
    }
    SUBCASE("a skeleton that is not above every joint is left out") {
        Asset a = skinned_triangle();
        a.scene.skins[0].skeleton = 2;  // a sibling of joint 1
        auto json = write(a, "skeleton.glb", warnings);
        REQUIRE(json["skins"].size() == 1);
        CHECK(!json["skins"][0].contains("skeleton"));
        CHECK(any_of(warnings, "is not above every joint; written without it"));
    }
    SUBCASE("joints without a common root") {
        Asset a = skinned_triangle();
        a.scene.nodes[2].parent = kNone;  // joint 2 becomes a root of its own
        auto json = write(a, "no_root.glb", warnings);
        CHECK(!json.contains("skins"));
        CHECK(any_of(warnings, "its joints have no common root"));
    }
    SUBCASE("rotation keys of zero and of another length") {
        Asset a = skinned_triangle();
        SceneAnimation animation;
        SceneAnimation::Track track;
        track.node = 1;
        track.path = AnimationPath::Rotation;
        track.times = {0, 1, 2};
        track.values = {0, 0, 0, 0, 0, 0, 2, 0, 0.1f, 0.2f, 0.3f, 0.4f};
        animation.tracks = {track};
        SceneAnimation::Track nan = track;
        nan.node = 2;
        nan.values[0] = std::numeric_limits<float>::quiet_NaN();
        animation.tracks.push_back(nan);
        a.scene.animations = {animation};
        auto json = write(a, "rotations.glb", warnings);
        CHECK(any_of(warnings, "1 zero rotation(s) written as the identity"));
        CHECK(any_of(warnings, "not a finite number; left out"));
        REQUIRE(json["animations"].size() == 1);
        CHECK(json["animations"][0]["channels"].size() == 1);
    }
}

TEST_CASE("write_asset writes a texture as what its bytes are (the stream's image_type aside), leaves out a JPEG "
          "cut off in its header and keeps one cut off in its image data, naming each texture") {
    auto dir = scratch_dir("asset_output_images");
    const std::vector<uint8_t>& jpeg = samples::kJpegBaseline16;
    // One textured triangle per texture, each with a material of its own.
    Asset a;
    Mesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    tri.triangles = {{0, 1, 2}};
    SceneMesh mesh{0, "tris", {}, {}};
    for (uint16_t i = 0; i < 4; ++i) {
        a.objects.push_back(tri);
        mesh.primitives.push_back({i, i});
        Material m;
        m.name = "m" + std::to_string(i);
        m.base_color_texture.texture = i;
        a.scene.materials.push_back(m);
    }
    a.scene.meshes = {mesh};
    SceneNode root;
    root.mesh = 0;
    a.scene.nodes = {root};
    SceneDescription::Texture mislabelled, header_cut, data_cut, whole;
    mislabelled.info.image_type = ImageType::Png;  // a stream that says PNG for a JPEG file
    mislabelled.image = jpeg;
    header_cut.info.image_type = ImageType::Jpeg;
    header_cut.image.assign(jpeg.begin(), jpeg.begin() + 150);  // inside the frame header (SOF0 at byte 140)
    data_cut.info.image_type = ImageType::Jpeg;
    data_cut.image.assign(jpeg.begin(), jpeg.end() - 40);  // inside the scan's data: no EOI
    whole.info.image_type = ImageType::Jpeg;
    whole.image = samples::kJpegProgressive16;
    a.scene.textures = {mislabelled, header_cut, data_cut, whole};

    std::vector<std::string> warnings;
    write_ok(dir / "images.glb", a, {}, &warnings);
    check_valid(dir / "images.glb");
    CHECK(any_of(warnings, "texture 0 is announced as PNG but its bytes are a JPEG file; written as image/jpeg"));
    CHECK(any_of(warnings, "texture 1: its JPEG file is truncated at byte 150 in the segment at byte 140 (17 bytes); "
                           "no viewer can open it, left out"));
    CHECK(any_of(warnings, "texture 2: its JPEG file is truncated at byte 314 in the data of scan 1 (no EOI marker); "
                           "written as it is"));
    CHECK(!any_of(warnings, "texture 3"));
    Glb glb = read_glb(dir / "images.glb");
    REQUIRE(glb.json["images"].size() == 3);
    for (const auto& image : glb.json["images"]) CHECK(image["mimeType"] == "image/jpeg");
    // Material 1 lost its texture: its triangle gets the default material; the others keep theirs.
    const auto& primitives = glb.json["meshes"][0]["primitives"];
    REQUIRE(primitives.size() == 4);
    CHECK(!primitives[1].contains("material"));
    for (int i : {0, 2, 3}) CHECK(primitives[i].contains("material"));
    Asset back = load_asset((dir / "images.glb").string());
    REQUIRE(back.scene.textures.size() == 3);
    CHECK(back.scene.textures[0].image == jpeg);
    CHECK(back.scene.textures[1].image == data_cut.image);
    CHECK(back.scene.textures[2].image == samples::kJpegProgressive16);
}

TEST_CASE("write_asset refuses bad options, unknown file types and unwritable places with a clear error") {
    Asset a;
    a.objects.resize(1);
    a.objects[0].positions = {{0, 0, 0}};
    a.objects[0].is_point_set = true;
    std::vector<std::string> warnings;
    std::string error;
    auto dir = scratch_dir("asset_output_errors");
    CHECK(!write_asset((dir / "x.glb").string(), a, AssetWriteOptions{.draco = true, .quantize = true}, warnings, error));
    CHECK(error.find("cannot be combined") != std::string::npos);
    CHECK(!write_asset((dir / "x.stl").string(), a, {}, warnings, error));
    CHECK(error.find("unknown output type") != std::string::npos);
    CHECK(!write_asset((dir / "x.ply").string(), a, AssetWriteOptions{.quantize = true}, warnings, error));
    CHECK(error.find("glTF features") != std::string::npos);
    CHECK(!write_asset((dir / "missing" / "x.glb").string(), a, {}, warnings, error));
    CHECK(error.find("x.glb") != std::string::npos);
    CHECK(!fs::exists(dir / "missing" / "x.glb"));
}

TEST_CASE("a normal-mapped material's primitives get tangents along u, perpendicular to the normal, handed by the image's up") {
    auto dir = scratch_dir("asset_output_tangents");
    // Two unit squares in z = 0 facing +z: one mapped as glTF images are (v grows downwards, so the
    // image's up is +y: right-handed, w = +1), one mirrored vertically (w = -1).
    Mesh upright;
    upright.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    upright.triangles = {{0, 1, 2}, {0, 2, 3}};
    upright.normals.assign(4, {0, 0, 1});
    upright.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    Mesh mirrored = upright;
    mirrored.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    Mesh plain = upright;  // drawn without a normal texture: no tangents
    Asset a;
    a.objects = {upright, mirrored, plain};
    a.scene.meshes = {SceneMesh{0, "squares", {{0, 0}, {1, 0}, {2, 1}}, {}}};
    SceneNode root;
    root.mesh = 0;
    a.scene.nodes = {root};
    Material normal_mapped;
    normal_mapped.normal_texture.texture = 0;
    Material flat;
    a.scene.materials = {normal_mapped, flat};
    SceneDescription::Texture png;  // a valid 1x1 PNG
    png.image = one_pixel_png();
    a.scene.textures = {png};

    for (AssetWriteOptions options : {AssetWriteOptions{}, AssetWriteOptions{.draco = true},
                                      AssetWriteOptions{.quantize = true}}) {
        fs::path out = dir / (options.draco ? "draco.glb" : options.quantize ? "quantize.glb" : "plain.glb");
        CAPTURE(out);
        write_ok(out, a, options);
        int errors = -1;
        std::string report;
        if (validate_gltf(out, errors, report)) {
            CHECK_MESSAGE(errors == 0, report);
            CHECK_MESSAGE(nlohmann::json::parse(report).value("numWarnings", -1) == 0, report);  // no generated tangent space
        }
        Glb glb = read_glb(out);
        const auto& prims = glb.json["meshes"][0]["primitives"];
        REQUIRE(prims.size() == 3);
        CHECK_FALSE(prims[2]["attributes"].contains("TANGENT"));
        for (int p = 0; p < 2; ++p) {
            REQUIRE(prims[p]["attributes"].contains("TANGENT"));
            const auto& acc = glb.json["accessors"][prims[p]["attributes"]["TANGENT"].get<int>()];
            CHECK(acc["type"] == "VEC4");
            const auto& view = glb.json["bufferViews"][acc["bufferView"].get<int>()];
            const size_t offset = view.value("byteOffset", 0) + acc.value("byteOffset", 0);
            const int component = acc["componentType"];
            const size_t stride = view.value("byteStride", component == 5126 ? 16 : 4);
            for (size_t v = 0; v < acc["count"].get<size_t>(); ++v) {
                std::array<double, 4> t{};
                for (int k = 0; k < 4; ++k) {
                    const uint8_t* at = glb.bin.data() + offset + v * stride;
                    if (component == 5126) {
                        float f;
                        std::memcpy(&f, at + 4 * k, 4);
                        t[k] = f;
                    } else {
                        REQUIRE(component == 5120);  // normalized signed byte (KHR_mesh_quantization)
                        t[k] = std::max(-1.0, int8_t(at[k]) / 127.0);
                    }
                }
                CHECK(t[0] == doctest::Approx(1).epsilon(0.01));
                CHECK(std::abs(t[1]) < 0.01);
                CHECK(std::abs(t[2]) < 0.01);
                CHECK(t[3] == (p == 0 ? 1.0 : -1.0));
            }
        }
    }
}

TEST_CASE("morph targets are written sparse where that is smaller: a few moved vertices, none, or all of them dense") {
    Asset asset = load_asset((source_dir() / "samples" / "trefoil.obj").string());
    REQUIRE(asset.objects.size() == 1);
    const size_t n = asset.objects[0].positions.size();
    REQUIRE(n > 300);
    VertexMorph morph;
    morph.targets = 3;
    morph.attributes = kMorphPosition;
    const size_t per = morph_record_values(morph.targets, morph.attributes);
    morph.values.assign(n * per, 0.0f);
    for (size_t v : {3u, 40u, 41u, 200u, 299u}) morph.values[v * per + morph_slot_offset(morph.attributes, 0, kMorphPosition) + 1] = 0.25f;
    for (size_t v = 0; v < n; ++v) morph.values[v * per + morph_slot_offset(morph.attributes, 1, kMorphPosition)] = -0.5f;
    asset.morphs = {morph};
    asset.scene.meshes[0].weights = {0.0f, 1.0f, 0.0f};
    const fs::path glb = scratch_dir("sparse_targets") / "targets.glb";
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(glb.string(), asset, AssetWriteOptions{}, warnings, error), error);
    check_valid(glb);
    const Glb g = read_glb(glb);
    const auto& targets = g.json["meshes"][0]["primitives"][0]["targets"];
    REQUIRE(targets.size() == 3);
    const auto& few = g.json["accessors"][targets[0]["POSITION"].get<int>()];
    CHECK_FALSE(few.contains("bufferView"));
    REQUIRE(few.contains("sparse"));
    CHECK(few["sparse"]["count"] == 5);
    CHECK(few["count"] == n);
    CHECK(few["min"][1] == 0.0);
    CHECK(few["max"][1] == 0.25);
    const auto& all = g.json["accessors"][targets[1]["POSITION"].get<int>()];
    CHECK(all.contains("bufferView"));
    CHECK_FALSE(all.contains("sparse"));
    const auto& none = g.json["accessors"][targets[2]["POSITION"].get<int>()];
    CHECK_FALSE(none.contains("bufferView"));
    CHECK_FALSE(none.contains("sparse"));
    // Read back: the same displacements everywhere.
    const Asset back = load_asset(glb.string());
    REQUIRE(back.morphs.size() == 1);
    REQUIRE(back.morphs[0].values.size() == morph.values.size());
    CHECK(back.morphs[0].values == morph.values);
}
