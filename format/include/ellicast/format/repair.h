// Repair packets (format 1.2, spec section 17): a systematic Cauchy Reed-Solomon code over GF(2^8)
// across a block of consecutive points of one object, cut into source batches of `batch` points.
// Follows spec/format.md section 17 (Format 1.2 addition: repair packets): 17.1 Block and source
// symbols; 17.2 The code; 17.3 POINTS_REPAIR payload; 17.5 Sender behaviour; and 23.5 (Repair packets
// over mapped points). What a decoder does with them (17.4) is in received_stream.h.
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/stream_info.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ellicast {

inline constexpr size_t kRepairHeaderSize = 8;    // first_index, batch, source_count, row
inline constexpr unsigned kMaxRepairRow = 254;    // rows k..254: a block has at most 255 symbols

// k source batches of `batch` consecutive points from first_index on; the block ends with the k
// batches or with the object's points (spec 17.1): point_count is min(k * batch, object points -
// first_index), set by clip() once the object's entry is known.
struct RepairBlock {
    uint32_t first_index = 0;
    uint16_t batch = 0;
    uint8_t sources = 0;       // k
    uint32_t point_count = 0;  // points in the block's range
    uint32_t source_count() const { return sources; }
    // Points of source batch i.
    uint32_t batch_points(uint32_t i) const {
        return static_cast<uint32_t>(std::min<uint64_t>(batch, uint64_t(point_count) - uint64_t(i) * batch));
    }
    // The range cut at the object's `object_points`; false when the last batch would hold no point.
    bool clip(uint32_t object_points) {
        const uint64_t last = uint64_t{first_index} + uint64_t(sources - 1) * batch;
        if (sources == 0 || last >= object_points) return false;
        point_count = static_cast<uint32_t>(std::min<uint64_t>(uint64_t(sources) * batch, object_points - uint64_t{first_index}));
        return true;
    }
    bool same_block(const RepairBlock& o) const {
        return first_index == o.first_index && batch == o.batch && sources == o.sources;
    }
};

struct RepairPacket {
    RepairBlock block;
    uint8_t row = 0;
    std::vector<uint8_t> symbol;
};

// GF(2^8) with the polynomial x^8 + x^4 + x^3 + x^2 + 1 (0x11D), spec 17.2.
uint8_t gf256_mul(uint8_t a, uint8_t b);
uint8_t gf256_inv(uint8_t a);  // a != 0
// The code's coefficient C(row, j) = inv(row XOR j).
inline uint8_t repair_coefficient(unsigned row, unsigned j) { return gf256_inv(static_cast<uint8_t>(row ^ j)); }

// Bytes of a source or repair symbol: ceil(batch * B / 8).
size_t repair_symbol_bytes(const RepairBlock& block, const StreamInfo& info, const ObjectInfo& object);

std::vector<uint8_t> encode_repair_payload(const RepairPacket& packet);
// The checks that need no stream info (spec 17.3, step 11): MalformedPayload when the payload is
// shorter than 9 bytes, batch or source_count is 0, the row is outside source_count..254, or the
// last batch starts past 2^32 - 1. The symbol is the rest of the payload (its length is checked
// against the object's record size by the caller). point_count is k * batch until clipped.
Error decode_repair_payload(std::span<const uint8_t> payload, RepairPacket& out);

// Source symbol i of `block` from the points that hold it (points[k] is point first + k of the
// batch, `object`'s attributes): the records bit-packed as in a POINTS payload, zero-padded.
std::vector<uint8_t> repair_source_symbol(const RepairBlock& block, std::span<const QuantizedPoint> batch_points,
                                          const StreamInfo& info, const ObjectInfo& object);
// The repair symbol of `row` (source_count <= row <= 254) from all k source symbols (equal lengths).
std::vector<uint8_t> repair_symbol(const std::vector<std::vector<uint8_t>>& sources, unsigned row);
// Solves for the missing source symbols: `sources[i]` is empty where unknown; `rows`/`symbols` are the
// repair rows used, at least as many as the unknowns (the first ones are used). Fills the unknown
// sources and returns true; false when too few rows were given.
bool recover_source_symbols(std::vector<std::vector<uint8_t>>& sources, const std::vector<uint8_t>& rows,
                            const std::vector<std::vector<uint8_t>>& symbols);

// The blocks the reference encoder cuts an object's points into (spec 17.5): the object's point
// batches of `batch` points (points_per_packet), grouped into as few blocks as hold at most
// `max_sources` (<= 254) batches each, of nearly equal sizes, clipped. Empty when there are no points.
std::vector<RepairBlock> plan_repair_blocks(uint32_t point_count, uint16_t batch, size_t max_sources);

// The POINTS_REPAIR packets of rows source_count .. source_count + repairs - 1 (at most row 254) of
// every block of object `object_id`, from its points in stream order. Sequence numbers from
// `first_sequence`.
Error packetize_repairs(const StreamInfo& info, uint16_t object_id, const std::vector<QuantizedPoint>& points,
                        const std::vector<RepairBlock>& blocks, size_t repairs, uint32_t stream_id,
                        uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);

}  // namespace ellicast
