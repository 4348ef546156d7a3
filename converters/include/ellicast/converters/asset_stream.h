// An Asset through a stream: on the way out its objects encoded and cut into packets (geometry, skin
// weights, morph targets, the exact layer, repair packets) and its scene cut into SCENE, MATERIAL,
// MATERIAL_EXTENSIONS, TEXTURE_FRAGMENT, ANIMATION, MORPH_ANIMATION and SKIN packets; on the way in
// its objects decoded and its scene rebuilt from whatever packets arrived.
#pragma once

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/format.h"

#include <string>
#include <vector>

namespace ellicast {

struct EncodedAsset {
    EncodeResult encoded;  // stream info, per-object contents, reports, warnings
    // Every packet in transmission order: STREAM_INFO, ELLIPSOIDS, POINT_MAP, then the scene (SCENE,
    // MATERIAL, TEXTURE_FRAGMENT: base data, a receiver wants it before the detail), then POINTS,
    // then NORMALS (surface normals), then TEXCOORDS (further texture-coordinate sets), then JOINT_WEIGHTS (skin weights), then MORPH_DELTAS (morph targets), then CONNECTIVITY (the exact layer), then POINTS_REPAIR (EncodeOptions::repair_ratio).
    // Sequence numbers count up in this order from 0.
    std::vector<std::vector<uint8_t>> packets;
    size_t stream_info_packets = 0, ellipsoid_packets = 0, scene_packets = 0, point_packets = 0, repair_packets = 0;
    size_t stream_info_bytes = 0, ellipsoid_bytes = 0, scene_bytes = 0, point_bytes = 0, repair_bytes = 0;
    size_t connectivity_packets = 0, connectivity_bytes = 0;  // the exact layer (format 1.3), after the points
    size_t weight_packets = 0, weight_bytes = 0;  // JOINT_WEIGHTS (format 1.5), right after the points
    size_t morph_packets = 0, morph_bytes = 0;    // MORPH_DELTAS (format 1.6), after the weights
    size_t map_packets = 0, map_bytes = 0;        // POINT_MAP (format 1.7), right after the ellipsoids
    size_t normal_packets = 0, normal_bytes = 0;  // NORMALS (format 1.8), right after the points
    size_t texcoord_packets = 0, texcoord_bytes = 0;  // TEXCOORDS (format 1.14), after the normals
};

// Encodes the objects of `asset` (one stream object each, in their own frames) and, when
// `with_scene`, packetizes its scene description. Returns false with `error` naming the problem
// (invalid options, too many objects, a scene table or name the format cannot carry).
bool encode_asset(const Asset& asset, const EncodeOptions& options, uint32_t stream_id, bool with_scene,
                  EncodedAsset& out, std::string& error);

// Reconstructs every object whose stream info arrived (decode_object) and rebuilds the scene
// around them (received_asset). Fails with `error` only when no STREAM_INFO arrived or an object
// cannot be built at all; the report says what each object received.
bool decode_asset(const ReceivedStream& stream, const DecodeOptions& options, Asset& out,
                  StreamDecodeReport& report, std::string& error);

}  // namespace ellicast
