// Draco compression of an ellicast::Mesh at the settings glTF-Transform uses by default
// (`gltf-transform draco`): Edgebreaker, 14-bit positions, 10-bit normals, 12-bit texture
// coordinates, 8-bit colours, encoding and decoding speed 5. Used for KHR_draco_mesh_compression
// output and by the Draco baselines of `ellicast compare`.
#pragma once

#include "ellicast/codec/mesh.h"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace ellicast {

// Draco refused a mesh or the settings: the message says what and why.
class DracoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct DracoSettings {
    int position_bits = 14;
    int normal_bits = 10;
    int texcoord_bits = 12;
    int color_bits = 8;
    int encoding_speed = 5;  // 0 (best compression) .. 10 (fastest)
    int decoding_speed = 5;
    // When set, positions are quantized on this grid (origin, cube edge) instead of the mesh's own
    // bounding box, so that separately compressed pieces of one model share one grid (no cracks).
    std::optional<std::array<float, 3>> position_origin;
    float position_range = 0;
};

// The unique ids of the attributes in a Draco bitstream (-1: absent), as KHR_draco_mesh_compression
// names them.
struct DracoAttributeIds {
    int position = -1, normal = -1, texcoord = -1, color = -1;
    std::vector<int> texcoord_sets;  // TEXCOORD_1, ... (format 1.14)
    // JOINTS_0 (8-bit when joints_8bit, else 16-bit), WEIGHTS_0 (normalized 8-bit when weights_8bit:
    // every weight a multiple of 1/255, as a stream's are; else float)
    int joints = -1, weights = -1;
    bool joints_8bit = false, weights_8bit = false;
};

// A skinned mesh's JOINTS_0 and WEIGHTS_0, one per vertex, for draco_encode: Draco then reorders them
// with the vertices (generic attributes, stored losslessly).
struct DracoSkin {
    const std::vector<std::array<uint16_t, 4>>* joints = nullptr;
    const std::vector<std::array<float, 4>>* weights = nullptr;
};

// The Draco bitstream of `mesh` (Edgebreaker) with every attribute it has (normals, TEXCOORD_0,
// COLOR_0); `ids`, when given, receives their unique ids. Throws DracoError when the mesh has no
// triangles or Draco refuses it.
std::vector<uint8_t> draco_encode(const Mesh& mesh, const DracoSettings& settings, DracoAttributeIds* ids = nullptr,
                                  const DracoSkin& skin = {});

// Decodes a Draco bitstream into a mesh (positions, triangles, and the attributes it carries).
// Returns false with `error` set when the bytes are not a decodable Draco mesh.
bool draco_decode(std::span<const uint8_t> bytes, Mesh& out, std::string& error);

// The axis-aligned cube (origin, edge) around the mesh's positions that Draco's own quantization
// would use: the bounding box's minimum corner and its largest extent.
std::pair<std::array<float, 3>, float> position_cube(const Mesh& mesh);

}  // namespace ellicast
