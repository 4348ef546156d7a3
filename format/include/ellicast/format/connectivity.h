// The exact layer (format 1.3, spec section 19): an object's original triangles over its points.
// The coded connectivity, the CONNECTIVITY and CONNECTIVITY_REPAIR payloads and their packetizing.
// Follows spec/format.md section 19 (Format 1.3 addition: the exact layer): 19.1 CONNECTIVITY payload;
// 19.2 The coded connectivity; 19.3 The range decoder; 19.5 Repair packets for the exact layer.
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/stream_info.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

using Triangle = std::array<uint32_t, 3>;

// Codes `triangles` (point indices; three distinct points each) over the points at the quantized
// `positions` (spec 19.2, 19.3): `coded` the bytes, `sent` the triangle list a decoder will
// decode (the input's triangles, each in the input's winding, in traversal order).
// MalformedPayload when a triangle is degenerate or out of range, or there is none.
Error encode_connectivity(const std::vector<std::array<uint32_t, 3>>& positions, const std::vector<Triangle>& triangles,
                          std::vector<uint8_t>& coded, std::vector<Triangle>& sent);
// Decodes `triangle_count` triangles over the points at `positions`; MalformedPayload with `why`
// when the connectivity is unusable (spec 19.2).
Error decode_connectivity(std::span<const uint8_t> coded, uint32_t triangle_count,
                          const std::vector<std::array<uint32_t, 3>>& positions, std::vector<Triangle>& out,
                          std::string& why);

inline constexpr size_t kConnectivityHeaderSize = 16;

// What every CONNECTIVITY packet of an object repeats, and its piece.
struct ConnectivityPiece {
    uint32_t triangle_count = 0;
    uint32_t coded_size = 0;
    uint32_t coded_crc = 0;
    uint32_t offset = 0;
    std::vector<uint8_t> data;
};
std::vector<uint8_t> encode_connectivity_payload(const ConnectivityPiece& piece);
// The object-independent checks of spec 19.1 (a data byte, the piece inside coded_size, a triangle
// count, coded_size <= 16 * triangle_count + 64).
Error decode_connectivity_payload(std::span<const uint8_t> payload, ConnectivityPiece& out);

// The CONNECTIVITY packets of object `object_id` (pieces of `coded` at the stream's packet size),
// numbered from `first_sequence`, saying version 1.3.
Error packetize_connectivity(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                             const std::vector<uint8_t>& coded, uint32_t stream_id, uint32_t first_sequence,
                             std::vector<std::vector<uint8_t>>& out);

// A repair symbol over an object's coded connectivity (spec 19.5).
struct ConnectivityRepair {
    uint32_t triangle_count = 0, coded_size = 0, coded_crc = 0;
    uint16_t symbol_size = 0;
    uint8_t row = 0;
    std::vector<uint8_t> symbol;
};
std::vector<uint8_t> encode_connectivity_repair_payload(const ConnectivityRepair& repair);
Error decode_connectivity_repair_payload(std::span<const uint8_t> payload, ConnectivityRepair& out);
// The CONNECTIVITY_REPAIR packets of rows k .. k + count - 1 over `coded` cut into symbols of the
// CONNECTIVITY pieces' size; MalformedPayload when k > 127 or rows would pass 254.
Error packetize_connectivity_repairs(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                                     const std::vector<uint8_t>& coded, size_t count, uint32_t stream_id,
                                     uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);

}  // namespace ellicast
