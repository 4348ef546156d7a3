// Acceptance of issue 5: every glTF sample goes through encode -> packets -> decode and comes out as
// the same scene: valid for the Khronos validator, same nodes and transforms, same materials,
// byte-identical texture files, each object within the decoder's quality bound; with packets lost
// the file is still valid, with what is missing named. And the commands do the same. A JPEG texture
// (a real file from a JPEG encoder, samples/jpeg_images.h) goes through like the samples' PNGs.
#include "jpeg_images.h"
#include "scene_compare.h"
#include "support.h"

#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/asset_stream.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

// The decoder's quality bound (issue 4), which every object of every sample meets with every packet,
// encoded with the default options: RMS distance at most 0.1% of the bounding-box diagonal, both
// ways on a closed object, from the original to the reconstruction on an open one (the base closes
// its holes and boundary, so the way back measures the closing, not the object).
constexpr double kDecoderBoundPercent = 0.1;
// What the objects of kGltfSamples (scene_compare.h) reached at the last change (in -> out / out -> in):
//   Box 0.010 / 0.021 (0.047 / 0.107 before normal repair); Duck 0.016 / 0.021; Fox 0.030 / 0.037;
//   milk truck (open) body 0.085, glass 0.097, trim 0.052, wheels 0.010 / 0.011; VertexColorTest
//   (open) label 0.039, plate 0.008; the two-material sphere 0.017 / 0.017.

// A program's path quoted for the shell, with a space after it (built with +=: GCC 12's
// -Wrestrict false positive on "'" + string).
std::string quoted_program(const fs::path& program) {
    std::string out = "'";
    out += program.string();
    out += "' ";
    return out;
}

// Coarse settings: what is tested is the scene and that the geometry comes back, not the base.
EncodeOptions coarse_encoding() {
    EncodeOptions o;
    o.max_ellipsoids = 60;
    o.coverage = 0.8;
    return o;
}
// Encodes `in`, loses the packets at the indices in `drop`, decodes at `grid`. `closed`, when given,
// gets the encoder's verdict per object: no boundary edges.
Asset round_trip(const Asset& in, int grid, const std::vector<size_t>& drop = {},
                 const EncodeOptions& encoding = coarse_encoding(), std::vector<bool>* closed = nullptr) {
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, encoding, 1, true, encoded, error), error);
    if (closed) {
        closed->clear();
        for (const auto& r : encoded.encoded.reports) closed->push_back(r.closed);
    }
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i)
        if (!std::count(drop.begin(), drop.end(), i)) REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
    Asset out;
    StreamDecodeReport report;
    DecodeOptions decoding;
    decoding.grid_resolution = grid;
    REQUIRE_MESSAGE(decode_asset(stream, decoding, out, report, error), error);
    return out;
}

bool any_of(const std::vector<std::string>& warnings, const std::string& needle) {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

void check_valid(const fs::path& path) {
    int errors = -1;
    std::string report;
    if (validate_gltf(path, errors, report)) CHECK_MESSAGE(errors == 0, path.string() << ": " << report);
}

// Each object of `out` is object i of `in`: every original vertex is there (all points arrived),
// within the stream's 14-bit position step; a triangle object is within `rms_percent` of the
// bounding-box diagonal (RMS surface distance from the original, and back when it is closed).
void check_geometry(const Asset& in, const Asset& out, const std::vector<bool>& closed, double rms_percent) {
    REQUIRE(out.objects.size() == in.objects.size());
    REQUIRE(closed.size() == in.objects.size());
    for (size_t i = 0; i < in.objects.size(); ++i) {
        const Mesh& a = in.objects[i];
        const Mesh& b = out.objects[i];
        CAPTURE(a.name);
        REQUIRE(!b.positions.empty());
        CHECK(b.is_point_set == a.is_point_set);
        CHECK(b.has_texcoords() == a.has_texcoords());
        CHECK(b.has_colors() == a.has_colors());
        const double step = bounding_box_diagonal({a}) / 16383.0;
        size_t missing = 0;
        for (const auto& p : a.positions) {
            double best = 1e300;
            for (const auto& q : b.positions) {
                double d = 0;
                for (int k = 0; k < 3; ++k) d += (double(p[k]) - q[k]) * (double(p[k]) - q[k]);
                best = std::min(best, d);
            }
            if (std::sqrt(best) > step) ++missing;
        }
        CHECK_MESSAGE(missing == 0, missing << " of " << a.positions.size() << " original vertices missing");
        if (a.is_point_set) continue;
        SurfaceDistanceOptions options;
        options.samples = 20000;
        SurfaceDistance d;
        std::string error;
        REQUIRE_MESSAGE(surface_distance({a}, {b}, options, d, error), error);
        MESSAGE(a.name << std::string(closed[i] ? " (closed)" : " (open)") << ": RMS distance " << d.percent(d.a_to_b.rms)
                       << "% (in -> out), " << d.percent(d.b_to_a.rms) << "% (out -> in) of the diagonal");
        CHECK(d.percent(d.a_to_b.rms) <= rms_percent);
        if (closed[i]) CHECK(d.percent(d.b_to_a.rms) <= rms_percent);
    }
}

}  // namespace

