// The scene (format 1.1): the node and mesh tables, materials and textures that SCENE, MATERIAL and
// TEXTURE_FRAGMENT packets carry, their payloads, and the whole scene description a sender cuts into
// packets (with the animations of animation.h and the skins of skin.h). Follows spec/format.md
// section 15 (Format 1.1 additions: scene, materials, textures: 15.1 SCENE, 15.2 MATERIAL,
// 15.3 TEXTURE_FRAGMENT), with the node record's skin of format 1.5 (section 21) and the mesh record's
// targets of format 1.6 (section 22). What a receiver shows (15.4) is in received_stream.h.
//
// All three types are sent with the skippable flag: a 1.0 decoder still reconstructs every object,
// only without placement and appearance.
#pragma once

#include "ellicast/format/animation.h"
#include "ellicast/format/camera_light.h"
#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"
#include "ellicast/format/extras.h"
#include "ellicast/format/skin.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

// A node of the scene graph. Roots have parent == kNone; a node's children are the nodes naming it
// as parent, in index order. The transform is either a column-major 4x4 matrix or T * R * S.
struct SceneNode {
    uint16_t index = 0;
    uint16_t parent = kNone;
    uint16_t mesh = kNone;  // index into the mesh table
    std::string name;       // UTF-8, at most 255 bytes
    bool has_matrix = false;
    std::array<float, 16> matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::array<float, 3> translation{0, 0, 0};
    std::array<float, 4> rotation{0, 0, 0, 1};  // quaternion x, y, z, w (glTF order)
    std::array<float, 3> scale{1, 1, 1};
    uint16_t skin = kNone;  // format 1.5 (spec 21): index into the skin table
    uint16_t camera = kNone;  // format 1.10 (spec 26.1): index into the camera table
    uint16_t light = kNone;   // format 1.10 (spec 26.1): index into the light table
    bool operator==(const SceneNode&) const = default;
};

// A mesh: primitives, each an object of the stream drawn with a material. Several nodes naming the
// same mesh instance it: its objects travel once.
struct ScenePrimitive {
    uint16_t object = 0;
    uint16_t material = kNone;
    bool operator==(const ScenePrimitive&) const = default;
};
struct SceneMesh {
    uint16_t index = 0;
    std::string name;
    std::vector<ScenePrimitive> primitives;
    // Format 1.6 (spec 22): one default weight per morph target (glTF mesh.weights); empty for a
    // mesh without targets. At most 255.
    std::vector<float> weights;
    bool operator==(const SceneMesh&) const = default;
};

// The records one SCENE packet carries, and the sizes of the whole tables.
struct SceneBatch {
    uint16_t node_count = 0;
    uint16_t mesh_count = 0;
    std::vector<SceneNode> nodes;
    std::vector<SceneMesh> meshes;
};

enum class AlphaMode : uint8_t { Opaque = 0, Mask = 1, Blend = 2 };

struct TextureRef {
    uint16_t texture = kNone;  // index into the texture table
    uint8_t texcoord = 0;      // TEXCOORD_n set
    float scale = 1;           // normalTexture.scale / occlusionTexture.strength; 1 otherwise
    bool operator==(const TextureRef&) const = default;
};

// glTF PBR metallic-roughness material.
struct Material {
    uint16_t index = 0;
    uint16_t material_count = 0;  // size of the whole material table
    std::string name;
    std::array<float, 4> base_color{1, 1, 1, 1};
    float metallic = 1;
    float roughness = 1;
    std::array<float, 3> emissive{0, 0, 0};
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;
    TextureRef base_color_texture, metallic_roughness_texture, normal_texture, occlusion_texture, emissive_texture;
    // Format 1.3 (spec 18.1): MATERIAL flags bit 0, the material has a MATERIAL_EXTENSIONS packet.
    bool has_extensions = false;
    // Sender side: the patch (spec 18.2) packetize_scene sends in a MATERIAL_EXTENSIONS packet (and
    // then sets has_extensions); empty: none. A decoded MATERIAL leaves it empty: a receiver finds
    // patches in ReceivedStream::material_extensions().
    std::string extensions;
    bool operator==(const Material&) const = default;
};

enum class ImageType : uint8_t { Png = 1, Jpeg = 2 };

// What every fragment of a texture repeats, so that any fragment is useful on its own.
struct TextureInfo {
    uint16_t index = 0;
    uint16_t texture_count = 0;  // size of the whole texture table
    ImageType image_type = ImageType::Png;
    uint16_t mag_filter = 0, min_filter = 0;  // glTF sampler values, 0 = unset
    uint16_t wrap_s = 10497, wrap_t = 10497;  // REPEAT
    uint32_t image_size = 0;                  // bytes of the whole image file
    uint32_t image_crc = 0;                   // CRC-32C of the whole image file
    bool operator==(const TextureInfo&) const = default;
};

