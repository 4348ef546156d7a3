// Animations (format 1.4) and morph animations (format 1.6): the tracks of keys that ANIMATION and
// MORPH_ANIMATION packets carry, their payloads, and an animation as a sender has it. Follows
// spec/format.md sections 20 (Format 1.4 addition: animations: 20.1 ANIMATION payload) and 22.2
// (MORPH_ANIMATION payload).
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

// Animations (format 1.4, spec 20). A track moves one property of one node over keys.
// Weights (morph target weights, format 1.6) travels in MORPH_ANIMATION packets only (spec 22.2).
enum class AnimationPath : uint8_t { Translation = 0, Rotation = 1, Scale = 2, Weights = 3 };
enum class Interpolation : uint8_t { Linear = 0, Step = 1, CubicSpline = 2 };

// What every packet of a track repeats.
struct AnimationTrackInfo {
    uint16_t node = 0;  // index of the SCENE node table
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t key_count = 0;
    uint8_t targets = 0;  // Weights: the weights per value, C (1..255); 0 for the other paths
    bool operator==(const AnimationTrackInfo&) const = default;
};

// f32 values per key: C (3, or 4 for rotation, `targets` for weights), three times that for cubic
// splines.
size_t animation_values_per_key(AnimationPath path, Interpolation interpolation, size_t targets = 0);

// One ANIMATION packet's content: keys [first_key, first_key + times.size()) of one track.
struct AnimationPiece {
    uint16_t animation = 0, animation_count = 0;
    uint16_t joins = kNone;  // MORPH_ANIMATION only: the ANIMATION this morph animation joins
    uint16_t track = 0, track_count = 0;
    std::string name;  // the animation's
    AnimationTrackInfo info;
    uint32_t first_key = 0;
    std::vector<float> times;   // one per key
    std::vector<float> values;  // animation_values_per_key per key
};
inline constexpr size_t kAnimationHeaderSize = 24;
std::vector<uint8_t> encode_animation_payload(const AnimationPiece& piece);
Error decode_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out);
// MORPH_ANIMATION (format 1.6, spec 22.2): the same content for a track of weights (info.path
// Weights, info.targets C) of a morph animation, which joins the ANIMATION `joins` or stands alone.
inline constexpr size_t kMorphAnimationHeaderSize = 26;
std::vector<uint8_t> encode_morph_animation_payload(const AnimationPiece& piece);
Error decode_morph_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out);

// An animation as a sender has it: tracks of whole key lists.
struct SceneAnimation {
    std::string name;
    struct Track {
        uint16_t node = 0;
        AnimationPath path = AnimationPath::Translation;
        Interpolation interpolation = Interpolation::Linear;
        uint8_t targets = 0;  // Weights (format 1.6): weights per value
        std::vector<float> times;
        std::vector<float> values;
    };
    // Tracks of every path: packetize_scene sends translation, rotation and scale tracks as
    // ANIMATION packets and weights tracks as MORPH_ANIMATION packets (spec 22.2, 22.5).
    std::vector<Track> tracks;
};

}  // namespace ellicast
