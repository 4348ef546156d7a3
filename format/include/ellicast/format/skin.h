// Skins (format 1.5): the joints that SKIN packets carry and the joints and weights of each point that
// JOINT_WEIGHTS packets carry, their payloads and packetizing. Follows spec/format.md section 21
// (Format 1.5 addition: skins): 21.1 SKIN payload; 21.2 JOINT_WEIGHTS payload.
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"
#include "ellicast/format/stream_info.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

// Skins (format 1.5, spec 21). A joint: a node of the SCENE table and its inverse bind matrix.
struct SkinJoint {
    uint16_t node = 0;
    std::array<float, 16> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
    bool operator==(const SkinJoint&) const = default;
};

// One SKIN packet's content: joints [first_joint, first_joint + joints.size()) of one skin.
struct SkinPiece {
    uint16_t skin = 0, skin_count = 0;
    uint16_t joint_count = 0, first_joint = 0;
    uint16_t skeleton = kNone;
    std::string name;  // the skin's
    std::vector<SkinJoint> joints;
};
inline constexpr size_t kSkinHeaderSize = 14;
inline constexpr size_t kSkinJointSize = 66;
std::vector<uint8_t> encode_skin_payload(const SkinPiece& piece);
Error decode_skin_payload(std::span<const uint8_t> payload, SkinPiece& out);

// A skin as a sender has it.
struct SceneSkin {
    std::string name;
    uint16_t skeleton = kNone;
    std::vector<SkinJoint> joints;
};

// The joints and weights of one point (spec 21.2): `count` influences (1..4), weights in 255ths,
// each at least 1, summing to 255, joints distinct. Unused slots are 0.
struct Influences {
    uint8_t count = 0;
    std::array<uint16_t, 4> joints{0, 0, 0, 0};
    std::array<uint8_t, 4> weights{0, 0, 0, 0};
    bool operator==(const Influences&) const = default;
};
// Whether an influence record keeps the rules of spec 21.2 (count 1..4, weights >= 1 summing to
// 255, distinct joints, unused slots 0).
bool valid_influences(const Influences& influences);
// Weights (any non-negative numbers, one per joint) as a record: the four largest, rounded to 255ths
// that sum to 255 (largest remainders first), influences rounding to 0 left out (the largest kept
// when all do). Joints in the order given among equal weights. Empty (count 0) when no weight is
// above 0.
Influences quantize_influences(std::span<const uint16_t> joints, std::span<const float> weights);

// One JOINT_WEIGHTS packet's content: the records of points [first_index, first_index + records.size()).
struct JointWeightsRun {
    uint32_t first_index = 0;
    std::vector<Influences> records;
};
inline constexpr size_t kJointWeightsHeaderSize = 8;
// Joint indices take one byte when every joint of the run is below 256, else two.
std::vector<uint8_t> encode_joint_weights_payload(const JointWeightsRun& run);
// The checks of spec 21.2 that need no stream info.
Error decode_joint_weights_payload(std::span<const uint8_t> payload, JointWeightsRun& out);
// The JOINT_WEIGHTS packets of object `object_id`, one record per point (`records.size()` must be
// the object's point_count and every record valid), runs of as many points as fit the stream's
// packet size, numbered from `first_sequence`, saying version 1.5.
Error packetize_joint_weights(const StreamInfo& info, uint16_t object_id, const std::vector<Influences>& records,
                              uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);

}  // namespace ellicast
