// What every packet of every format version has in common: the version numbers, the constants of the
// packet layout (magic, header and checksum sizes, packet size limits, the object id of stream-level
// packets, the skippable flag) and the packet types. Follows spec/format.md sections 3 (Packet
// structure), 4 (Packet types) and 9 (Versioning).
//
// This library implements format 1.14 (kFormatMajor.kSpecMinor), which includes every earlier minor
// version: it reads streams of format 1.0 to 1.14 (and packets of a later minor version as section 9
// says), and each packet it writes says the minor version its layout calls for: 1.1 (kFormatMinor)
// for the types of 1.0 and 1.1, and for the types and fields added later the versions below.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace ellicast {

// Format versions (spec 9): the minor version that added each type or field, and the newest.

inline constexpr uint8_t kFormatMajor = 1;
inline constexpr uint8_t kFormatMinor = 1;  // 1.1 added SCENE, MATERIAL, TEXTURE_FRAGMENT
// 1.2 added MANIFEST (signed streams). Only MANIFEST packets say 1.2: every other packet keeps the
// minor version whose layout it follows, so a 1.1 decoder reads a signed stream as it always did.
inline constexpr uint8_t kManifestMinor = 2;
inline constexpr uint8_t kRepairMinor = 2;  // 1.2 also added POINTS_REPAIR (spec 17)
// 1.3 added MATERIAL_EXTENSIONS (a material's extensions as a JSON patch, spec 18); those packets
// say 1.3, MATERIAL packets keep saying 1.1 (bit 0 of their flags byte is read whatever they say).
inline constexpr uint8_t kMaterialExtensionsMinor = 3;
inline constexpr uint8_t kConnectivityMinor = 3;  // 1.3 added CONNECTIVITY (the exact layer, spec 19)
inline constexpr uint8_t kAnimationMinor = 4;  // 1.4 added ANIMATION (spec 20)
// 1.5 added SKIN, JOINT_WEIGHTS and the SCENE node record's skin (spec 21); SCENE packets say 1.5
// only when a node record of theirs carries a skin.
inline constexpr uint8_t kSkinMinor = 5;
// 1.6 added MORPH_DELTAS, MORPH_ANIMATION and the SCENE mesh record's targets (spec 22); SCENE
// packets say 1.6 only when a mesh record of theirs carries targets.
inline constexpr uint8_t kMorphMinor = 6;
// 1.7 added MAPPED_POINTS, POINT_MAP and the object entry's map fields (spec 23); STREAM_INFO
// packets say 1.7 (with 48-byte entries) only in a stream that maps an object.
inline constexpr uint8_t kMapMinor = 7;
// 1.8 added NORMALS and the object entry's surface-normals flag (spec 24); STREAM_INFO packets say
// 1.8 only in a stream with an object that has surface normals.
inline constexpr uint8_t kSurfaceNormalsMinor = 8;
// 1.9 added MANIFEST scheme 2, bound to a content (spec 25); those MANIFEST packets say 1.9.
inline constexpr uint8_t kBoundManifestMinor = 9;
// 1.10 added CAMERA, LIGHT and the SCENE node record's camera and light (spec 26); SCENE packets say
// 1.10 only when a node record of theirs carries them.
inline constexpr uint8_t kCameraLightMinor = 10;
// 1.11 added EXACT_MESH and EXACT_MESH_REPAIR, an exact layer that carries vertices (spec 27).
inline constexpr uint8_t kExactMeshMinor = 11;
// 1.12 added EXTRAS, the glTF extras of the asset, the scene and the tables' elements (spec 28).
inline constexpr uint8_t kExtrasMinor = 12;
// 1.13 added REQUIRED_EXTENSION, the names of the extensions the source asset required (spec 29).
inline constexpr uint8_t kRequiredExtensionMinor = 13;
// 1.14 added TEXCOORDS, an object's further texture-coordinate sets (spec 30).
inline constexpr uint8_t kTexcoordsMinor = 14;
// The newest format version this library reads and writes (spec/format.md's version).
inline constexpr uint8_t kSpecMinor = 14;

inline constexpr std::array<uint8_t, 4> kPacketMagic = {0xE1, 'L', 'C', 'S'};
inline constexpr size_t kHeaderSize = 20;                       // bytes before the payload
inline constexpr size_t kChecksumSize = 4;                      // CRC-32C after the payload
inline constexpr size_t kPacketOverhead = kHeaderSize + kChecksumSize;
inline constexpr size_t kMinPacketSize = 128;                   // smallest packet size a sender may choose
inline constexpr size_t kMaxPacketSize = 65000;                 // largest packet on the wire
inline constexpr size_t kDefaultPacketSize = 1200;              // one UDP datagram under a 1280-byte IPv6 MTU