TEST_CASE("every glTF sample through encode and decode with all packets: same scene, materials, texture files, "
          "geometry within the decoder's bound, and a valid glTF") {
    auto dir = scratch_dir("scene_roundtrip");
    for (const char* f : kGltfSamples) {
        if (!have_sample(f)) continue;
        std::string name = f;
        CAPTURE(name);
        Asset in = load_asset(sample(f));
        std::vector<bool> closed;
        // The defaults, decoded at the stream's grid: what a user gets.
        Asset out = round_trip(in, 0, {}, EncodeOptions{}, &closed);
        CHECK(out.warnings.empty());
        check_geometry(in, out, closed, kDecoderBoundPercent);
        fs::path file = dir / (fs::path(f).stem().string() + ".glb");
        std::vector<std::string> warnings;
        std::string error;
        REQUIRE_MESSAGE(write_asset(file.string(), out, {}, warnings, error), error);
        CHECK(warnings.empty());
        check_valid(file);
        check_same_scene(in, load_asset(file.string()));
    }
}

TEST_CASE("with packets lost the decoded scene is still a valid glTF: a missing object is left out, a material "
          "whose texture did not fully arrive falls back to the default material") {
    const char* f = "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf";
    if (!have_sample(f)) return;
    Asset in = load_asset(sample(f));
    EncodedAsset encoded;
    std::string error;
    REQUIRE(encode_asset(in, coarse_encoding(), 1, true, encoded, error));
    // Lose every ELLIPSOIDS, POINTS and POINTS_REPAIR packet of object 3 (the wheels) and one texture fragment.
    std::vector<size_t> drop;
    bool texture_dropped = false;
    for (size_t i = 0; i < encoded.packets.size(); ++i) {
        PacketView view;
        REQUIRE(parse_packet(encoded.packets[i], view) == Error::Ok);
        const auto type = PacketType(view.header.type);
        if ((type == PacketType::Ellipsoids || is_points_type(uint8_t(type)) || type == PacketType::PointsRepair) &&
            view.header.object_id == 3)
            drop.push_back(i);
        if (type == PacketType::TextureFragment && !texture_dropped) drop.push_back(i), texture_dropped = true;
    }
    Asset out = round_trip(in, 0, drop);
    CHECK(out.objects[3].positions.empty());
    CHECK(any_of(out.warnings, "material 0 (truck) is waiting for its baseColorTexture texture 0"));
    auto dir = scratch_dir("scene_roundtrip_loss");
    std::vector<std::string> warnings;
    REQUIRE_MESSAGE(write_asset((dir / "lossy.glb").string(), out, {}, warnings, error), error);
    CHECK(any_of(warnings, "(object 3) has not arrived"));
    check_valid(dir / "lossy.glb");
    Asset back = load_asset((dir / "lossy.glb").string());
    REQUIRE(back.scene.nodes.size() == 5);
    CHECK(back.scene.nodes[2].mesh == kNone);  // the wheel nodes stay, without their mesh
    CHECK(back.scene.nodes[4].mesh == kNone);
    CHECK(back.scene.textures.empty());
    // The body is drawn with the default material; glass and window trim keep theirs.
    REQUIRE(back.scene.materials.size() == 2);
    bool body_seen = false;
    for (size_t n = 0; n < in.scene.nodes.size(); ++n) {
        if (in.scene.nodes[n].mesh == kNone || back.scene.nodes[n].mesh == kNone) continue;
        const auto& pa = in.scene.meshes[in.scene.nodes[n].mesh].primitives;
        const auto& pb = back.scene.meshes[back.scene.nodes[n].mesh].primitives;
        REQUIRE(pa.size() == pb.size());
        for (size_t p = 0; p < pa.size(); ++p) {
            const Material& ma = in.scene.materials[pa[p].material];
            CAPTURE(ma.name);
            if (ma.base_color_texture.texture != kNone) {
                CHECK(pb[p].material == kNone);
                body_seen = true;
                continue;
            }
            REQUIRE(pb[p].material != kNone);
            const Material& mb = back.scene.materials[pb[p].material];
            CHECK(mb.name == ma.name);
            for (int k = 0; k < 4; ++k) CHECK(mb.base_color[k] == doctest::Approx(ma.base_color[k]));
        }
    }
    CHECK(body_seen);
}

