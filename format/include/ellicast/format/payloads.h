// The payloads of the geometry's critical types: STREAM_INFO parts, ELLIPSOIDS, and POINTS or (format
// 1.7) MAPPED_POINTS; their encoders and decoders, and how many elements fit a packet. Follows
// spec/format.md sections 5 (STREAM_INFO), 6 (ELLIPSOIDS), 7 (POINTS), 12 (Sender behaviour: how full
// the reference encoder fills a packet) and 23.4 (MAPPED_POINTS payload).
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/stream_info.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace ellicast {

// A part of the stream info as one STREAM_INFO packet carries it: the stream-level fields and the
// entries of objects [first_object, first_object + objects.size()) of a table of object_count.
struct StreamInfoPart {
    StreamInfo info;            // info.objects holds only this part's entries
    uint16_t object_count = 0;  // size of the whole object table
    uint16_t first_object = 0;
};

struct EllipsoidBatch {
    uint32_t first_index = 0;
    std::vector<QuantizedEllipsoid> ellipsoids;
};

struct PointBatch {
    uint32_t first_index = 0;
    std::vector<QuantizedPoint> points;
};

// Payload encoders. They do not split: the caller chooses counts that fit its packet size.
std::vector<uint8_t> encode_stream_info_payload(const StreamInfo& info, uint16_t first_object, uint16_t count);
std::vector<uint8_t> encode_ellipsoids_payload(const EllipsoidBatch& batch);
std::vector<uint8_t> encode_points_payload(const PointBatch& batch, const StreamInfo& info, const ObjectInfo& object);

// Payload decoders: MalformedPayload when a length or field is inconsistent.
// `version_minor`: that of the packet; the entries' map fields (spec 23.1) are read only from 1.7 on.
Error decode_stream_info_payload(std::span<const uint8_t> payload, StreamInfoPart& out,
                                 uint8_t version_minor = kSpecMinor);
// The content id of a STREAM_INFO packet (the u32 at payload offset 12, spec 5.4) without decoding the
// rest, as a receiver with a key binds packets to it (spec 25.2); none for another type or a payload
// shorter than 16 bytes.
std::optional<uint32_t> stream_info_content_id(uint8_t type, std::span<const uint8_t> payload);
Error decode_ellipsoids_payload(std::span<const uint8_t> payload, EllipsoidBatch& out);
// Needs the object's info: the record size depends on its attributes and the bit depths. For a
// mapped object (MAPPED_POINTS, spec 23.4) the positions are the offsets inside the points' cells,
// and encode_points_payload writes the low position_bits - map_level bits of each coordinate.
Error decode_points_payload(std::span<const uint8_t> payload, const StreamInfo& info, const ObjectInfo& object,
                            PointBatch& out);

// How many ellipsoids / points / object entries fit the payload of a packet of `packet_size` bytes.
size_t ellipsoids_per_packet(size_t packet_size);
size_t points_per_packet(size_t packet_size, const StreamInfo& info, const ObjectInfo& object);
size_t objects_per_stream_info_packet(size_t packet_size, size_t entry_size = kObjectEntrySize);
// Points per POINTS / MAPPED_POINTS packet the reference packetizer cuts an object into (and the
// repair blocks' batch): as many as fit, and for a mapped object at most its map_batch.
size_t point_batch_size(const StreamInfo& info, const ObjectInfo& object);
// The entry size a STREAM_INFO of `info` is written with: 48 when an object is mapped (spec 23.1), else 44.
size_t stream_info_entry_size(const StreamInfo& info);

}  // namespace ellicast
