// The exact layer (format 1.3, spec section 19): an object's original triangles over its points.
// The coded connectivity, the CONNECTIVITY and CONNECTIVITY_REPAIR payloads and their packetizing.
// Follows spec/format.md section 19 (Format 1.3 addition: the exact layer): 19.1 CONNECTIVITY payload;
// 19.2 The coded connectivity; 19.3 The range decoder; 19.5 Repair packets for the exact layer.
// And section 27 (format 1.11): the coded mesh, whose triangles also carry vertices that travel in no
// POINTS packet, in EXACT_MESH and EXACT_MESH_REPAIR packets (the same layouts with carried_count).
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/quantize.h"
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

// Format 1.11 (spec 27.2): the coded mesh. `vertices` are the object's points (the first `n`) and
// then the vertices it carries, in any order; `triangles` name them. `coded` gets the bytes, `sent`
// the triangle list a decoder will decode (over the points, then the carried vertices numbered in
// the order the coded mesh introduces them), `carried_order` the input index of each carried vertex
// in that order. With no carried vertex (vertices.size() == n) the bytes are those of
// encode_connectivity. MalformedPayload when a triangle is degenerate or out of range, there is
// none, or a carried vertex is used by no triangle.
Error encode_exact_mesh(const std::vector<QuantizedPoint>& vertices, size_t n, const std::vector<Triangle>& triangles,
                        const StreamInfo& info, const ObjectInfo& object, std::vector<uint8_t>& coded,
                        std::vector<Triangle>& sent, std::vector<uint32_t>& carried_order);
// Decodes `triangle_count` triangles and `carried_count` carried vertices over the object's `points`
// (index order; their positions and texture coordinates predict, spec 27.2); MalformedPayload with
// `why` when the mesh is unusable.
Error decode_exact_mesh(std::span<const uint8_t> coded, uint32_t triangle_count, uint32_t carried_count,
                        const std::vector<QuantizedPoint>& points, const StreamInfo& info, const ObjectInfo& object,
                        std::vector<Triangle>& out, std::vector<QuantizedPoint>& carried, std::string& why);

inline constexpr size_t kConnectivityHeaderSize = 16;
inline constexpr size_t kExactMeshHeaderSize = 20;        // spec 27.1: carried_count after triangle_count
inline constexpr uint32_t kMaxCarriedVertices = 1u << 24;  // spec 27.1

// What every CONNECTIVITY (or EXACT_MESH, with carried_count) packet of an object repeats, and its piece.
struct ConnectivityPiece {
    uint32_t triangle_count = 0;
    uint32_t carried_count = 0;  // format 1.11: EXACT_MESH only
    uint32_t coded_size = 0;
    uint32_t coded_crc = 0;
    uint32_t offset = 0;
    std::vector<uint8_t> data;
};
// `mesh`: the EXACT_MESH layout (spec 27.1), else CONNECTIVITY's.
std::vector<uint8_t> encode_connectivity_payload(const ConnectivityPiece& piece, bool mesh = false);
// The object-independent checks of spec 19.1 (a data byte, the piece inside coded_size, a triangle
// count, coded_size <= 16 * triangle_count + 64), or with `mesh` those of spec 27.1 that need no
// object (carried_count 1 .. 2^24); the object's checks are exact_layer_fits.
Error decode_connectivity_payload(std::span<const uint8_t> payload, ConnectivityPiece& out, bool mesh = false);
// Spec 19.1, 19.5, 27.1: whether an exact-layer packet's counts fit its object (a surface; at most
// 8 triangles a vertex; the coded size within its bound).
bool exact_layer_fits(const StreamInfo& info, const ObjectInfo& object, uint32_t triangle_count, uint32_t carried_count,
                      uint32_t coded_size, bool mesh);

// The CONNECTIVITY packets of object `object_id` (pieces of `coded` at the stream's packet size),
// numbered from `first_sequence`, saying version 1.3; with `carried_count` > 0, EXACT_MESH packets
// saying 1.11 (spec 27.1).
Error packetize_connectivity(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                             const std::vector<uint8_t>& coded, uint32_t stream_id, uint32_t first_sequence,
                             std::vector<std::vector<uint8_t>>& out, uint32_t carried_count = 0);

// A repair symbol over an object's coded connectivity (spec 19.5).
struct ConnectivityRepair {
    uint32_t triangle_count = 0, carried_count = 0, coded_size = 0, coded_crc = 0;
    uint16_t symbol_size = 0;
    uint8_t row = 0;
    std::vector<uint8_t> symbol;
};
std::vector<uint8_t> encode_connectivity_repair_payload(const ConnectivityRepair& repair, bool mesh = false);
Error decode_connectivity_repair_payload(std::span<const uint8_t> payload, ConnectivityRepair& out, bool mesh = false);
// The CONNECTIVITY_REPAIR packets of rows k .. k + count - 1 over `coded` cut into symbols of the
// CONNECTIVITY pieces' size; MalformedPayload when k > 127 or rows would pass 254.
Error packetize_connectivity_repairs(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                                     const std::vector<uint8_t>& coded, size_t count, uint32_t stream_id,
                                     uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out,
                                     uint32_t carried_count = 0);

}  // namespace ellicast