TEST_CASE("under random packet loss of any kind the receiver's file is always a valid glTF, plain, Draco or "
          "quantized, and every gap is named") {
    const char* files[] = {"gltf/CesiumMilkTruck/CesiumMilkTruck.gltf",
                           "gltf/SphereTwoMaterials/sphere_two_materials_mesh_and_point_cloud.gltf"};
    auto dir = scratch_dir("scene_roundtrip_random_loss");
    std::mt19937 random(20261121);
    int trial = 0, present = 0;
    for (const char* f : files) {
        if (!have_sample(f)) continue;
        ++present;
        Asset in = load_asset(sample(f));
        EncodedAsset encoded;
        std::string error;
        REQUIRE_MESSAGE(encode_asset(in, coarse_encoding(), 1, true, encoded, error), error);
        // The STREAM_INFO always arrives (a carousel repeats it most often); without it nothing can be
        // built and decoding fails, naming it.
        {
            ReceivedStream stream;
            for (size_t i = encoded.stream_info_packets; i < encoded.packets.size(); ++i)
                REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
            Asset out;
            StreamDecodeReport report;
            CHECK(!decode_asset(stream, {}, out, report, error));
            CHECK_MESSAGE(error.find("STREAM_INFO") != std::string::npos, error);
        }
        for (double loss : {0.3, 0.6, 0.9, 0.99}) {
            const std::string name = f;
            CAPTURE(name);
            CAPTURE(loss);
            ReceivedStream stream;
            size_t kept = 0;
            std::bernoulli_distribution lost(loss);
            for (size_t i = 0; i < encoded.packets.size(); ++i) {
                if (i >= encoded.stream_info_packets && lost(random)) continue;
                REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
                ++kept;
            }
            Asset out;
            StreamDecodeReport report;
            DecodeOptions decoding;
            decoding.grid_resolution = 24;
            REQUIRE_MESSAGE(decode_asset(stream, decoding, out, report, error), error);
            const bool any_object = std::any_of(out.objects.begin(), out.objects.end(),
                                                [](const Mesh& m) { return !m.positions.empty(); });
            AssetWriteOptions options;
            options.draco = trial % 3 == 1;
            options.quantize = trial % 3 == 2;
            ++trial;
            fs::path file = dir / ("trial" + std::to_string(trial) + ".glb");
            std::vector<std::string> warnings;
            REQUIRE_MESSAGE(write_asset(file.string(), out, options, warnings, error), error);
            check_valid(file);
            // A gap is named: in the asset's or the writer's warnings (the scene), or in the decode
            // report (an object that did not get all its points, or has no entry).
            const bool incomplete = std::any_of(report.objects.begin(), report.objects.end(),
                                                [](const ObjectDecodeReport& o) { return !o.complete; });
            const bool named = out.warnings.size() + warnings.size() > 0 || incomplete;
            if (kept < encoded.packets.size()) CHECK_MESSAGE(named, "kept " << kept << " of " << encoded.packets.size());
            if (!any_object) continue;  // a valid file with nothing in it (the command refuses to write one)
            // Read back: a material is there only with every texture it uses.
            Asset back = load_asset(file.string());
            for (const Material& m : back.scene.materials)
                for (const TextureRef* ref : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                              &m.occlusion_texture, &m.emissive_texture})
                    if (ref->texture != kNone) CHECK(ref->texture < back.scene.textures.size());
        }
    }
    CHECK(trial == 4 * present);  // four loss rates for every asset present (none without ../shared)
}

