// Cutting a whole stream's geometry into packets: the content of each object, quantized, and
// packetize_stream, which writes its STREAM_INFO, ELLIPSOIDS, POINT_MAP, POINTS or MAPPED_POINTS and
// NORMALS packets. Follows spec/format.md section 12 (Sender behaviour). The other types are cut by
// the packetize_* functions next to their payloads (scene.h, repair.h, connectivity.h, skin.h,
// morph.h, normals.h).
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/normals.h"
#include "ellicast/format/texcoords.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/stream_info.h"

#include <cstdint>
#include <vector>

namespace ellicast {

// The content of one object, quantized, ready to be cut into packets.
struct ObjectContent {
    std::vector<QuantizedEllipsoid> ellipsoids;  // must match info.objects[i].ellipsoid_count
    std::vector<QuantizedPoint> points;          // in stream order; must match point_count
    // Format 1.3, the exact layer (spec 19): the coded original triangles (empty: none), sent by
    // packetize_connectivity, not by packetize_stream.
    std::vector<uint8_t> connectivity;
    uint32_t triangle_count = 0;
    // Format 1.11 (spec 27): the vertices the exact layer carries, in the order it introduces them
    // (then `connectivity` is the coded mesh, sent in EXACT_MESH packets); empty otherwise.
    std::vector<QuantizedPoint> carried;
    // Format 1.8 (spec 24): for an object with surface normals, one entry per point (sent by
    // packetize_stream in NORMALS packets); empty otherwise.
    std::vector<NormalEntry> normals;
    // Format 1.14 (spec 30): the object's further texture-coordinate sets (TEXCOORD_1, ...), each with
    // a record per point (sent by packetize_stream in TEXCOORDS packets); empty for none.
    std::vector<TexcoordSet> texcoord_sets;
};

struct StreamPackets {
    std::vector<std::vector<uint8_t>> stream_info;  // every STREAM_INFO part
    std::vector<std::vector<uint8_t>> ellipsoids;   // every ELLIPSOIDS packet, object by object
    std::vector<std::vector<uint8_t>> points;       // every POINTS / MAPPED_POINTS packet, in stream order
    std::vector<std::vector<uint8_t>> maps;         // format 1.7: every POINT_MAP packet, object by object
    std::vector<std::vector<uint8_t>> normals;      // format 1.8: every NORMALS packet, object by object
    std::vector<std::vector<uint8_t>> texcoords;    // format 1.14: every TEXCOORDS packet, object by object
};

// Cuts a stream into packets of at most info.packet_size bytes. Sequence numbers run from 0 in the
// order stream info, ellipsoids, points. Requires check_stream_info(info) == Ok and contents that
// match the object table (checked: MalformedPayload otherwise).
Error packetize_stream(const StreamInfo& info, const std::vector<ObjectContent>& contents, uint32_t stream_id,
                       StreamPackets& out);

}  // namespace ellicast
