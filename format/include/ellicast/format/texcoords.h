// Further texture-coordinate sets (format 1.14): the TEXCOORDS packets that carry glTF's TEXCOORD_1 to
// TEXCOORD_7 of a run of an object's points, each with the quantization range of its set.
// Follows spec/format.md section 30 (Format 1.14 addition: more texture-coordinate sets): 30.1
// TEXCOORDS payload; 30.2 What a receiver shows.
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/paged_records.h"
#include "ellicast/format/stream_info.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ellicast {

// Sets beyond set 0 an object may have (TEXCOORD_1 .. TEXCOORD_7).
inline constexpr uint8_t kMaxTexcoordSets = 7;
inline constexpr size_t kTexcoordsHeaderSize = 28;

// The quantization of one further set of an object: T bits a component over [origin, origin + scale].
struct TexcoordRange {
    uint8_t bits = 12;
    std::array<float, 2> origin{0, 0};
    std::array<float, 2> scale{1, 1};
    bool operator==(const TexcoordRange&) const = default;  // floats as numbers: +0 and -0 agree
};

// One TEXCOORDS packet's content: set `set` (1 .. set_count) of points [first_index, first_index + records.size()).
struct TexcoordsRun {
    uint32_t first_index = 0;
    uint8_t set = 1;
    uint8_t set_count = 1;
    TexcoordRange range;
    std::vector<std::array<uint16_t, 2>> records;  // (qu, qv) per point, in index order
};

// Bytes of a TEXCOORDS payload of `count` records at `bits` a component.
size_t texcoords_payload_size(size_t count, unsigned bits);
std::vector<uint8_t> encode_texcoords_payload(const TexcoordsRun& run);
// Every check of step 11 (spec 30.1): MalformedPayload when shorter than 28 bytes, count 0, set_count
// 0 or above 7, set 0 or above set_count, bits outside 4..16, a run past index 2^32 - 1, a range that
// is not finite, negative or whose end is infinite, or a length that does not match.
Error decode_texcoords_payload(std::span<const uint8_t> payload, TexcoordsRun& out);
// The coordinates of a record (spec 30.1, as 7.1 and 8.4).
std::array<float, 2> dequantize_texcoord(const std::array<uint16_t, 2>& q, const TexcoordRange& range);
// The record of coordinates `t` in `range` (clamped to it; 0 where the scale is 0).
std::array<uint16_t, 2> quantize_texcoord(const std::array<float, 2>& t, const TexcoordRange& range);
// A range covering `values` (origin the smallest, scale the extent, 1 where it is 0) whose end is
// at least the largest value in f32.
TexcoordRange texcoord_range(const std::vector<std::array<float, 2>>& values, uint8_t bits);

// One further set of an object, as an encoder sends it: the range and a record per point.
struct TexcoordSet {
    TexcoordRange range;
    std::vector<std::array<uint16_t, 2>> records;  // one per point, in point order
};
// The TEXCOORDS packets of object `object_id` (each set's records.size() must be its point_count; at
// most 7 sets; the object must carry texture coordinates), runs of as many points as fit the
// stream's packet size, set by set, numbered from `first_sequence`, saying version 1.14.
Error packetize_texcoords(const StreamInfo& info, uint16_t object_id, const std::vector<TexcoordSet>& sets,
                          uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);

// What a receiver holds of one further set of an object (spec 30.1, step 15): the range of the first
// packet accepted for it and the records by point index (two u16 each, the stride).
struct ReceivedTexcoordSet {
    bool has_range = false;
    TexcoordRange range;
    PagedRecords<uint16_t> records{2};
};

}  // namespace ellicast