TEST_CASE("ellicast decode of a stream whose texture fragments were lost: the Duck gets the default material, "
          "the summary and warnings name the material and the texture") {
    const char* f = "gltf/Duck/Duck.gltf";
    if (!have_sample(f)) return;
    auto dir = scratch_dir("scene_roundtrip_no_texture");
    Asset in = load_asset(sample(f));
    EncodedAsset encoded;
    std::string error;
    REQUIRE(encode_asset(in, coarse_encoding(), 1, true, encoded, error));
    std::vector<std::vector<uint8_t>> kept, all_but_one;
    size_t fragments = 0;
    for (const auto& packet : encoded.packets) {
        PacketView view;
        REQUIRE(parse_packet(packet, view) == Error::Ok);
        if (PacketType(view.header.type) == PacketType::TextureFragment) {
            if (fragments++ > 0) all_but_one.push_back(packet);
            continue;
        }
        kept.push_back(packet);
        all_but_one.push_back(packet);
    }
    REQUIRE(fragments > 1);
    const std::string exe = quoted_program(ellicast_exe());
    auto decode = [&](const std::vector<std::vector<uint8_t>>& packets, const std::string& name, int& status) {
        auto bytes = write_container(packets);
        std::ofstream((dir / (name + ".ellc")).string(), std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return run_command(exe + "decode -q --grid 24 '" + (dir / (name + ".ellc")).string() + "' -o '" +
                               (dir / (name + ".glb")).string() + "'",
                           status);
    };
    int status = 0;
    std::string log = decode(kept, "none", status);
    REQUIRE_MESSAGE(status == 0, log);
    CHECK_MESSAGE(log.find("warning: material 0 (blinn3-fx) is waiting for its baseColorTexture texture 0 (none of "
                           "it arrived); its primitives get the default material") != std::string::npos,
                  log);
    CHECK_MESSAGE(log.find("scene: 3 of 3 nodes, 1 of 1 meshes, 0 of 1 materials shown (1 waiting for a texture), "
                           "0 of ? textures complete") != std::string::npos,
                  log);
    check_valid(dir / "none.glb");
    Asset back = load_asset((dir / "none.glb").string());
    CHECK(back.scene.materials.empty());
    CHECK(back.scene.textures.empty());
    REQUIRE(back.scene.meshes.size() == 1);
    CHECK(back.scene.meshes[0].primitives[0].material == kNone);
    REQUIRE(back.objects.size() == 1);
    CHECK(back.objects[0].has_texcoords());  // the coordinates are kept for when the texture arrives

    log = decode(all_but_one, "partial", status);
    REQUIRE_MESSAGE(status == 0, log);
    CHECK_MESSAGE(log.find("is waiting for its baseColorTexture texture 0 (") != std::string::npos, log);
    CHECK(log.find(" of " + std::to_string(in.scene.textures[0].image.size()) + " bytes arrived)") != std::string::npos);
    check_valid(dir / "partial.glb");
    CHECK(load_asset((dir / "partial.glb").string()).scene.meshes[0].primitives[0].material == kNone);
}

TEST_CASE("ellicast encode, decode --quantize and convert --draco carry a glTF's scene end to end") {
    const char* f = "gltf/Duck/Duck.gltf";
    if (!have_sample(f)) return;
    auto dir = scratch_dir("scene_roundtrip_cli");
    const std::string exe = quoted_program(ellicast_exe());
    int status = 0;
    std::string log = run_command(exe + "encode -q -e 60 -c 0.8 '" + sample(f) + "' -o '" + (dir / "duck.ellc").string() + "'", status);
    REQUIRE_MESSAGE(status == 0, log);
    CHECK(log.find("scene: 3 nodes, 1 meshes, 1 materials, 1 textures") != std::string::npos);
    log = run_command(exe + "validate '" + (dir / "duck.ellc").string() + "'", status);
    CHECK_MESSAGE(status == 0, log);
    log = run_command(exe + "decode -q --grid 24 --quantize '" + (dir / "duck.ellc").string() + "' -o '" +
                          (dir / "duck.glb").string() + "'",
                      status);
    REQUIRE_MESSAGE(status == 0, log);
    check_valid(dir / "duck.glb");
    Asset in = load_asset(sample(f));
    Asset quantized = load_asset((dir / "duck.glb").string());
    CHECK(quantized.scene.nodes.size() == in.scene.nodes.size() + 1);  // + the dequantization node
    REQUIRE(quantized.scene.textures.size() == 1);
    CHECK(quantized.scene.textures[0].image == in.scene.textures[0].image);

    log = run_command(exe + "convert -q -e 60 -c 0.8 --grid 24 --draco '" + sample(f) + "' '" +
                          (dir / "duck_draco.glb").string() + "'",
                      status);
    REQUIRE_MESSAGE(status == 0, log);
    check_valid(dir / "duck_draco.glb");
    check_same_scene(in, load_asset((dir / "duck_draco.glb").string()));
    if (have_node_package("@gltf-transform/cli")) {
        log = run_command(quoted_program(node_modules() / ".bin" / "gltf-transform") + "inspect --format csv '" +
                              (dir / "duck_draco.glb").string() + "'",
                          status);
        CHECK_MESSAGE(status == 0, log);
        CHECK(log.find("KHR_draco_mesh_compression") != std::string::npos);
    }

    // Refused: Draco with quantization, and either with a PLY output.
    log = run_command(exe + "decode --draco --quantize '" + (dir / "duck.ellc").string() + "' -o '" +
                          (dir / "x.glb").string() + "'",
                      status);
    CHECK(status == 2);
    CHECK(log.find("cannot be combined") != std::string::npos);
    log = run_command(exe + "decode --draco '" + (dir / "duck.ellc").string() + "' -o '" + (dir / "x.ply").string() + "'",
                      status);
    CHECK(status == 2);
    // PLY output of a scene: the world-space meshes (the Duck's 0.01 root scale applied).
    log = run_command(exe + "convert -q -e 60 -c 0.8 --grid 24 '" + sample(f) + "' '" + (dir / "duck.ply").string() + "'",
                      status);
    REQUIRE_MESSAGE(status == 0, log);
    LoadResult ply = load_meshes((dir / "duck.ply").string());
    LoadResult world = load_gltf(sample(f));
    CHECK(bounding_box_diagonal(ply.meshes) == doctest::Approx(bounding_box_diagonal(world.meshes)).epsilon(0.02));
}

namespace {

std::vector<uint8_t> file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_bytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The Duck with its texture replaced by `jpeg`, written into `dir`: as Duck.gltf with an external
// duck.jpg (no mimeType, as the Duck has it), or as duck.glb with the JPEG in a bufferView of the BIN
// chunk (mimeType image/jpeg, as glTF requires there).
fs::path jpeg_duck(const fs::path& dir, const std::vector<uint8_t>& jpeg, bool glb) {
    auto json = nlohmann::json::parse(file_bytes(shared_samples() / "gltf/Duck/Duck.gltf"));
    if (!glb) {
        fs::copy_file(shared_samples() / "gltf/Duck/Duck0.bin", dir / "Duck0.bin", fs::copy_options::overwrite_existing);
        write_bytes(dir / "duck.jpg", jpeg);
        json["images"][0] = {{"uri", "duck.jpg"}};
        std::ofstream(dir / "Duck.gltf") << json.dump();
        return dir / "Duck.gltf";
    }
    std::vector<uint8_t> bin = file_bytes(shared_samples() / "gltf/Duck/Duck0.bin");
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", jpeg.size()}});
    json["images"][0] = {{"bufferView", json["bufferViews"].size() - 1}, {"mimeType", "image/jpeg"}};
    bin.insert(bin.end(), jpeg.begin(), jpeg.end());
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    json["buffers"][0] = {{"byteLength", bin.size()}};
    std::string text = json.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
    };
    u32(0x46546C67);  // "glTF"
    u32(2);
    u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);  // JSON
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942);  // BIN
    out.insert(out.end(), bin.begin(), bin.end());
    write_bytes(dir / "duck.glb", out);
    return dir / "duck.glb";
}

}  // namespace

