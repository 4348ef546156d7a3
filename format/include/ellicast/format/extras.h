// Extras (format 1.12): the glTF `extras` of the asset, of its scene and of the elements of the
// stream's tables, as JSON texts that EXTRAS packets carry in fragments. Follows spec/format.md
// section 28 (Format 1.12 addition: extras): 28.1 EXTRAS payload, its checks and what completes a
// text; what a receiver keeps of them is in received_stream.h.
#pragma once

#include "ellicast/format/error.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ellicast {

// What a text belongs to (spec 28.1, target_kind).
enum class ExtrasTarget : uint8_t {
    Asset = 0,
    Scene = 1,
    Node = 2,
    Mesh = 3,
    Material = 4,
    Texture = 5,
    Animation = 6,       // an animation of the ANIMATION table
    Skin = 7,
    Camera = 8,
    Light = 9,
    MorphAnimation = 10  // a morph animation of the MORPH_ANIMATION table that joins none
};
inline constexpr uint8_t kExtrasTargetKinds = 11;
inline constexpr size_t kExtrasHeaderSize = 20;
inline constexpr uint32_t kMaxExtrasText = 65536;  // bytes of one text (spec 28.1, rule 4)

// "asset", "scene", "node", "mesh", "material", "texture", "animation", "skin", "camera", "light",
// "morph animation".
const char* extras_target_name(ExtrasTarget kind);
// A target as messages name it: "asset", "scene", "node 3", "morph animation 0".
std::string extras_target_label(ExtrasTarget kind, uint16_t index);

// Sender side: one element's extras, the JSON text as it travels (SceneDescription::extras).
struct SceneExtras {
    ExtrasTarget kind = ExtrasTarget::Asset;
    uint16_t index = 0;  // 0 for the asset and the scene
    std::string text;
    bool operator==(const SceneExtras&) const = default;
};

// One EXTRAS payload.
struct ExtrasFragment {
    ExtrasTarget kind = ExtrasTarget::Asset;
    uint16_t index = 0;
    uint16_t text_count = 0;  // texts in the whole stream
    uint32_t text_size = 0;   // bytes of the whole text
    uint32_t text_crc = 0;    // CRC-32C of the whole text
    uint32_t offset = 0;      // of this fragment's bytes in the text
    std::vector<uint8_t> data;
};

std::vector<uint8_t> encode_extras_payload(const ExtrasFragment& fragment);
// Spec 28.1, rules 1..5 (one reason for all): Ok or MalformedPayload.
Error decode_extras_payload(std::span<const uint8_t> payload, ExtrasFragment& out);
// Whether a whole text is acceptable (spec 28.1: rules 2..6 of 18.2 on any JSON value, depth 32).
bool acceptable_extras_text(std::string_view text);

}  // namespace ellicast
