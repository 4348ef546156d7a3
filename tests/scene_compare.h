// Comparing two scenes the way a user would: the same nodes (names, hierarchy, transforms), the same
// materials (factors, modes, textures byte for byte). Shared by the scene writer and round-trip tests.
#pragma once

#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include <ellicast/broadcast/reception.h>
#include "encode_options.h"
#include "support.h"

#include <algorithm>
#include <functional>
#include <tuple>

#include <Eigen/Dense>

#include <cmath>
#include <string>

namespace ellicast::test {

// Every glTF sample of ../shared/samples (paths relative to it), and one's full path.
inline constexpr const char* kGltfSamples[] = {
    "gltf/Box-glb/Box.glb",
    "gltf/Box-glb/Box_Draco.glb",
    "gltf/Duck/Duck.gltf",
    "gltf/Duck-glb/Duck.glb",
    "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf",
    "gltf/Fox/Fox.gltf",
    "gltf/VertexColorTest/VertexColorTest.gltf",
    "gltf/SphereTwoMaterials/sphere_two_materials_mesh_and_point_cloud.gltf"};
inline std::string sample(const std::string& rel) { return (shared_samples() / rel).string(); }

// Whether `packet` is of `type` (the header's type byte).
inline bool is_packet_type(const std::vector<uint8_t>& packet, PacketType type) {
    return packet.size() > 6 && packet[6] == uint8_t(type);
}

// A receiver given every packet but the last of `type` is not complete, and is with it.
inline void check_complete_only_with_last(const std::vector<std::vector<uint8_t>>& packets, PacketType type) {
    CAPTURE(int(type));
    size_t last = packets.size();
    for (size_t i = 0; i < packets.size(); ++i)
        if (is_packet_type(packets[i], type)) last = i;
    REQUIRE(last < packets.size());
    broadcast::Reception reception;
    for (size_t i = 0; i < packets.size(); ++i)
        if (i != last) reception.take(packets[i]);
    CHECK_FALSE(reception.complete());
    reception.take(packets[last]);
    CHECK(reception.complete());
}

// What a receiver makes of `packets` without those for which lost(index) holds, decoded at grid
// `grid`; `out`, when given, gets the stream it held.
inline Asset received_without(const std::vector<std::vector<uint8_t>>& packets, const std::function<bool(size_t)>& lost,
                              uint32_t grid, ReceivedStream* out = nullptr) {
    ReceivedStream stream;
    for (size_t i = 0; i < packets.size(); ++i)
        if (!lost(i)) REQUIRE(stream.add_packet(packets[i], i) == Error::Ok);
    Asset asset;
    StreamDecodeReport report;
    std::string error;
    DecodeOptions decoding;
    decoding.grid_resolution = grid;
    REQUIRE_MESSAGE(decode_asset(stream, decoding, asset, report, error), error);
    if (out) *out = std::move(stream);
    return asset;
}

// The image bytes a texture reference of `a` shows (empty when none).
inline std::vector<uint8_t> referenced_image(const Asset& a, const TextureRef& ref) {
    if (ref.texture == kNone || ref.texture >= a.scene.textures.size()) return {};
    return a.scene.textures[ref.texture].image;
}

// Checks that `out` has the scene of `in`: node count, names, parents, which nodes show a mesh and
// how many primitives it has, transforms (to float precision), materials with their factors, modes
// and texture images byte for byte, (format 1.10) the same cameras and lights on the same nodes, and
// (format 1.12) the same extras on the same elements, (format 1.13) the same required extensions.
inline void check_same_scene(const Asset& in, const Asset& out) {
    REQUIRE(out.scene.nodes.size() == in.scene.nodes.size());
    for (size_t i = 0; i < in.scene.nodes.size(); ++i) {
        const SceneNode& a = in.scene.nodes[i];
        const SceneNode& b = out.scene.nodes[i];
        CAPTURE(i);
        CHECK(a.name == b.name);
        CHECK(a.parent == b.parent);
        REQUIRE((a.mesh == kNone) == (b.mesh == kNone));
        if (a.mesh != kNone)
            CHECK(in.scene.meshes[a.mesh].primitives.size() == out.scene.meshes[b.mesh].primitives.size());
        CHECK(a.camera == b.camera);
        CHECK(a.light == b.light);
        Eigen::Matrix4d ma = node_matrix(a), mb = node_matrix(b);
        CHECK_MESSAGE((ma - mb).cwiseAbs().maxCoeff() <= 1e-5 * std::max(1.0, ma.cwiseAbs().maxCoeff()),
                      "transform of node " << i << " differs");
    }
    REQUIRE(out.scene.materials.size() == in.scene.materials.size());
    for (size_t i = 0; i < in.scene.materials.size(); ++i) {
        const Material& a = in.scene.materials[i];
        const Material& b = out.scene.materials[i];
        CAPTURE(i);
        CHECK(a.name == b.name);
        for (int k = 0; k < 4; ++k) CHECK(a.base_color[k] == doctest::Approx(b.base_color[k]));
        for (int k = 0; k < 3; ++k) CHECK(a.emissive[k] == doctest::Approx(b.emissive[k]));
        CHECK(a.metallic == doctest::Approx(b.metallic));
        CHECK(a.roughness == doctest::Approx(b.roughness));
        CHECK(a.alpha_mode == b.alpha_mode);
        if (a.alpha_mode == AlphaMode::Mask) CHECK(a.alpha_cutoff == doctest::Approx(b.alpha_cutoff));
        CHECK(a.double_sided == b.double_sided);
        const TextureRef* ra[] = {&a.base_color_texture, &a.metallic_roughness_texture, &a.normal_texture,
                                  &a.occlusion_texture, &a.emissive_texture};
        const TextureRef* rb[] = {&b.base_color_texture, &b.metallic_roughness_texture, &b.normal_texture,
                                  &b.occlusion_texture, &b.emissive_texture};
        for (int s = 0; s < 5; ++s) {
            CAPTURE(s);
            CHECK(referenced_image(in, *ra[s]) == referenced_image(out, *rb[s]));
            if (ra[s]->texture != kNone) CHECK(ra[s]->scale == doctest::Approx(rb[s]->scale));
        }
    }
    // Cameras and lights (format 1.10): the same records (f32 values, names), in the same order.
    REQUIRE(out.scene.cameras.size() == in.scene.cameras.size());
    for (size_t i = 0; i < in.scene.cameras.size(); ++i) {
        SceneCamera a = in.scene.cameras[i], b = out.scene.cameras[i];
        a.index = b.index = 0, a.camera_count = b.camera_count = 0;  // table bookkeeping, not the camera
        CAPTURE(i);
        CHECK(a == b);
    }
    REQUIRE(out.scene.lights.size() == in.scene.lights.size());
    for (size_t i = 0; i < in.scene.lights.size(); ++i) {
        SceneLight a = in.scene.lights[i], b = out.scene.lights[i];
        a.index = b.index = 0, a.light_count = b.light_count = 0;
        CAPTURE(i);
        CHECK(a == b);
    }
    // Extras (format 1.12): the same texts on the same elements.
    const auto texts = [](const Asset& a) {
        std::vector<std::tuple<uint8_t, uint16_t, std::string>> out;
        for (const SceneExtras& e : a.scene.extras) out.emplace_back(uint8_t(e.kind), e.index, e.text);
        std::sort(out.begin(), out.end());
        return out;
    };
    CHECK(texts(in) == texts(out));
    // Required extensions (format 1.13): the same names in the same order.
    CHECK(in.scene.required_extensions == out.scene.required_extensions);
    // Animations (format 1.4): the same tracks over the same nodes, key for key.
    REQUIRE(out.scene.animations.size() == in.scene.animations.size());
    for (size_t i = 0; i < in.scene.animations.size(); ++i) {
        const SceneAnimation& a = in.scene.animations[i];
        const SceneAnimation& b = out.scene.animations[i];
        CAPTURE(i);
        CHECK(a.name == b.name);
        REQUIRE(a.tracks.size() == b.tracks.size());
        for (size_t t = 0; t < a.tracks.size(); ++t) {
            CAPTURE(t);
            CHECK(a.tracks[t].node == b.tracks[t].node);
            CHECK(a.tracks[t].path == b.tracks[t].path);
            CHECK(a.tracks[t].interpolation == b.tracks[t].interpolation);
            CHECK(a.tracks[t].times == b.tracks[t].times);
            CHECK(a.tracks[t].values == b.tracks[t].values);
        }
    }
}

}  // namespace ellicast::test