TEST_CASE("a JPEG texture goes through encode and decode byte for byte, as image/jpeg, from a .gltf with an "
          "external .jpg and from a .glb with the JPEG in a bufferView, and the files are valid glTF") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    auto dir = scratch_dir("scene_roundtrip_jpeg");
    const struct {
        const char* name;
        const std::vector<uint8_t>& jpeg;
        bool glb;
    } cases[] = {{"baseline", samples::kJpegBaseline16, false}, {"progressive", samples::kJpegProgressive16, true}};
    for (const auto& c : cases) {
        const std::string name = c.name;
        CAPTURE(name);
        const fs::path sub = dir / name;
        fs::create_directories(sub);
        const fs::path input = jpeg_duck(sub, c.jpeg, c.glb);
        check_valid(input);
        Asset in = load_asset(input.string());
        CHECK(in.warnings.empty());  // nothing about its image; its camera travels (format 1.10)
        CHECK(in.scene.cameras.size() == 1);
        REQUIRE(in.scene.textures.size() == 1);
        CHECK(in.scene.textures[0].info.image_type == ImageType::Jpeg);
        CHECK(in.scene.textures[0].image == c.jpeg);

        Asset out = round_trip(in, 24);
        CHECK(out.warnings.empty());
        REQUIRE(out.scene.textures.size() == 1);
        CHECK(out.scene.textures[0].info.image_type == ImageType::Jpeg);
        CHECK(out.scene.textures[0].image == c.jpeg);
        REQUIRE(out.scene.materials.size() == 1);
        CHECK(out.scene.materials[0].base_color_texture.texture == 0);
        for (const char* extension : {".gltf", ".glb"}) {
            const fs::path file = sub / (std::string("out") + extension);
            std::vector<std::string> warnings;
            std::string error;
            REQUIRE_MESSAGE(write_asset(file.string(), out, {}, warnings, error), error);
            CHECK(warnings.empty());
            check_valid(file);
            Asset back = load_asset(file.string());
            CHECK(back.warnings.empty());
            REQUIRE(back.scene.textures.size() == 1);
            CHECK(back.scene.textures[0].image == c.jpeg);
            check_same_scene(in, back);
            if (std::string(extension) == ".gltf") {
                auto json = nlohmann::json::parse(file_bytes(file));
                REQUIRE(json["images"].size() == 1);
                CHECK(json["images"][0]["mimeType"] == "image/jpeg");
            }
        }
    }
}

