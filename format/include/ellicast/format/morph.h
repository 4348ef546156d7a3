// Morph targets (format 1.6): the displacements of an object's points that MORPH_DELTAS packets carry,
// their payload and packetizing. Follows spec/format.md section 22.1 (MORPH_DELTAS payload); the
// MORPH_ANIMATION packets of section 22.2 are in animation.h.
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/stream_info.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ellicast {

// Morph targets (format 1.6, spec 22.1): the displacements of a run of an object's points, in
// slots (per target, the position displacement (attributes bit 0) and then the normal displacement
// (bit 1)) of 3 components, quantized to i16 against one f32 scale per slot: `values` holds, per
// point, per slot, 3 integers (a slot left out of a record is 0, 0, 0).
inline constexpr uint8_t kMorphPosition = 1, kMorphNormal = 2;
struct MorphDeltasRun {
    uint32_t first_index = 0;
    uint16_t count = 0;
    uint8_t target_count = 0;
    uint8_t attributes = 0;
    std::vector<float> scales;     // one per slot
    std::vector<int16_t> values;   // count * slots * 3
};
inline constexpr size_t kMorphDeltasHeaderSize = 8;
// Values of one point's record (slots * 3): target_count * 3 * (attributes bits set).
size_t morph_record_values(uint8_t target_count, uint8_t attributes);
// Where, in a point's record, the slot of `attribute` (kMorphPosition or kMorphNormal, one of
// `attributes`) of target `target` starts (spec 22.1: per target, the position, then the normal).
inline size_t morph_slot_offset(uint8_t attributes, size_t target, uint8_t attribute) {
    const bool both = (attributes & kMorphPosition) && (attributes & kMorphNormal);
    return 3 * (both ? 2 : 1) * target + (both && attribute == kMorphNormal ? 3 : 0);
}
// Component `q` of slot `slot` dequantized: q * scale in f32 (spec 22.1).
inline float morph_dequantize(int16_t q, float scale) { return static_cast<float>(q) * scale; }
std::vector<uint8_t> encode_morph_deltas_payload(const MorphDeltasRun& run);
// The checks of spec 22.1 that need no stream info.
Error decode_morph_deltas_payload(std::span<const uint8_t> payload, MorphDeltasRun& out);
// The MORPH_DELTAS packets of object `object_id`: `values` holds one record per point of the
// object (point_count * morph_record_values(...) finite values), cut into runs of as many points as
// fit the stream's packet size, numbered from `first_sequence`, saying version 1.6.
Error packetize_morph_deltas(const StreamInfo& info, uint16_t object_id, uint8_t target_count, uint8_t attributes,
                             const std::vector<float>& values, uint32_t stream_id, uint32_t first_sequence,
                             std::vector<std::vector<uint8_t>>& out);

}  // namespace ellicast