inline constexpr uint16_t kStreamObjectId = 0xFFFF;             // object id of stream-level packets
inline constexpr uint16_t kMaxObjects = 0xFFFF;                 // object ids are 0..65534

inline constexpr uint8_t kFlagSkippable = 0x01;                 // header flags bit 0

enum class PacketType : uint8_t {
    StreamInfo = 0x01,  // critical: frames, bit depths, object table
    Ellipsoids = 0x02,  // critical: a batch of quantized ellipsoids of one object
    Points = 0x03,      // critical: a batch of bit-packed surface points of one object
    PointsRepair = 0x04,  // 1.2, skippable: a repair symbol of an erasure code over a block of points
    Connectivity = 0x05,  // 1.3, skippable: a piece of an object's coded original triangles (the exact layer)
    ConnectivityRepair = 0x06,  // 1.3, skippable: a repair symbol over an object's coded connectivity
    JointWeights = 0x07,  // 1.5, skippable: the skin joints and weights of a run of an object's points
    MorphDeltas = 0x08,   // 1.6, skippable: the morph target displacements of a run of an object's points
    MappedPoints = 0x09,  // 1.7, critical: a batch of an object's points, positions inside the cells of its map
    PointMap = 0x0A,      // 1.7, critical: a fragment of an object's map of occupied cells
    Normals = 0x0B,       // 1.8, skippable: which normals of a run of points are sent, and those normals
    ExactMesh = 0x0C,     // 1.11, skippable: a piece of an object's coded mesh (the exact layer with carried vertices)
    ExactMeshRepair = 0x0D,  // 1.11, skippable: a repair symbol over an object's coded mesh
    Texcoords = 0x0E,     // 1.14, skippable: one further texture-coordinate set of a run of an object's points
    Scene = 0x10,       // 1.1, skippable: nodes (hierarchy, names, transforms) and meshes (object + material)
    Material = 0x11,    // 1.1, skippable: one PBR material
    TextureFragment = 0x12,  // 1.1, skippable: a piece of one texture image, at its byte offset
    MaterialExtensions = 0x13,  // 1.3, skippable: a material's extensions and texture transforms (JSON)
    Animation = 0x14,   // 1.4, skippable: keys of one track of an animation
    Skin = 0x15,        // 1.5, skippable: joints and inverse bind matrices of a skin
    MorphAnimation = 0x16,  // 1.6, skippable: keys of one track of morph target weights
    Camera = 0x17,      // 1.10, skippable: one glTF camera
    Light = 0x18,       // 1.10, skippable: one punctual light (KHR_lights_punctual)
    Extras = 0x19,      // 1.12, skippable: a fragment of the extras JSON of the asset, the scene or an element
    RequiredExtension = 0x1A,  // 1.13, skippable: the name of one extension the source asset required
    Manifest = 0x20,    // 1.2, skippable: signed digests of the stream's other packets
    // 0x00 is invalid; 0x0F reserved for geometry; 0x1B..0x1F reserved for the scene;
    // 0x21..0x7F future; 0x80..0xFF experimental.
};

// POINTS or (format 1.7) MAPPED_POINTS: a packet of an object's point records.
inline bool is_points_type(uint8_t type) {
    return type == static_cast<uint8_t>(PacketType::Points) || type == static_cast<uint8_t>(PacketType::MappedPoints);
}

// CONNECTIVITY or (format 1.11) EXACT_MESH: a piece of an object's exact layer; and their repair types.
inline bool is_exact_layer_type(uint8_t type) {
    return type == static_cast<uint8_t>(PacketType::Connectivity) || type == static_cast<uint8_t>(PacketType::ExactMesh);
}
inline bool is_exact_layer_repair_type(uint8_t type) {
    return type == static_cast<uint8_t>(PacketType::ConnectivityRepair) ||
           type == static_cast<uint8_t>(PacketType::ExactMeshRepair);
}

// Name of a packet type ("STREAM_INFO", ...), or "UNKNOWN(0xNN)".
std::string packet_type_name(uint8_t type);

// True for the types this implementation decodes (every type up to format 1.14).
bool is_known_packet_type(uint8_t type);

// An index into one of the scene's tables (spec 15, 21, 22) that names nothing.
inline constexpr uint16_t kNone = 0xFFFF;  // "no parent / no mesh / no material / no texture"

}  // namespace ellicast