TEST_CASE("with a JPEG texture fragment lost the Duck gets the default material and the file stays valid, "
          "once every fragment arrived it shows the JPEG") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    auto dir = scratch_dir("scene_roundtrip_jpeg_loss");
    Asset in = load_asset(jpeg_duck(dir, samples::kJpegBaseline16, false).string());
    EncodeOptions encoding = coarse_encoding();
    encoding.packet_size = 256;  // the 354-byte JPEG in 2 fragments
    EncodedAsset encoded;
    std::string error;
    REQUIRE(encode_asset(in, encoding, 1, true, encoded, error));
    std::vector<size_t> fragments;
    for (size_t i = 0; i < encoded.packets.size(); ++i) {
        PacketView view;
        REQUIRE(parse_packet(encoded.packets[i], view) == Error::Ok);
        if (PacketType(view.header.type) == PacketType::TextureFragment) fragments.push_back(i);
    }
    REQUIRE(fragments.size() == 2);
    for (size_t lost : fragments) {
        CAPTURE(lost);
        Asset out = round_trip(in, 24, {lost}, encoding);
        CHECK(any_of(out.warnings, "material 0 (blinn3-fx) is waiting for its baseColorTexture texture 0 ("));
        CHECK(any_of(out.warnings, " of 354 bytes arrived)"));
        const fs::path file = dir / ("lost" + std::to_string(lost) + ".glb");
        std::vector<std::string> warnings;
        REQUIRE_MESSAGE(write_asset(file.string(), out, {}, warnings, error), error);
        check_valid(file);
        Asset back = load_asset(file.string());
        CHECK(back.scene.materials.empty());
        CHECK(back.scene.textures.empty());
        REQUIRE(back.scene.meshes.size() == 1);
        CHECK(back.scene.meshes[0].primitives[0].material == kNone);
    }
    Asset whole = round_trip(in, 24, {}, encoding);
    REQUIRE(whole.scene.textures.size() == 1);
    CHECK(whole.scene.textures[0].image == samples::kJpegBaseline16);
}