struct TextureFragment {
    TextureInfo info;
    uint32_t offset = 0;
    std::vector<uint8_t> data;
};

inline constexpr size_t kTextureFragmentHeaderSize = 28;

// Everything of the scene that travels besides geometry.
struct SceneDescription {
    std::vector<SceneNode> nodes;  // node i has index i
    std::vector<SceneMesh> meshes; // mesh i has index i
    std::vector<Material> materials;
    struct Texture {
        TextureInfo info;           // index, counts, size and CRC are filled in by packetize_scene
        std::vector<uint8_t> image; // the image file bytes as the asset had them
    };
    std::vector<Texture> textures;
    std::vector<SceneAnimation> animations;  // format 1.4
    std::vector<SceneSkin> skins;            // format 1.5: SceneNode::skin indexes it
    // Format 1.10 (spec 26): SceneNode::camera and ::light index them; index and count are filled in
    // by packetize_scene.
    std::vector<SceneCamera> cameras;
    std::vector<SceneLight> lights;
    // Format 1.12 (spec 28): the extras texts, at most one a target, each naming an element of these
    // tables (kind Animation: an index into `animations`, which packetize_scene sends as the ANIMATION
    // or MORPH_ANIMATION table's, spec 28.1; kind MorphAnimation is not used here).
    std::vector<SceneExtras> extras;
    // Format 1.13 (spec 29): the names of the extensions the source asset required, in its order (at
    // most 255, each a name of spec 29.1, each once).
    std::vector<std::string> required_extensions;
};

std::vector<uint8_t> encode_scene_payload(const SceneBatch& batch);
// `version_minor`: that of the packet; a node record's skin (spec 21) is read only from 1.5 on, its
// camera and light (spec 26.1) only from 1.10 on.
Error decode_scene_payload(std::span<const uint8_t> payload, SceneBatch& out, uint8_t version_minor = kSpecMinor);
std::vector<uint8_t> encode_material_payload(const Material& material);
Error decode_material_payload(std::span<const uint8_t> payload, Material& out);
std::vector<uint8_t> encode_texture_fragment_payload(const TextureFragment& fragment);
Error decode_texture_fragment_payload(std::span<const uint8_t> payload, TextureFragment& out);

struct ScenePackets {
    std::vector<std::vector<uint8_t>> scene;      // SCENE packets
    std::vector<std::vector<uint8_t>> materials;  // one MATERIAL packet per material, each followed by
                                                  // its MATERIAL_EXTENSIONS packet when it has one
    std::vector<uint16_t> extensions_too_large;   // materials whose patch did not fit a packet: sent without
    std::vector<std::vector<uint8_t>> textures;   // TEXTURE_FRAGMENT packets, texture by texture
    std::vector<std::vector<uint8_t>> animations; // ANIMATION packets, track by track (format 1.4), then
                                                  // MORPH_ANIMATION packets (format 1.6)
    std::vector<std::vector<uint8_t>> skins;      // SKIN packets, skin by skin (format 1.5)
    std::vector<std::vector<uint8_t>> cameras_lights;  // CAMERA, then LIGHT packets (format 1.10)
    std::vector<std::vector<uint8_t>> extras;     // EXTRAS packets, text by text in target order (format 1.12)
    std::vector<std::vector<uint8_t>> required_extensions;  // REQUIRED_EXTENSION packets, in name order (format 1.13)
};

// Cuts a scene description into packets of at most `packet_size` bytes, numbered from
// `first_sequence`. MalformedPayload when a table is larger than 65535 entries, a name longer than
// 255 bytes, a record does not fit one packet, a reference points outside its table, or an image is
// empty or over 4 GiB; for animations when a table has more than 65535 entries, a track has no key,
// values of another count than its keys need, a float that is not finite, negative or not strictly
// increasing times, a cubic spline of one key, or a node outside the node table; for cameras and
// lights (format 1.10) when a table has more than 65534 entries, a record breaks spec 26.2 / 26.3, or a
// node names one outside its table; for extras (format 1.12) when a target is named twice, lies outside
// its table, or its text is empty, longer than 65536 bytes or not acceptable JSON (spec 28.1); for required extensions
// (format 1.13) when there are more than 255, or one is not a name of spec 29.1 or is listed twice.
Error packetize_scene(const SceneDescription& scene, size_t packet_size, uint32_t stream_id, uint32_t first_sequence,
                      ScenePackets& out);

}  // namespace ellicast
