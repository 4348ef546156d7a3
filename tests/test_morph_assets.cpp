// Morph targets (format 1.6, spec 22): a real asset (the Duck) given two morph targets, default
// weights and two animations of them (one moving a node too, one moving weights alone), read from
// glTF, sent as MORPH_DELTAS and MORPH_ANIMATION packets, shown once they have arrived, and written
// back as a glTF the Khronos validator accepts.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

const char* const kDuck = "gltf/Duck/Duck.gltf";

bool any_warning(const Asset& a, const std::string& text) {
    return std::any_of(a.warnings.begin(), a.warnings.end(), [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// The displacements the morphed Duck gets, per vertex of its POSITION accessor: target 0 inflates
// it (position: a tenth of the way away from the centre; normal: +0.1 in y), target 1 lifts its top
// (position: y grows with the height; no normal).
struct DuckTargets {
    std::vector<std::array<float, 3>> inflate, inflate_normal, lift;
};

DuckTargets duck_targets(const std::vector<uint8_t>& bin) {
    // POSITION: accessor 2, bufferView 1 (stride 12) at offset 28788, 2399 VEC3 floats.
    const size_t count = 2399, offset = 28788;
    DuckTargets t;
    for (size_t v = 0; v < count; ++v) {
        std::array<float, 3> p;
        std::memcpy(p.data(), bin.data() + offset + 12 * v, 12);
        const std::array<float, 3> centre = {13.4f, 87.0f, -3.7f};
        t.inflate.push_back({0.1f * (p[0] - centre[0]), 0.1f * (p[1] - centre[1]), 0.1f * (p[2] - centre[2])});
        t.inflate_normal.push_back({0.0f, 0.1f, 0.0f});
        t.lift.push_back({0.0f, 0.25f * (p[1] - 9.9f), 0.0f});
    }
    return t;
}

// The Duck with the two targets on its primitive, default weights (0, 0.5), an animation "Breathe"
// (node 2 slides and target 0 swells, LINEAR) and an animation "Lift" (weights only, STEP), written
// as a .gltf (its .bin and PNG beside it, the new data in a data: URI buffer).
fs::path morphed_duck(const fs::path& dir, DuckTargets& targets) {
    for (const char* file : {"Duck0.bin", "DuckCM.png"})
        if (!fs::exists(dir / file)) fs::copy_file(shared_samples() / "gltf/Duck" / file, dir / file);
    targets = duck_targets(read_bytes(dir / "Duck0.bin"));
    auto j = nlohmann::json::parse(read_bytes(shared_samples() / kDuck));
    std::vector<uint8_t> data;
    auto& views = j["bufferViews"];
    auto& accessors = j["accessors"];
    auto add = [&](const void* bytes, size_t size, size_t count, const char* type, nlohmann::json min = nullptr,
                   nlohmann::json max = nullptr) {
        nlohmann::json view = {{"buffer", 1}, {"byteOffset", data.size()}, {"byteLength", size}};
        data.insert(data.end(), static_cast<const uint8_t*>(bytes), static_cast<const uint8_t*>(bytes) + size);
        while (data.size() % 4) data.push_back(0);
        views.push_back(view);
        nlohmann::json accessor = {{"bufferView", views.size() - 1}, {"componentType", 5126}, {"count", count}, {"type", type}};
        if (!min.is_null()) accessor["min"] = min, accessor["max"] = max;
        accessors.push_back(accessor);
        return accessors.size() - 1;
    };
    auto vec3 = [&](const std::vector<std::array<float, 3>>& v, bool bounds) {
        nlohmann::json mn = nullptr, mx = nullptr;
        if (bounds) {
            std::array<float, 3> lo = v[0], hi = v[0];
            for (const auto& x : v)
                for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
            mn = lo, mx = hi;
        }
        return add(v.data(), v.size() * 12, v.size(), "VEC3", mn, mx);
    };
    const size_t inflate = vec3(targets.inflate, true), inflate_normal = vec3(targets.inflate_normal, false),
                 lift = vec3(targets.lift, true);
    auto& prim = j["meshes"][0]["primitives"][0];
    prim["targets"] = {{{"POSITION", inflate}, {"NORMAL", inflate_normal}}, {{"POSITION", lift}}};
    j["meshes"][0]["weights"] = {0.0, 0.5};
    const std::vector<float> times = {0, 1, 2}, weights = {0, 0, 1, 0.5f, 0, 0};
    const std::vector<float> slide = {0, 0, 0, 0, 10, 0, 0, 0, 0};
    const std::vector<float> step_times = {0, 0.5f}, step_weights = {0, 0, 0, 1};
    const size_t t = add(times.data(), 12, 3, "SCALAR", {0.0}, {2.0});
    const size_t w = add(weights.data(), weights.size() * 4, weights.size(), "SCALAR");
    const size_t s = add(slide.data(), slide.size() * 4, 3, "VEC3");
    const size_t st = add(step_times.data(), 8, 2, "SCALAR", {0.0}, {0.5});
    const size_t sw = add(step_weights.data(), step_weights.size() * 4, step_weights.size(), "SCALAR");
    j["animations"] = {
        {{"name", "Breathe"},
         {"samplers", {{{"input", t}, {"output", s}}, {{"input", t}, {"output", w}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "translation"}}}},
                       {{"sampler", 1}, {"target", {{"node", 2}, {"path", "weights"}}}}}}},
        {{"name", "Lift"},
         {"samplers", {{{"input", st}, {"output", sw}, {"interpolation", "STEP"}}}},
         {"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "weights"}}}}}}}};
    j["buffers"].push_back({{"byteLength", data.size()}, {"uri", "data:application/octet-stream;base64," + base64(data)}});
    const fs::path path = dir / "MorphDuck.gltf";
    std::ofstream(path, std::ios::binary) << j.dump();
    return path;
}

// The largest difference between the displacements of target `t` of every vertex of `out` and
// those of the source vertex at the same position (the nearest), over `component` (0 position,
// 1 normal).
double largest_difference(const Asset& source, const Asset& out, size_t t, size_t component) {
    const Mesh& a = source.objects.at(0);
    const VertexMorph& am = source.morphs.at(0);
    const Mesh& b = out.objects.at(0);
    const VertexMorph& bm = out.morphs.at(0);
    const size_t pa = morph_record_values(am.targets, am.attributes), pb = morph_record_values(bm.targets, bm.attributes);
    double worst = 0;
    for (size_t v = 0; v < b.positions.size(); ++v) {
        size_t nearest = 0;
        double best = 1e300;
        for (size_t u = 0; u < a.positions.size(); ++u) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d += (double(a.positions[u][k]) - b.positions[v][k]) * (double(a.positions[u][k]) - b.positions[v][k]);
            if (d < best) best = d, nearest = u;
        }
        for (size_t k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(double(am.values[nearest * pa + t * 6 + 3 * component + k]) -
                                             double(bm.values[v * pb + t * 6 + 3 * component + k])));
    }
    return worst;
}

// Every packet but those `lost` says, through a receiver, into an asset.
Asset decode_without(const EncodedAsset& encoded, const std::function<bool(size_t)>& lost) {
    return received_without(encoded.packets, lost, 24);
}

void check_writes_clean(const Asset& asset, const fs::path& path) {
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(path.string(), asset, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(path);
}

}  // namespace

TEST_CASE("a morphing Duck comes back morphing: its targets, default weights and weight animations, in a valid file") {
    if (!have_sample(kDuck)) return;
    const fs::path dir = scratch_dir("morph_duck");
    DuckTargets targets;
    const Asset in = load_asset(morphed_duck(dir, targets).string());
    REQUIRE(in.objects.size() == 1);
    REQUIRE(in.scene.meshes.size() == 1);
    CHECK(in.scene.meshes[0].weights == std::vector<float>{0.0f, 0.5f});
    REQUIRE(in.morphs.size() == 1);
    CHECK(in.morphs[0].targets == 2);
    CHECK(in.morphs[0].attributes == (kMorphPosition | kMorphNormal));
    REQUIRE(in.scene.animations.size() == 2);
    CHECK(in.scene.animations[0].tracks.size() == 2);
    CHECK(in.scene.animations[1].tracks.size() == 1);
    CHECK(in.scene.animations[1].tracks[0].path == AnimationPath::Weights);
    CHECK(in.scene.animations[1].tracks[0].targets == 2);
    for (const auto& w : in.warnings) CHECK_MESSAGE(w.find("morph target") == std::string::npos, w);

    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    CHECK(encoded.morph_packets > 0);
    // Breathe's weights join its ANIMATION; Lift stands alone: two morph animations, one track each.
    CHECK(std::count_if(encoded.packets.begin(), encoded.packets.end(),
                        [](const auto& p) { return is_packet_type(p, PacketType::MorphAnimation); }) == 2);
    CHECK(std::count_if(encoded.packets.begin(), encoded.packets.end(),
                        [](const auto& p) { return is_packet_type(p, PacketType::Animation); }) == 1);

    // Every packet: the targets on every vertex, the default weights and both animations, as they were.
    const Asset all = decode_without(encoded, [](size_t) { return false; });
    REQUIRE(all.scene.meshes.size() == 1);
    CHECK(all.scene.meshes[0].weights == std::vector<float>{0.0f, 0.5f});
    REQUIRE(all.morphs.size() == 1);
    REQUIRE(all.morphs[0].targets == 2);
    REQUIRE(all.scene.animations.size() == 2);
    CHECK(all.scene.animations[0].name == "Breathe");
    REQUIRE(all.scene.animations[0].tracks.size() == 2);
    CHECK(all.scene.animations[0].tracks[1].path == AnimationPath::Weights);
    CHECK(all.scene.animations[0].tracks[1].values == in.scene.animations[0].tracks[1].values);
    CHECK(all.scene.animations[1].name == "Lift");
    CHECK(all.scene.animations[1].tracks[0].interpolation == Interpolation::Step);
    const fs::path glb = dir / "all.glb";
    check_writes_clean(all, glb);

    // Read back: the written file's vertices carry their source vertex's displacements. The Duck
    // comes back exact (the exact layer), so each vertex is a source vertex, with its own record,
    // quantized.
    const Asset back = load_asset(glb.string());
    REQUIRE(back.morphs.size() == 1);
    REQUIRE(back.morphs[0].targets == 2);
    CHECK(back.scene.meshes.at(0).weights == std::vector<float>{0.0f, 0.5f});
    // Within the quantization of spec 22.1: half a step of the slot's scale (its largest component
    // over 32767), plus float rounding.
    for (size_t t = 0; t < 2; ++t)
        for (size_t component = 0; component < 2; ++component) {
            CAPTURE(t);
            CAPTURE(component);
            double largest = 0;
            for (size_t v = 0; v < in.objects[0].positions.size(); ++v)
                for (size_t k = 0; k < 3; ++k)
                    largest = std::max(largest, double(std::abs(in.morphs[0].values[v * 12 + t * 6 + 3 * component + k])));
            CHECK(largest_difference(in, back, t, component) <= largest / 65534 * 1.001 + 1e-7);
        }
    REQUIRE(back.scene.animations.size() == 2);
    CHECK(back.scene.animations[0].tracks.size() == 2);
}

TEST_CASE("the Duck keeps its base shape, and says why, until its displacements arrive, and no animation is played in part") {
    if (!have_sample(kDuck)) return;
    const fs::path dir = scratch_dir("morph_duck_lossy");
    DuckTargets targets;
    const Asset in = load_asset(morphed_duck(dir, targets).string());
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    auto of_type = [&](PacketType type) {
        std::vector<size_t> out;
        for (size_t i = 0; i < encoded.packets.size(); ++i)
            if (is_packet_type(encoded.packets[i], type)) out.push_back(i);
        return out;
    };
    const auto deltas = of_type(PacketType::MorphDeltas), morph_animations = of_type(PacketType::MorphAnimation);
    REQUIRE(deltas.size() >= 2);
    REQUIRE(morph_animations.size() == 2);

    SUBCASE("every MORPH_DELTAS packet lost: the base shape, and no weight track") {
        const Asset a = decode_without(encoded, [&](size_t i) { return is_packet_type(encoded.packets[i], PacketType::MorphDeltas); });
        CHECK(a.scene.meshes.at(0).weights.empty());
        CHECK(any_warning(a, "is shown without its 2 morph targets"));
        CHECK(any_warning(a, "no displacements of object 0 have arrived"));
        // Breathe still slides (its weight track left out); Lift has nothing left to move.
        REQUIRE(a.scene.animations.size() == 1);
        CHECK(a.scene.animations[0].tracks.size() == 1);
        CHECK(a.scene.animations[0].tracks[0].path == AnimationPath::Translation);
        check_writes_clean(a, dir / "no_deltas.glb");
    }
    SUBCASE("Breathe's MORPH_ANIMATION packet lost: Breathe is not played at all, Lift is") {
        const Asset a = decode_without(encoded, [&](size_t i) { return i == morph_animations[0]; });
        REQUIRE(a.scene.animations.size() == 1);
        CHECK(a.scene.animations[0].name == "Lift");
        CHECK(any_warning(a, "morph animations did not arrive at all; the animations wait for them"));
        check_writes_clean(a, dir / "no_breathe_weights.glb");
    }
    SUBCASE("half the POINTS and half the MORPH_DELTAS lost: still morphing, from the nearest points that have arrived") {
        size_t n = 0;
        const Asset a = decode_without(encoded, [&](size_t i) {
            return (is_packet_type(encoded.packets[i], PacketType::Points) || is_packet_type(encoded.packets[i], PacketType::MappedPoints) || is_packet_type(encoded.packets[i], PacketType::MorphDeltas)) &&
                   (n++ % 2 == 0);
        });
        CHECK(a.scene.meshes.at(0).weights == std::vector<float>{0.0f, 0.5f});
        REQUIRE(a.morphs.at(0).targets == 2);
        CHECK(a.morphs[0].values.size() == morph_record_values(2, 3) * a.objects[0].positions.size());
        CHECK(a.scene.animations.size() == 2);
        check_writes_clean(a, dir / "half.glb");
    }
}

TEST_CASE("a receiver waiting for the morphing Duck is not done before its last MORPH_DELTAS and MORPH_ANIMATION packets") {
    if (!have_sample(kDuck)) return;
    const fs::path dir = scratch_dir("morph_duck_reception");
    DuckTargets targets;
    const Asset in = load_asset(morphed_duck(dir, targets).string());
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    // Every packet but one of a kind, then that one: complete only with it.
    for (PacketType held_back : {PacketType::MorphDeltas, PacketType::MorphAnimation})
        check_complete_only_with_last(encoded.packets, held_back);
}

TEST_CASE("Khronos SimpleMorph (a real asset, committed) comes back with its two targets, default weights and weight animation") {
    const fs::path file = source_dir() / "samples" / "khronos" / "SimpleMorph" / "SimpleMorph.gltf";
    const Asset in = load_asset(file.string());
    REQUIRE(in.morphs.size() == 1);
    REQUIRE(in.morphs[0].targets == 2);
    CHECK(in.morphs[0].attributes == kMorphPosition);
    CHECK(in.scene.meshes.at(0).weights == std::vector<float>{0.5f, 0.5f});
    REQUIRE(in.scene.animations.size() == 1);
    REQUIRE(in.scene.animations[0].tracks.size() == 1);
    CHECK(in.scene.animations[0].tracks[0].path == AnimationPath::Weights);
    CHECK(in.scene.animations[0].tracks[0].times.size() == 5);
    for (const auto& w : in.warnings) CHECK_MESSAGE(w.find("morph") == std::string::npos, w);

    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    const Asset all = decode_without(encoded, [](size_t) { return false; });
    REQUIRE(all.morphs.at(0).targets == 2);
    REQUIRE(all.scene.animations.size() == 1);
    CHECK(all.scene.animations[0].tracks[0].values == in.scene.animations[0].tracks[0].values);
    const fs::path glb = scratch_dir("simple_morph") / "SimpleMorph.glb";
    check_writes_clean(all, glb);
    // The triangle comes back exact: its three vertices with the source's displacements (1, 0 and
    // -1 are multiples of the scale: exact).
    const Asset back = load_asset(glb.string());
    REQUIRE(back.objects.at(0).positions.size() == 3);
    REQUIRE(back.morphs.at(0).targets == 2);
    for (size_t v = 0; v < 3; ++v) {
        // The source vertex at the same place (within the 14-bit quantization step).
        size_t source = 0;
        double best = 1e300;
        for (size_t u = 0; u < 3; ++u) {
            double d = 0;
            for (int k = 0; k < 3; ++k)
                d += std::pow(double(in.objects[0].positions[u][k]) - back.objects[0].positions[v][k], 2);
            if (d < best) best = d, source = u;
        }
        CHECK(best < 1e-6);
        for (size_t k = 0; k < 6; ++k)
            CHECK(back.morphs[0].values[v * 6 + k] == doctest::Approx(in.morphs[0].values[source * 6 + k]).epsilon(1e-6));
    }
}

TEST_CASE("broken morph targets in a glTF are named in a warning and cost the targets, not the model") {
    const fs::path source = source_dir() / "samples" / "khronos" / "SimpleMorph" / "SimpleMorph.gltf";
    const fs::path dir = scratch_dir("morph_broken");
    auto edited = [&](const std::string& name, const std::function<void(nlohmann::json&)>& edit) {
        auto j = nlohmann::json::parse(read_bytes(source));
        edit(j);
        const fs::path path = dir / (name + ".gltf");
        std::ofstream(path, std::ios::binary) << j.dump();
        return load_asset(path.string());
    };
    SUBCASE("a target accessor of another count than the vertices") {
        const Asset a = edited("count", [](nlohmann::json& j) { j["accessors"][3]["count"] = 2; });
        CHECK(any_warning(a, "target 1 POSITION: not a VEC3 of the vertex count; its morph targets are not sent"));
        CHECK(any_warning(a, "its morph targets are not sent (the base shape is)"));
        CHECK(a.scene.meshes.at(0).weights.empty());
        CHECK(a.objects.at(0).positions.size() == 3);
        // The weight channel has nothing left to move.
        CHECK(any_warning(a, "moves morph target weights of a node whose mesh's morph targets are not sent"));
        CHECK(a.scene.animations.empty());
    }
    SUBCASE("default weights of another count than the targets") {
        const Asset a = edited("weights", [](nlohmann::json& j) { j["meshes"][0]["weights"] = {0.5}; });
        CHECK(any_warning(a, "1 default weights for 2 morph targets; sent as 0"));
        CHECK(a.scene.meshes.at(0).weights == std::vector<float>{0.0f, 0.0f});
        CHECK(a.morphs.at(0).targets == 2);
    }
    SUBCASE("a weight channel whose output is not one weight per target per key") {
        const Asset a = edited("output", [](nlohmann::json& j) { j["accessors"][5]["count"] = 9; });
        CHECK(any_warning(a, "channel 0"));
        CHECK(a.scene.animations.empty());
        CHECK(a.morphs.at(0).targets == 2);  // the targets still travel
    }
    SUBCASE("a target that names an accessor that does not exist") {
        const Asset a = edited("missing", [](nlohmann::json& j) {
            j["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = 99;
        });
        CHECK(any_warning(a, "its morph targets are not sent"));
        CHECK(a.scene.meshes.at(0).weights.empty());
    }
}