TEST_CASE("a point cloud drawn with a normal-mapped material gets tangents too: the two-material sphere writes without a validator warning") {
    const char* f = "gltf/SphereTwoMaterials/sphere_two_materials_mesh_and_point_cloud.gltf";
    if (!have_sample(f)) return;
    const Asset in = load_asset(sample(f));
    const Asset out = round_trip(in, 24);
    const fs::path path = scratch_dir("point_tangents") / "sphere.glb";
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(path.string(), out, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(path);
}

TEST_CASE("convert writes a glTF as its input was stored: Draco stays Draco, quantized stays quantized, --plain asks for plain") {
    const fs::path dir = scratch_dir("convert_like_input");
    const std::string exe = quoted_program(ellicast_exe()), trefoil = (source_dir() / "samples" / "trefoil.obj").string();
    int status = 0;
    auto convert = [&](const std::string& options, const fs::path& in, const fs::path& out) {
        const std::string log = run_command(exe + "convert -q " + options + " '" + in.string() + "' '" + out.string() + "'", status);
        REQUIRE_MESSAGE(status == 0, log);
        check_valid(out);
        return log;
    };
    convert("--draco", trefoil, dir / "draco.glb");
    convert("--quantize", trefoil, dir / "quantized.glb");
    convert("", trefoil, dir / "plain.glb");
    const Asset draco = load_asset((dir / "draco.glb").string()), quantized = load_asset((dir / "quantized.glb").string());
    REQUIRE(draco.source_draco);
    REQUIRE(quantized.source_quantized);
    CHECK_FALSE(load_asset((dir / "plain.glb").string()).source_draco);

    std::string log = convert("", dir / "draco.glb", dir / "draco_again.glb");
    CHECK(log.find("output written Draco") != std::string::npos);
    CHECK(load_asset((dir / "draco_again.glb").string()).source_draco);
    // The same meshes the same way: about the input's size (the exact layer gives back the triangles).
    CHECK(fs::file_size(dir / "draco_again.glb") <= 1.1 * double(fs::file_size(dir / "draco.glb")));
    log = convert("", dir / "quantized.glb", dir / "quantized_again.glb");
    CHECK(log.find("output written quantized") != std::string::npos);
    CHECK(load_asset((dir / "quantized_again.glb").string()).source_quantized);
    CHECK(fs::file_size(dir / "quantized_again.glb") <= 1.1 * double(fs::file_size(dir / "quantized.glb")));
    convert("--plain", dir / "draco.glb", dir / "plain_again.glb");
    const Asset plain = load_asset((dir / "plain_again.glb").string());
    CHECK_FALSE(plain.source_draco);
    CHECK_FALSE(plain.source_quantized);
    // Asked for explicitly, the other way wins; --plain with either is refused.
    convert("--quantize", dir / "draco.glb", dir / "asked.glb");
    CHECK(load_asset((dir / "asked.glb").string()).source_quantized);
    run_command(exe + "convert -q --plain --draco '" + trefoil + "' '" + (dir / "x.glb").string() + "'", status);
    CHECK(status == 2);
}

// ---- Cameras and punctual lights (format 1.10, spec 26) ----

namespace {

// `asset` through encode and decode with every packet but those of `lost_type` (0: none), written as
// .glb and .gltf under `dir`, each checked by the Khronos validator (no error, no warning); returns the
// decoded asset. `bytes` gets the bytes of the CAMERA and LIGHT packets sent.
Asset viewed_round_trip(const Asset& in, const fs::path& dir, uint8_t lost_type, size_t* bytes = nullptr) {
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_encoding(), 1, true, encoded, error), error);
    size_t sent = 0;
    for (const auto& p : encoded.packets)
        if (is_packet_type(p, PacketType::Camera) || is_packet_type(p, PacketType::Light)) sent += p.size();
    if (bytes) *bytes = sent;
    Asset out = received_without(encoded.packets, [&](size_t i) { return lost_type && encoded.packets[i][6] == lost_type; }, 24);
    for (const char* extension : {".glb", ".gltf"}) {
        const fs::path file = dir / (std::string("out") + extension);
        std::vector<std::string> warnings;
        REQUIRE_MESSAGE(write_asset(file.string(), out, AssetWriteOptions{}, warnings, error), error);
        check_gltf_clean(file);
    }
    return out;
}

// Khronos Cameras (samples/khronos/Cameras) with KHR_lights_punctual added: a directional light on a
// new node, a point light with a range and a spot light on the camera nodes, and a third camera
// (perspective, infinite, without aspect ratio) named by no node.
fs::path lit_cameras(const fs::path& dir) {
    const fs::path source = source_dir() / "samples" / "khronos" / "Cameras";
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(source / "Cameras.gltf"));
    fs::copy_file(source / "simpleSquare.bin", dir / "simpleSquare.bin", fs::copy_options::overwrite_existing);
    doc["extensionsUsed"] = {"KHR_lights_punctual"};
    doc["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::parse(R"([
        {"type": "directional", "name": "Sun", "color": [1.0, 0.9, 0.7], "intensity": 2.5},
        {"type": "point", "name": "Bulb", "intensity": 40, "range": 12.5},
        {"type": "spot", "name": "Torch", "color": [0.2, 0.4, 1.0], "intensity": 15,
         "spot": {"innerConeAngle": 0.25, "outerConeAngle": 1.5707963267948966}}])");
    doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 1;
    doc["nodes"][2]["extensions"]["KHR_lights_punctual"]["light"] = 2;
    doc["nodes"].push_back({{"name", "Sun node"}, {"rotation", {-0.5, 0.0, 0.0, 0.8660254}},
                            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc["scenes"][0]["nodes"].push_back(3);
    doc["cameras"].push_back({{"type", "perspective"}, {"name", "Endless"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.05}}}});
    std::ofstream(dir / "LitCameras.gltf") << doc.dump(2);
    return dir / "LitCameras.gltf";
}

}  // namespace

