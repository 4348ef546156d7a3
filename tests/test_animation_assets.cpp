// Animations of real assets (format 1.4, spec 20): read from glTF, sent as ANIMATION packets, shown
// once whole, written back as glTF animations the Khronos validator accepts.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <algorithm>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

bool is_animation(const std::vector<uint8_t>& p) { return p.size() > 6 && p[6] == 0x14; }

Asset decode_without(const EncodedAsset& encoded, const std::function<bool(size_t)>& lost) {
    return received_without(encoded.packets, lost, 24);
}

void check_valid_without_warnings(const Asset& asset, const fs::path& path) {
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset(path.string(), asset, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(path);
}

}  // namespace

TEST_CASE("the milk truck's wheels turn after a broadcast: its animation comes back key for key, and not before it is whole") {
    const std::string file = "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf";
    if (!have_sample(file)) return;
    const Asset in = load_asset(sample(file));
    REQUIRE(in.scene.animations.size() == 1);
    const SceneAnimation& wheels = in.scene.animations[0];
    REQUIRE(wheels.tracks.size() == 2);
    for (const auto& t : wheels.tracks) {
        CHECK(t.path == AnimationPath::Rotation);
        CHECK(t.interpolation == Interpolation::Linear);
        CHECK(t.times.size() > 10);
        CHECK(t.values.size() == 4 * t.times.size());
        CHECK(in.scene.nodes.at(t.node).mesh != kNone);  // a node that shows the wheels
    }
    CHECK_FALSE(std::any_of(in.warnings.begin(), in.warnings.end(),
                            [](const std::string& w) { return w.find("animation") != std::string::npos; }));

    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    const size_t animation_packets = size_t(std::count_if(encoded.packets.begin(), encoded.packets.end(), is_animation));
    CHECK(animation_packets >= 2);

    // Every packet: the same animation, and a file the validator accepts without a warning.
    const Asset all = decode_without(encoded, [](size_t) { return false; });
    check_same_scene(in, all);
    const fs::path dir = scratch_dir("animation_truck");
    check_valid_without_warnings(all, dir / "truck.glb");

    // One ANIMATION packet lost: the animation is not shown (no wheel turning while the other stands
    // still), the receiver says why, and the file is still valid.
    size_t first = 0;
    while (!is_animation(encoded.packets[first])) ++first;
    const Asset partial = decode_without(encoded, [&](size_t i) { return i == first; });
    CHECK(partial.scene.animations.empty());
    CHECK(std::any_of(partial.warnings.begin(), partial.warnings.end(),
                      [](const std::string& w) { return w.find("animation 0 not shown") != std::string::npos; }));
    check_valid_without_warnings(partial, dir / "partial.glb");

    // The node a track moves did not arrive: that track is left out, the other still turns its wheels.
    const uint16_t moved = wheels.tracks[0].node;
    const Asset no_node = decode_without(encoded, [&](size_t i) {
        // Drop the SCENE packet holding node `moved` (every other packet arrives).
        PacketView v;
        if (parse_packet(encoded.packets[i], v) != Error::Ok || v.header.type != 0x10) return false;
        SceneBatch batch;
        if (decode_scene_payload(v.payload, batch) != Error::Ok) return false;
        return std::any_of(batch.nodes.begin(), batch.nodes.end(), [&](const SceneNode& n) { return n.index == moved; });
    });
    if (!no_node.scene.animations.empty()) {
        CHECK(no_node.scene.animations[0].tracks.size() < 2);
    }
    check_valid_without_warnings(no_node, dir / "no_node.glb");
}

TEST_CASE("every glTF sample keeps its animations through encode, packets and decode") {
    for (const char* file : kGltfSamples) {
        CAPTURE(file);
        if (!have_sample(file)) continue;
        const Asset in = load_asset(sample(file));
        EncodedAsset encoded;
        std::string error;
        REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
        const Asset out = decode_without(encoded, [](size_t) { return false; });
        REQUIRE(out.scene.animations.size() == in.scene.animations.size());
        for (size_t a = 0; a < in.scene.animations.size(); ++a) {
            REQUIRE(out.scene.animations[a].tracks.size() == in.scene.animations[a].tracks.size());
            for (size_t t = 0; t < in.scene.animations[a].tracks.size(); ++t) {
                CHECK(out.scene.animations[a].tracks[t].times == in.scene.animations[a].tracks[t].times);
                CHECK(out.scene.animations[a].tracks[t].values == in.scene.animations[a].tracks[t].values);
            }
        }
    }
}
