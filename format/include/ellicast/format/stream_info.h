// The stream info: the stream-level fields (bit depths, packet size, content id, encoder parameters)
// and the object table (each object's frame, counts, kind, attributes and flags) that every other
// packet is read against. Follows spec/format.md section 5 (STREAM_INFO: 5.1 Stream-level fields,
// 5.2 Object entry, 5.3 Validity), with the entry's exact-layer flag of format 1.3 (section 19), map
// fields of 1.7 (23.1) and surface-normals flag of 1.8 (24.1). The payload is in payloads.h.
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ellicast {

enum class ObjectKind : uint8_t {
    Surface = 0,   // a triangle mesh: ellipsoids + points, reconstructed as a surface
    PointSet = 1,  // a point primitive: points only, shown as points
};

inline constexpr uint8_t kAttrNormal = 0x01;
inline constexpr uint8_t kAttrTexcoord = 0x02;
inline constexpr uint8_t kAttrColor = 0x04;
inline constexpr uint8_t kAttrColorAlpha = 0x08;  // colour has 4 channels (RGBA), else 3 (RGB)
inline constexpr uint8_t kAttrKnownMask = 0x0F;

// The quantization frame of an object: an axis-aligned cube with its minimum corner at `origin`
// and edge length `scale` (> 0). Positions and ellipsoid centres are quantized inside it.
struct Frame {
    std::array<float, 3> origin{};
    float scale = 1;
    bool operator==(const Frame&) const = default;
};

struct ObjectInfo {
    Frame frame;
    uint32_t ellipsoid_count = 0;
    uint32_t point_count = 0;
    ObjectKind kind = ObjectKind::Surface;
    uint8_t attributes = 0;                    // kAttr* bits
    std::array<float, 2> texcoord_origin{};    // texture coordinates quantized in
    std::array<float, 2> texcoord_scale{1, 1}; // [origin, origin + scale] per component
    // Format 1.3 (spec 19.1): the object's exact layer travels in CONNECTIVITY packets (entry flags
    // bit 8); a receiver waits for it to call the object complete. Never set for a point set.
    bool exact_layer = false;
    // Format 1.7 (spec 23.1): 0, or the level L (1..position_bits - 1) of the map the object's points
    // are placed by, their records then holding positions inside their cells (MAPPED_POINTS); and
    // the batch n that deals indices to ranks (spec 23.2), >= 1 exactly when map_level > 0.
    uint8_t map_level = 0;
    uint16_t map_batch = 0;
    // Format 1.8 (spec 24.1, entry flags bit 9): the object's normals are those of its surface (the
    // exact layer's), except those NORMALS packets send; its records carry no normal (attributes
    // bit 0 clear). Only on a surface with an exact layer.
    bool surface_normals = false;

    bool operator==(const ObjectInfo&) const = default;
    // Whether a receiver shows normals on the object: sent in its records, or surface normals.
    bool has_normals() const { return (attributes & kAttrNormal) != 0 || surface_normals; }
    bool mapped() const { return map_level > 0; }
    bool has(uint8_t attr) const { return (attributes & attr) == attr; }
    int color_channels() const { return has(kAttrColor) ? (has(kAttrColorAlpha) ? 4 : 3) : 0; }
};

inline constexpr uint16_t kEntryExactLayer = 0x0100;  // object entry flags (offset 26), format 1.3
inline constexpr uint16_t kEntrySurfaceNormals = 0x0200;  // format 1.8 (spec 24.1)
inline constexpr size_t kStreamInfoFixedSize = 32;  // v1.0 stream-level part of STREAM_INFO
inline constexpr size_t kObjectEntrySize = 44;      // v1.0 object table entry
inline constexpr size_t kMappedEntrySize = 48;      // format 1.7: the entry with its map fields (spec 23.1)

struct StreamInfo {
    uint16_t packet_size = kDefaultPacketSize;  // the sender's maximum packet size
    uint8_t position_bits = 14;                 // 8..16 per axis
    uint8_t normal_bits = 10;                   // 4..16 per octahedral component
    uint8_t texcoord_bits = 12;                 // 4..16 per component
    uint8_t color_bits = 8;                     // 2..16 per channel
    uint8_t ellipsoid_encoding = 0;             // 0: the 16-byte layout of format 1.0
    uint32_t content_id = 0;                    // changes whenever the sender's content changes
    uint16_t grid_hint = 0;                     // suggested decoder grid resolution, 0 = none
    float coverage_target = 0;                  // encoder parameter: covered volume fraction aimed at
    uint32_t seed = 0;                          // encoder parameter: random seed
    std::vector<ObjectInfo> objects;            // the whole object table
};

// Number of bits of one point record of `object` at the stream's bit depths: a POINTS record
// (spec 7.1), or for a mapped object a mapped record (spec 23.4: 3 (position_bits - map_level)
// position bits).
size_t point_record_bits(const StreamInfo& info, const ObjectInfo& object);
// Bits of each coordinate a record of `object` carries: position_bits, or position_bits - map_level.
unsigned record_position_bits(const StreamInfo& info, const ObjectInfo& object);

// Checks that the stream-level fields and every object are in range (bit depths, packet size,
// finite frames with positive scale, attributes known, kind known). Returns MalformedPayload or Ok.
Error check_stream_info(const StreamInfo& info);

}  // namespace ellicast