TEST_CASE("Khronos Cameras through encode and decode: both cameras come back on their nodes, and the glTF is valid") {
    const fs::path dir = scratch_dir("camera_light_cameras");
    const std::string path = (source_dir() / "samples" / "khronos" / "Cameras" / "Cameras.gltf").string();
    Asset in = load_asset(path);
    CHECK(in.warnings.empty());
    REQUIRE(in.scene.cameras.size() == 2);
    CHECK(in.scene.cameras[0].projection == CameraProjection::Perspective);
    CHECK(in.scene.cameras[0].b == 0.7f);  // yfov
    CHECK(in.scene.cameras[1].projection == CameraProjection::Orthographic);
    size_t bytes = 0;
    Asset out = viewed_round_trip(in, dir, 0, &bytes);
    check_same_scene(in, out);
    MESSAGE("Cameras.gltf: the 2 CAMERA packets cost " << bytes << " bytes");
    CHECK(bytes == 2 * (24 + 24));  // no names
    const nlohmann::json json = gltf_document(dir / "out.glb");
    REQUIRE(json["cameras"].size() == 2);
    CHECK(json["cameras"][0]["type"] == "perspective");
    CHECK(json["cameras"][0]["perspective"]["zfar"] == 100.0);
    CHECK(json["cameras"][1]["orthographic"]["xmag"] == 1.0);
    size_t with_camera = 0;
    for (const auto& n : json["nodes"]) with_camera += n.contains("camera");
    CHECK(with_camera == 2);
}

TEST_CASE("punctual lights and an infinite camera travel: directional, point with range, spot at pi over 2, on their nodes, validator clean") {
    const fs::path dir = scratch_dir("camera_light_lights");
    const fs::path input = lit_cameras(dir);
    check_gltf_clean(input);
    Asset in = load_asset(input.string());
    CHECK(in.warnings.empty());
    REQUIRE(in.scene.lights.size() == 3);
    REQUIRE(in.scene.cameras.size() == 3);
    // pi / 2 as a double rounds to an f32 above it; the encoder takes the one below (spec 26.5).
    CHECK(double(in.scene.lights[2].outer_cone) <= 1.5707963267948966);
    CHECK(in.scene.lights[2].outer_cone == std::nextafter(float(1.5707963267948966), 0.0f));
    CHECK(in.scene.cameras[2].zfar == 0);
    size_t bytes = 0;
    Asset out = viewed_round_trip(in, dir, 0, &bytes);
    check_same_scene(in, out);
    MESSAGE("3 cameras and 3 lights: " << bytes << " bytes of CAMERA and LIGHT packets");
    const nlohmann::json json = gltf_document(dir / "out.glb");
    CHECK(json["extensionsUsed"].dump().find("KHR_lights_punctual") != std::string::npos);
    CHECK_FALSE(json.contains("extensionsRequired"));
    const auto& lights = json["extensions"]["KHR_lights_punctual"]["lights"];
    REQUIRE(lights.size() == 3);
    CHECK(lights[0]["type"] == "directional");
    CHECK_FALSE(lights[0].contains("range"));
    CHECK(lights[1]["range"] == 12.5);
    CHECK(lights[2]["spot"]["innerConeAngle"] == double(0.25f));
    CHECK_FALSE(json["cameras"][2]["perspective"].contains("zfar"));  // infinite
    CHECK_FALSE(json["cameras"][2]["perspective"].contains("aspectRatio"));
    // A receiver that lost every LIGHT packet writes the nodes without lights, still valid.
    const fs::path unlit = dir / "unlit";
    fs::create_directories(unlit);
    Asset dark = viewed_round_trip(in, unlit, uint8_t(PacketType::Light));
    CHECK(dark.scene.lights.empty());
    for (const SceneNode& n : dark.scene.nodes) CHECK(n.light == kNone);
    CHECK(any_of(dark.warnings, "is shown without its light"));
    CHECK(dark.scene.cameras.size() == 3);
}

TEST_CASE("Khronos DirectionalLight (glTF-Sample-Assets) through encode and decode, when $ELLICAST_CORPUS holds it") {
    const char* corpus = std::getenv("ELLICAST_CORPUS");
    const fs::path path = corpus ? fs::path(corpus) / "Models" / "DirectionalLight" / "glTF" / "DirectionalLight.gltf" : fs::path();
    if (!corpus || !fs::exists(path)) {
        MESSAGE("skipped: set ELLICAST_CORPUS to a checkout of KhronosGroup/glTF-Sample-Assets to run it");
        return;
    }
    Asset in = load_asset(path.string());
    REQUIRE(in.scene.lights.size() == 1);
    REQUIRE(in.scene.cameras.size() == 1);
    const fs::path dir = scratch_dir("camera_light_directional");
    Asset out = viewed_round_trip(in, dir, 0);
    check_same_scene(in, out);
}
