// ellicast format v1.2: packets, their payloads, quantization, container files.
//
// The normative description is spec/format.md; this header is its reference implementation.
// Depends on nothing but the standard library: no geometry algorithms, no glTF.
//
// Every parse function takes bytes it does not trust: it checks each length against what is
// really there, allocates at most in proportion to the input, and returns an error code that
// names what was wrong instead of throwing or crashing.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <functional>
#include <vector>

namespace ellicast {

// ---------------------------------------------------------------------------------------------
// Constants of format v1.1

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
// The newest format version this library reads and writes (spec/format.md's version).
inline constexpr uint8_t kSpecMinor = 8;

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

inline constexpr size_t kEllipsoidBytes = 16;                   // one quantized ellipsoid

// Container file: an 8-byte signature, a 4-byte file header, then packets back to back.
inline constexpr std::array<uint8_t, 8> kContainerSignature = {0x89, 'E', 'L', 'C', 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr size_t kContainerHeaderSize = 12;
inline constexpr uint8_t kContainerVersion = 1;

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
    Scene = 0x10,       // 1.1, skippable: nodes (hierarchy, names, transforms) and meshes (object + material)
    Material = 0x11,    // 1.1, skippable: one PBR material
    TextureFragment = 0x12,  // 1.1, skippable: a piece of one texture image, at its byte offset
    MaterialExtensions = 0x13,  // 1.3, skippable: a material's extensions and texture transforms (JSON)
    Animation = 0x14,   // 1.4, skippable: keys of one track of an animation
    Skin = 0x15,        // 1.5, skippable: joints and inverse bind matrices of a skin
    MorphAnimation = 0x16,  // 1.6, skippable: keys of one track of morph target weights
    Manifest = 0x20,    // 1.2, skippable: signed digests of the stream's other packets
    // 0x00 is invalid; 0x0C..0x0F reserved for geometry; 0x17..0x1F reserved for the scene;
    // 0x21..0x7F future; 0x80..0xFF experimental.
};

// POINTS or (format 1.7) MAPPED_POINTS: a packet of an object's point records.
inline bool is_points_type(uint8_t type) {
    return type == static_cast<uint8_t>(PacketType::Points) || type == static_cast<uint8_t>(PacketType::MappedPoints);
}

// Names in the stream are UTF-8 (spec 15). True when `text` is well-formed UTF-8 (no overlong
// forms, no surrogates, nothing above U+10FFFF).
bool is_valid_utf8(std::string_view text);

// `text` with every byte sequence that is not well-formed UTF-8 replaced by U+FFFD (one per
// maximal ill-formed subpart, as Unicode recommends): what a decoder shows of a name (spec 15.1).
std::string replace_invalid_utf8(std::string_view text);

// Name of a packet type ("STREAM_INFO", ...), or "UNKNOWN(0xNN)".
std::string packet_type_name(uint8_t type);

// True for the types this implementation decodes (every type up to format 1.8).
bool is_known_packet_type(uint8_t type);

// ---------------------------------------------------------------------------------------------
// Errors

enum class Error : uint8_t {
    Ok = 0,
    TooShort,             // fewer bytes than a packet header and checksum
    BadMagic,             // the first four bytes are not E1 4C 43 53
    UnsupportedMajor,     // major version other than 1
    InvalidType,          // packet type 0
    Oversized,            // header declares a packet larger than kMaxPacketSize
    Truncated,            // the declared payload runs past the bytes available
    LengthMismatch,       // a datagram holds bytes after the packet
    BadChecksum,          // CRC-32C does not match: the packet is damaged
    UnknownCriticalType,  // a type this decoder does not know, not marked skippable
    MalformedPayload,     // payload length or fields inconsistent with the packet type
    NoStreamInfo,         // payload needs the stream info of its object, which has not arrived
    UnknownObject,        // object id beyond the stream's object table
    IndexOutOfRange,      // an ellipsoid or point index beyond the object's declared count
    StreamMismatch,       // a packet of another stream id, or stream info contradicting earlier info
    BadSignature,         // a container file that does not start with the ellicast signature
    UnsupportedContainer, // container version other than 1
    IoError,              // a file could not be read or written
    ManifestSignature,    // with a key: a MANIFEST whose key id or Ed25519 signature does not match it
    NotAuthenticated,     // with a key: a packet that no verified MANIFEST lists
};

// A short readable name for an error ("bad checksum", ...).
const char* error_name(Error e);

// ---------------------------------------------------------------------------------------------
// Checksum

// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78, init and final xor 0xFFFFFFFF).
// Pass the previous result as `crc` to continue over more data. crc32c("123456789") == 0xE3069283.
uint32_t crc32c(const uint8_t* data, size_t size, uint32_t crc = 0);

// ---------------------------------------------------------------------------------------------
// Packets

struct PacketHeader {
    uint8_t version_major = kFormatMajor;
    uint8_t version_minor = kFormatMinor;
    uint8_t type = 0;
    uint8_t flags = 0;
    uint32_t stream_id = 0;
    uint32_t sequence = 0;
    uint16_t object_id = kStreamObjectId;
    uint16_t payload_length = 0;

    bool skippable() const { return (flags & kFlagSkippable) != 0; }
    size_t packet_size() const { return kPacketOverhead + payload_length; }
};

// A packet as parsed in place: the header and a view of its payload inside the caller's bytes.
struct PacketView {
    PacketHeader header;
    std::span<const uint8_t> payload;
    size_t size = 0;  // whole packet: header + payload + checksum
};

// Serializes a packet: header (payload_length taken from payload.size()), payload, CRC-32C.
// Requires payload.size() <= kMaxPacketSize - kPacketOverhead.
std::vector<uint8_t> write_packet(PacketHeader header, std::span<const uint8_t> payload);
// The header of a skippable packet of a type a later minor version added (every type but
// STREAM_INFO, ELLIPSOIDS and POINTS), saying version 1.`minor`.
PacketHeader skippable_header(PacketType type, uint8_t minor, uint32_t stream_id, uint32_t sequence,
                              uint16_t object_id);

// Parses the packet at the start of `bytes`, which may continue with other data (a container).
// Checks magic, major version, type, declared length against kMaxPacketSize and against the bytes
// available, then the checksum. Does not look inside the payload.
Error parse_packet_prefix(std::span<const uint8_t> bytes, PacketView& out);

// Parses a datagram that must hold exactly one packet (LengthMismatch if bytes follow it).
Error parse_packet(std::span<const uint8_t> bytes, PacketView& out);

// Sets the sequence number of a serialized packet and recomputes its checksum. The sequence number
// counts transmissions (a carousel's repeats get new numbers); receivers estimate loss from its gaps
// and never use it to identify content. Returns false if `packet` is not a valid packet.
bool restamp_packet(std::vector<uint8_t>& packet, uint32_t sequence);

// ---------------------------------------------------------------------------------------------
// Geometry values (dequantized)

// An ellipsoid: the points x with |diag(1/radii) * R^T (x - center)|^2 <= 1, where R is the rotation
// of the unit quaternion `rotation` = (w, x, y, z); column i of R is the direction of semi-axis i.
// As an implicit quadric: x'Ax + 2b'x + c <= 0 with A = R diag(1/r^2) R^T, b = -A center,
// c = center' A center - 1 (the paper normalizes c to 1).
struct Ellipsoid {
    std::array<float, 3> center{};
    std::array<float, 3> radii{};
    std::array<float, 4> rotation{1, 0, 0, 0};
};

// A surface sample: an original vertex with the attributes its object carries.
struct SurfacePoint {
    std::array<float, 3> position{};
    std::array<float, 3> normal{};      // unit length, when the object has normals
    std::array<float, 2> texcoord{};    // when the object has TEXCOORD_0
    std::array<float, 4> color{0, 0, 0, 1};  // linear RGBA in [0,1], when the object has COLOR_0
};

// ---------------------------------------------------------------------------------------------
// Stream info

enum class ObjectKind : uint8_t {
    Surface = 0,   // a triangle mesh: ellipsoids + points, reconstructed as a surface
    PointSet = 1,  // a point primitive: points only, shown as points
};

inline constexpr uint8_t kAttrNormal = 0x01;
inline constexpr uint8_t kAttrTexcoord = 0x02;
inline constexpr uint8_t kAttrColor = 0x04;
inline constexpr uint8_t kAttrColorAlpha = 0x08;  // colour has 4 channels (RGBA), else 3 (RGB)
inline constexpr uint8_t kAttrKnownMask = 0x0F;

// The quantization frame of an object: an axis-aligned cube with its minimum corner at `origin`
// and edge length `scale` (> 0). Positions and ellipsoid centres are quantized inside it.
struct Frame {
    std::array<float, 3> origin{};
    float scale = 1;
    bool operator==(const Frame&) const = default;
};

struct ObjectInfo {
    Frame frame;
    uint32_t ellipsoid_count = 0;
    uint32_t point_count = 0;
    ObjectKind kind = ObjectKind::Surface;
    uint8_t attributes = 0;                    // kAttr* bits
    std::array<float, 2> texcoord_origin{};    // texture coordinates quantized in
    std::array<float, 2> texcoord_scale{1, 1}; // [origin, origin + scale] per component
    // Format 1.3 (spec 19.1): the object's exact layer travels in CONNECTIVITY packets (entry flags
    // bit 8); a receiver waits for it to call the object complete. Never set for a point set.
    bool exact_layer = false;
    // Format 1.7 (spec 23.1): 0, or the level L (1..position_bits - 1) of the map the object's points
    // are placed by, their records then holding positions inside their cells (MAPPED_POINTS); and
    // the batch n that deals indices to ranks (spec 23.2), >= 1 exactly when map_level > 0.
    uint8_t map_level = 0;
    uint16_t map_batch = 0;
    // Format 1.8 (spec 24.1, entry flags bit 9): the object's normals are those of its surface (the
    // exact layer's), except those NORMALS packets send; its records carry no normal (attributes
    // bit 0 clear). Only on a surface with an exact layer.
    bool surface_normals = false;

    bool operator==(const ObjectInfo&) const = default;
    // Whether a receiver shows normals on the object: sent in its records, or surface normals.
    bool has_normals() const { return (attributes & kAttrNormal) != 0 || surface_normals; }
    bool mapped() const { return map_level > 0; }
    bool has(uint8_t attr) const { return (attributes & attr) == attr; }
    int color_channels() const { return has(kAttrColor) ? (has(kAttrColorAlpha) ? 4 : 3) : 0; }
};

inline constexpr uint16_t kEntryExactLayer = 0x0100;  // object entry flags (offset 26), format 1.3
inline constexpr uint16_t kEntrySurfaceNormals = 0x0200;  // format 1.8 (spec 24.1)
inline constexpr size_t kStreamInfoFixedSize = 32;  // v1.0 stream-level part of STREAM_INFO
inline constexpr size_t kObjectEntrySize = 44;      // v1.0 object table entry
inline constexpr size_t kMappedEntrySize = 48;      // format 1.7: the entry with its map fields (spec 23.1)

struct StreamInfo {
    uint16_t packet_size = kDefaultPacketSize;  // the sender's maximum packet size
    uint8_t position_bits = 14;                 // 8..16 per axis
    uint8_t normal_bits = 10;                   // 4..16 per octahedral component
    uint8_t texcoord_bits = 12;                 // 4..16 per component
    uint8_t color_bits = 8;                     // 2..16 per channel
    uint8_t ellipsoid_encoding = 0;             // 0: the 16-byte layout of format 1.0
    uint32_t content_id = 0;                    // changes whenever the sender's content changes
    uint16_t grid_hint = 0;                     // suggested decoder grid resolution, 0 = none
    float coverage_target = 0;                  // encoder parameter: covered volume fraction aimed at
    uint32_t seed = 0;                          // encoder parameter: random seed
    std::vector<ObjectInfo> objects;            // the whole object table
};

// Number of bits of one point record of `object` at the stream's bit depths: a POINTS record
// (spec 7.1), or for a mapped object a mapped record (spec 23.4: 3 (position_bits - map_level)
// position bits).
size_t point_record_bits(const StreamInfo& info, const ObjectInfo& object);
// Bits of each coordinate a record of `object` carries: position_bits, or position_bits - map_level.
unsigned record_position_bits(const StreamInfo& info, const ObjectInfo& object);

// Checks that the stream-level fields and every object are in range (bit depths, packet size,
// finite frames with positive scale, attributes known, kind known). Returns MalformedPayload or Ok.
Error check_stream_info(const StreamInfo& info);

// ---------------------------------------------------------------------------------------------
// Quantization (section "Quantization" of the spec states every error bound)

// A quantized ellipsoid, 16 bytes: centre 3 x 15 bits, radii 3 x 13 bits, rotation as the
// "smallest three" of its quaternion (2-bit index + 3 x 14 bits).
struct QuantizedEllipsoid {
    std::array<uint16_t, 3> center{};   // 0..32767 across the frame
    std::array<uint16_t, 3> radii{};    // 0..8191, radius = q * scale / 8191
    uint8_t largest = 0;                // index (0=w,1=x,2=y,3=z) of the dropped quaternion component
    std::array<uint16_t, 3> rotation{}; // 0..16383, the other three components in order
};

QuantizedEllipsoid quantize_ellipsoid(const Ellipsoid& e, const Frame& frame);
Ellipsoid dequantize_ellipsoid(const QuantizedEllipsoid& q, const Frame& frame);
void pack_ellipsoid(const QuantizedEllipsoid& q, uint8_t out[kEllipsoidBytes]);
QuantizedEllipsoid unpack_ellipsoid(const uint8_t in[kEllipsoidBytes]);

// Largest distance between a point of the true ellipsoid surface and its image on the
// dequantized ellipsoid (the bound of spec section "Quantization"), for radii up to max_radius.
double ellipsoid_error_bound(const Frame& frame, double max_radius);

// A point record as integers, before bit packing.
struct QuantizedPoint {
    std::array<uint32_t, 3> position{};
    std::array<uint32_t, 2> normal{};
    std::array<uint32_t, 2> texcoord{};
    std::array<uint32_t, 4> color{};
};

QuantizedPoint quantize_point(const SurfacePoint& p, const StreamInfo& info, const ObjectInfo& object);
SurfacePoint dequantize_point(const QuantizedPoint& q, const StreamInfo& info, const ObjectInfo& object);

// Octahedral normal encoding at `bits` per component (the unit vector n -> two integers).
std::array<uint32_t, 2> encode_octahedral(const std::array<float, 3>& n, int bits);
std::array<float, 3> decode_octahedral(const std::array<uint32_t, 2>& q, int bits);

// ---------------------------------------------------------------------------------------------
// Payloads

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

// ---------------------------------------------------------------------------------------------
// Mapped points (format 1.7, spec 23)

// The rank (spec 23.2) of the point of index `index` < point_count, batch n >= 1.
uint32_t mapped_rank(uint32_t index, uint32_t point_count, uint32_t batch);
// The inverse: the index of the point of rank `rank`.
uint32_t mapped_index(uint32_t rank, uint32_t point_count, uint32_t batch);
// Morton code (spec 23.2) of the cell of level `level` that holds quantized position q (position_bits P).
uint64_t morton_cell(const std::array<uint32_t, 3>& q, unsigned position_bits, unsigned level);
// The minimum corner, in quantized units, of the cell of level `level` with Morton code `code`.
std::array<uint32_t, 3> cell_corner(uint64_t code, unsigned position_bits, unsigned level);

struct MapCell {
    uint64_t code = 0;   // Morton code at the map's level
    uint32_t count = 0;  // points in the cell, >= 1
    bool operator==(const MapCell&) const = default;
};

// A POINT_MAP fragment (spec 23.3): cells of level map_level in increasing code, with counts.
struct PointMapFragment {
    uint32_t first_rank = 0;
    uint32_t point_total = 0;   // sum of the counts
    uint8_t root_level = 0;     // F
    uint8_t rice = 0;           // k
    uint16_t root_count = 0;    // R (filled by the decoder; the encoder derives it from the cells)
    std::vector<MapCell> cells;
};

inline constexpr size_t kPointMapHeaderSize = 12;

// Encodes a fragment: the roots are the distinct cells of level root_level above `cells`.
std::vector<uint8_t> encode_point_map_payload(const PointMapFragment& fragment, unsigned map_level);
// Bits of the tree encode_point_map_payload would write (without the 12-byte header).
size_t point_map_tree_bits(std::span<const MapCell> cells, unsigned map_level, unsigned root_level, unsigned rice);
// The fixed fields (spec 23.3, step 11): MalformedPayload when shorter than 12 bytes, point_total
// 0, rice > 15 or root_count 0. Fills the header fields of `out`, no cells.
Error decode_point_map_header(std::span<const uint8_t> payload, PointMapFragment& out);
// The whole payload for an object mapped at `map_level` of `position_bits` (spec 23.3, step 13):
// MalformedPayload (with `why`) when the tree is malformed.
Error decode_point_map_payload(std::span<const uint8_t> payload, unsigned position_bits, unsigned map_level,
                               PointMapFragment& out, std::string* why = nullptr);

// An object's cells at `level`, with counts, from its points in rank order; false when the points
// are not in increasing cell order along their ranks (they were not ordered by mapped_order).
bool point_map_cells(const std::vector<QuantizedPoint>& points, const StreamInfo& info, const ObjectInfo& object,
                     std::vector<MapCell>& cells);
// Cuts an object's cells into fragments that each fit a packet of `packet_size` bytes, with the
// lowest root level at which every subtree fits one, and each fragment's best Rice parameter.
std::vector<PointMapFragment> plan_point_map(const std::vector<MapCell>& cells, unsigned map_level, size_t packet_size);

// The encoder's choice (spec 23.7): the level whose POINT_MAP and MAPPED_POINTS packets take the
// fewest bytes, the map's counted `map_weight` times (a carousel repeats it), against those of
// POINTS packets; level 0 when mapping does not pay.
struct PointMapChoice {
    uint8_t level = 0;
    uint16_t batch = 0;
    uint64_t plain_bytes = 0;   // POINTS packets
    uint64_t map_bytes = 0;     // POINT_MAP packets at the chosen level
    uint64_t point_bytes = 0;   // MAPPED_POINTS packets at the chosen level
};
PointMapChoice choose_point_map(const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                                const ObjectInfo& object, double map_weight = 2.0);
// The order in which to send `points` (given in the encoder's priority order) for a map of `level`
// and `batch`: out[i] is the position in `points` of the point of index i. Within a cell, the points
// keep their given order.
std::vector<uint32_t> mapped_order(const std::vector<QuantizedPoint>& points, unsigned position_bits, unsigned level,
                                   uint32_t batch);

// ---------------------------------------------------------------------------------------------
// Packetizing a whole stream

// Surface normals (format 1.8, spec 24): a point's normal entry says whether its normal is sent
// (then its octahedral normal, normal_bits per component) or left to the surface.
struct NormalEntry {
    bool sent = false;
    std::array<uint32_t, 2> normal{};  // when sent
    bool operator==(const NormalEntry&) const = default;
};

// The content of one object, quantized, ready to be cut into packets.
struct ObjectContent {
    std::vector<QuantizedEllipsoid> ellipsoids;  // must match info.objects[i].ellipsoid_count
    std::vector<QuantizedPoint> points;          // in stream order; must match point_count
    // Format 1.3, the exact layer (spec 19): the coded original triangles (empty: none), sent by
    // packetize_connectivity, not by packetize_stream.
    std::vector<uint8_t> connectivity;
    uint32_t triangle_count = 0;
    // Format 1.8 (spec 24): for an object with surface normals, one entry per point (sent by
    // packetize_stream in NORMALS packets); empty otherwise.
    std::vector<NormalEntry> normals;
};

struct StreamPackets {
    std::vector<std::vector<uint8_t>> stream_info;  // every STREAM_INFO part
    std::vector<std::vector<uint8_t>> ellipsoids;   // every ELLIPSOIDS packet, object by object
    std::vector<std::vector<uint8_t>> points;       // every POINTS / MAPPED_POINTS packet, in stream order
    std::vector<std::vector<uint8_t>> maps;         // format 1.7: every POINT_MAP packet, object by object
    std::vector<std::vector<uint8_t>> normals;      // format 1.8: every NORMALS packet, object by object
};

// Cuts a stream into packets of at most info.packet_size bytes. Sequence numbers run from 0 in the
// order stream info, ellipsoids, points. Requires check_stream_info(info) == Ok and contents that
// match the object table (checked: MalformedPayload otherwise).
Error packetize_stream(const StreamInfo& info, const std::vector<ObjectContent>& contents, uint32_t stream_id,
                       StreamPackets& out);

// ---------------------------------------------------------------------------------------------
// Scene, materials, textures (format 1.1). All three types are sent with the skippable flag:
// a 1.0 decoder still reconstructs every object, only without placement and appearance.

inline constexpr uint16_t kNone = 0xFFFF;  // "no parent / no mesh / no material / no texture"

// A node of the scene graph. Roots have parent == kNone; a node's children are the nodes naming it
// as parent, in index order. The transform is either a column-major 4x4 matrix or T * R * S.
struct SceneNode {
    uint16_t index = 0;
    uint16_t parent = kNone;
    uint16_t mesh = kNone;  // index into the mesh table
    std::string name;       // UTF-8, at most 255 bytes
    bool has_matrix = false;
    std::array<float, 16> matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::array<float, 3> translation{0, 0, 0};
    std::array<float, 4> rotation{0, 0, 0, 1};  // quaternion x, y, z, w (glTF order)
    std::array<float, 3> scale{1, 1, 1};
    uint16_t skin = kNone;  // format 1.5 (spec 21): index into the skin table
    bool operator==(const SceneNode&) const = default;
};

// A mesh: primitives, each an object of the stream drawn with a material. Several nodes naming the
// same mesh instance it: its objects travel once.
struct ScenePrimitive {
    uint16_t object = 0;
    uint16_t material = kNone;
    bool operator==(const ScenePrimitive&) const = default;
};
struct SceneMesh {
    uint16_t index = 0;
    std::string name;
    std::vector<ScenePrimitive> primitives;
    // Format 1.6 (spec 22): one default weight per morph target (glTF mesh.weights); empty for a
    // mesh without targets. At most 255.
    std::vector<float> weights;
    bool operator==(const SceneMesh&) const = default;
};

// The records one SCENE packet carries, and the sizes of the whole tables.
struct SceneBatch {
    uint16_t node_count = 0;
    uint16_t mesh_count = 0;
    std::vector<SceneNode> nodes;
    std::vector<SceneMesh> meshes;
};

enum class AlphaMode : uint8_t { Opaque = 0, Mask = 1, Blend = 2 };

struct TextureRef {
    uint16_t texture = kNone;  // index into the texture table
    uint8_t texcoord = 0;      // TEXCOORD_n set
    float scale = 1;           // normalTexture.scale / occlusionTexture.strength; 1 otherwise
    bool operator==(const TextureRef&) const = default;
};

// glTF PBR metallic-roughness material.
struct Material {
    uint16_t index = 0;
    uint16_t material_count = 0;  // size of the whole material table
    std::string name;
    std::array<float, 4> base_color{1, 1, 1, 1};
    float metallic = 1;
    float roughness = 1;
    std::array<float, 3> emissive{0, 0, 0};
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;
    TextureRef base_color_texture, metallic_roughness_texture, normal_texture, occlusion_texture, emissive_texture;
    // Format 1.3 (spec 18.1): MATERIAL flags bit 0, the material has a MATERIAL_EXTENSIONS packet.
    bool has_extensions = false;
    // Sender side: the patch (spec 18.2) packetize_scene sends in a MATERIAL_EXTENSIONS packet (and
    // then sets has_extensions); empty: none. A decoded MATERIAL leaves it empty: a receiver finds
    // patches in ReceivedStream::material_extensions().
    std::string extensions;
    bool operator==(const Material&) const = default;
};

// Format 1.3 (spec 18.2): the JSON patch of one material.
struct MaterialExtensions {
    uint16_t index = 0;
    uint16_t material_count = 0;  // size of the whole material table
    std::string patch;            // the JSON text, as received
    bool operator==(const MaterialExtensions&) const = default;
};
inline constexpr size_t kMaterialExtensionsMinSize = 6;  // index, count, and the shortest patch "{}"

// A texture reference of a patch (spec 18.2, 18.3).
struct PatchTextureReference {
    std::string path;         // member names (array positions) from the top, joined by '/'
    uint16_t texture = 0;     // index into the stream's texture table
    size_t index_offset = 0;  // where the digits of its "index" stand in the patch text
    size_t index_length = 0;
};

// Checks a patch by spec 18.2 (rules 2..8: UTF-8, RFC 8259 grammar, surrogates, finite numbers,
// unique names, depth 32, shape and texture rules): Ok, with its texture references in document
// order when `references` is given, or MalformedPayload.
Error check_material_patch(std::string_view patch, std::vector<PatchTextureReference>* references = nullptr);
// The patch with the index of each of its texture references (as check_material_patch found them)
// replaced by map(index): a patch moved to another texture table.
std::string remap_patch_textures(std::string_view patch, const std::vector<PatchTextureReference>& references,
                                 const std::function<uint16_t(uint16_t)>& map);

enum class ImageType : uint8_t { Png = 1, Jpeg = 2 };

// What every fragment of a texture repeats, so that any fragment is useful on its own.
struct TextureInfo {
    uint16_t index = 0;
    uint16_t texture_count = 0;  // size of the whole texture table
    ImageType image_type = ImageType::Png;
    uint16_t mag_filter = 0, min_filter = 0;  // glTF sampler values, 0 = unset
    uint16_t wrap_s = 10497, wrap_t = 10497;  // REPEAT
    uint32_t image_size = 0;                  // bytes of the whole image file
    uint32_t image_crc = 0;                   // CRC-32C of the whole image file
    bool operator==(const TextureInfo&) const = default;
};

struct TextureFragment {
    TextureInfo info;
    uint32_t offset = 0;
    std::vector<uint8_t> data;
};

inline constexpr size_t kTextureFragmentHeaderSize = 28;

// Animations (format 1.4, spec 20). A track moves one property of one node over keys.
// Weights (morph target weights, format 1.6) travels in MORPH_ANIMATION packets only (spec 22.2).
enum class AnimationPath : uint8_t { Translation = 0, Rotation = 1, Scale = 2, Weights = 3 };
enum class Interpolation : uint8_t { Linear = 0, Step = 1, CubicSpline = 2 };

// What every packet of a track repeats.
struct AnimationTrackInfo {
    uint16_t node = 0;  // index of the SCENE node table
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t key_count = 0;
    uint8_t targets = 0;  // Weights: the weights per value, C (1..255); 0 for the other paths
    bool operator==(const AnimationTrackInfo&) const = default;
};

// f32 values per key: C (3, or 4 for rotation, `targets` for weights), three times that for cubic
// splines.
size_t animation_values_per_key(AnimationPath path, Interpolation interpolation, size_t targets = 0);

// One ANIMATION packet's content: keys [first_key, first_key + times.size()) of one track.
struct AnimationPiece {
    uint16_t animation = 0, animation_count = 0;
    uint16_t joins = kNone;  // MORPH_ANIMATION only: the ANIMATION this morph animation joins
    uint16_t track = 0, track_count = 0;
    std::string name;  // the animation's
    AnimationTrackInfo info;
    uint32_t first_key = 0;
    std::vector<float> times;   // one per key
    std::vector<float> values;  // animation_values_per_key per key
};
inline constexpr size_t kAnimationHeaderSize = 24;
std::vector<uint8_t> encode_animation_payload(const AnimationPiece& piece);
Error decode_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out);
// MORPH_ANIMATION (format 1.6, spec 22.2): the same content for a track of weights (info.path
// Weights, info.targets C) of a morph animation, which joins the ANIMATION `joins` or stands alone.
inline constexpr size_t kMorphAnimationHeaderSize = 26;
std::vector<uint8_t> encode_morph_animation_payload(const AnimationPiece& piece);
Error decode_morph_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out);

// An animation as a sender has it: tracks of whole key lists.
struct SceneAnimation {
    std::string name;
    struct Track {
        uint16_t node = 0;
        AnimationPath path = AnimationPath::Translation;
        Interpolation interpolation = Interpolation::Linear;
        uint8_t targets = 0;  // Weights (format 1.6): weights per value
        std::vector<float> times;
        std::vector<float> values;
    };
    // Tracks of every path: packetize_scene sends translation, rotation and scale tracks as
    // ANIMATION packets and weights tracks as MORPH_ANIMATION packets (spec 22.2, 22.5).
    std::vector<Track> tracks;
};

// Skins (format 1.5, spec 21). A joint: a node of the SCENE table and its inverse bind matrix.
struct SkinJoint {
    uint16_t node = 0;
    std::array<float, 16> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
    bool operator==(const SkinJoint&) const = default;
};

// One SKIN packet's content: joints [first_joint, first_joint + joints.size()) of one skin.
struct SkinPiece {
    uint16_t skin = 0, skin_count = 0;
    uint16_t joint_count = 0, first_joint = 0;
    uint16_t skeleton = kNone;
    std::string name;  // the skin's
    std::vector<SkinJoint> joints;
};
inline constexpr size_t kSkinHeaderSize = 14;
inline constexpr size_t kSkinJointSize = 66;
std::vector<uint8_t> encode_skin_payload(const SkinPiece& piece);
Error decode_skin_payload(std::span<const uint8_t> payload, SkinPiece& out);

// A skin as a sender has it.
struct SceneSkin {
    std::string name;
    uint16_t skeleton = kNone;
    std::vector<SkinJoint> joints;
};

// The joints and weights of one point (spec 21.2): `count` influences (1..4), weights in 255ths,
// each at least 1, summing to 255, joints distinct. Unused slots are 0.
struct Influences {
    uint8_t count = 0;
    std::array<uint16_t, 4> joints{0, 0, 0, 0};
    std::array<uint8_t, 4> weights{0, 0, 0, 0};
    bool operator==(const Influences&) const = default;
};
// Whether an influence record keeps the rules of spec 21.2 (count 1..4, weights >= 1 summing to
// 255, distinct joints, unused slots 0).
bool valid_influences(const Influences& influences);
// Weights (any non-negative numbers, one per joint) as a record: the four largest, rounded to 255ths
// that sum to 255 (largest remainders first), influences rounding to 0 left out (the largest kept
// when all do). Joints in the order given among equal weights. Empty (count 0) when no weight is
// above 0.
Influences quantize_influences(std::span<const uint16_t> joints, std::span<const float> weights);

// One JOINT_WEIGHTS packet's content: the records of points [first_index, first_index + records.size()).
struct JointWeightsRun {
    uint32_t first_index = 0;
    std::vector<Influences> records;
};
inline constexpr size_t kJointWeightsHeaderSize = 8;
// Joint indices take one byte when every joint of the run is below 256, else two.
std::vector<uint8_t> encode_joint_weights_payload(const JointWeightsRun& run);
// The checks of spec 21.2 that need no stream info.
Error decode_joint_weights_payload(std::span<const uint8_t> payload, JointWeightsRun& out);
// The JOINT_WEIGHTS packets of object `object_id`, one record per point (`records.size()` must be
// the object's point_count and every record valid), runs of as many points as fit the stream's
// packet size, numbered from `first_sequence`, saying version 1.5.
Error packetize_joint_weights(const StreamInfo& info, uint16_t object_id, const std::vector<Influences>& records,
                              uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);

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

// Surface normals (format 1.8, spec 24): NORMALS packets (NormalEntry is declared with ObjectContent).
// One NORMALS packet's content: the entries of points [first_index, first_index + entries.size()).
struct NormalsRun {
    uint32_t first_index = 0;
    std::vector<NormalEntry> entries;
};
inline constexpr size_t kNormalsHeaderSize = 8;
// Bytes of a NORMALS payload of `count` entries, `sent` of them sent, at `normal_bits`.
size_t normals_payload_size(size_t count, size_t sent, unsigned normal_bits);
std::vector<uint8_t> encode_normals_payload(const NormalsRun& run, unsigned normal_bits);
// The fixed fields (spec 24.2, step 11): MalformedPayload when shorter than 8 bytes, count 0,
// sent_count > count, or first_index + count past 2^32 - 1.
Error check_normals_header(std::span<const uint8_t> payload);
// The whole payload at the stream's normal_bits (spec 24.2, step 13): MalformedPayload when the
// length or the number of flags set does not match sent_count.
Error decode_normals_payload(std::span<const uint8_t> payload, unsigned normal_bits, NormalsRun& out);
// The NORMALS packets of object `object_id` (entries.size() must be its point_count), runs of as many
// points as fit the stream's packet size, numbered from `first_sequence`, saying version 1.8.
Error packetize_normals(const StreamInfo& info, uint16_t object_id, const std::vector<NormalEntry>& entries,
                        uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out);
// The surface normal of every point (spec 24.3) from the quantized positions and the exact layer's
// triangles, and per point the ratio |S| / (sum of the angles) (0 when undefined): a normal whose
// ratio is small can turn under rounding (the reference encoder sends it when the ratio is under 0.1).
struct SurfaceNormals {
    std::vector<std::array<float, 3>> normal;  // (0, 0, 0) where undefined
    std::vector<float> condition;              // |S| / sum of theta; 0 where undefined
};
SurfaceNormals surface_normals(const std::vector<std::array<uint32_t, 3>>& positions,
                               std::span<const std::array<uint32_t, 3>> triangles);
// Whether some triangle contributes to the surface normal of each point (m != 0, exact integers):
// the conformance test of spec 24.4.
std::vector<char> surface_normal_defined(const std::vector<std::array<uint32_t, 3>>& positions,
                                         std::span<const std::array<uint32_t, 3>> triangles);

// Everything of the scene that travels besides geometry.
struct SceneDescription {
    std::vector<SceneNode> nodes;  // node i has index i
    std::vector<SceneMesh> meshes; // mesh i has index i
    std::vector<Material> materials;
    struct Texture {
        TextureInfo info;           // index, counts, size and CRC are filled in by packetize_scene
        std::vector<uint8_t> image; // the image file bytes as the asset had them
    };
    std::vector<Texture> textures;
    std::vector<SceneAnimation> animations;  // format 1.4
    std::vector<SceneSkin> skins;            // format 1.5: SceneNode::skin indexes it
};

std::vector<uint8_t> encode_scene_payload(const SceneBatch& batch);
// `version_minor`: that of the packet; a node record's skin (spec 21) is read only from 1.5 on.
Error decode_scene_payload(std::span<const uint8_t> payload, SceneBatch& out, uint8_t version_minor = kSpecMinor);
std::vector<uint8_t> encode_material_payload(const Material& material);
Error decode_material_payload(std::span<const uint8_t> payload, Material& out);
std::vector<uint8_t> encode_material_extensions_payload(const MaterialExtensions& extensions);
Error decode_material_extensions_payload(std::span<const uint8_t> payload, MaterialExtensions& out);
std::vector<uint8_t> encode_texture_fragment_payload(const TextureFragment& fragment);
Error decode_texture_fragment_payload(std::span<const uint8_t> payload, TextureFragment& out);

struct ScenePackets {
    std::vector<std::vector<uint8_t>> scene;      // SCENE packets
    std::vector<std::vector<uint8_t>> materials;  // one MATERIAL packet per material, each followed by
                                                  // its MATERIAL_EXTENSIONS packet when it has one
    std::vector<uint16_t> extensions_too_large;   // materials whose patch did not fit a packet: sent without
    std::vector<std::vector<uint8_t>> textures;   // TEXTURE_FRAGMENT packets, texture by texture
    std::vector<std::vector<uint8_t>> animations; // ANIMATION packets, track by track (format 1.4), then
                                                  // MORPH_ANIMATION packets (format 1.6)
    std::vector<std::vector<uint8_t>> skins;      // SKIN packets, skin by skin (format 1.5)
};

// Cuts a scene description into packets of at most `packet_size` bytes, numbered from
// `first_sequence`. MalformedPayload when a table is larger than 65535 entries, a name longer than
// 255 bytes, a record does not fit one packet, a reference points outside its table, or an image is
// empty or over 4 GiB; for animations when a table has more than 65535 entries, a track has no key,
// values of another count than its keys need, a float that is not finite, negative or not strictly
// increasing times, a cubic spline of one key, or a node outside the node table.
Error packetize_scene(const SceneDescription& scene, size_t packet_size, uint32_t stream_id, uint32_t first_sequence,
                      ScenePackets& out);

// ---------------------------------------------------------------------------------------------
// Signed streams (format 1.2, spec section 16). A MANIFEST packet lists 16-byte digests of other
// packets (SHA-256 of the packet without its checksum and with its sequence number zeroed,
// truncated) and an Ed25519 signature over itself. This library lays the bytes out and computes
// digests; signing and verifying are in the auth library (libsodium).

inline constexpr size_t kPacketDigestSize = 16;
inline constexpr size_t kManifestFixedSize = 24;
inline constexpr size_t kManifestSignatureSize = 64;
inline constexpr size_t kKeyIdSize = 8;
inline constexpr uint8_t kManifestSchemeEd25519 = 1;
// What a signature signs: this ASCII context, then the packet without signature and checksum.
inline constexpr std::string_view kManifestContext = "ellicast manifest";

using PacketDigest = std::array<uint8_t, kPacketDigestSize>;

struct ManifestPart {
    uint8_t scheme = kManifestSchemeEd25519;
    uint16_t part = 0;
    uint16_t part_count = 1;
    uint32_t packet_count = 0;  // digests in all parts together
    uint32_t first = 0;         // index of digests[0] in the whole list
    std::array<uint8_t, kKeyIdSize> key_id{};
    std::vector<PacketDigest> digests;
    std::array<uint8_t, kManifestSignatureSize> signature{};
};

std::vector<uint8_t> encode_manifest_payload(const ManifestPart& part);
// MalformedPayload when the payload is empty, or (scheme 1) the length does not match digest_count,
// part_count is 0, part is not below it, or the digests run past packet_count. A scheme other than 1
// is not an error: only `scheme` is set, and the caller skips such a packet (its layout is a later
// version's).
Error decode_manifest_payload(std::span<const uint8_t> payload, ManifestPart& out);
// Digests one MANIFEST packet of `packet_size` bytes can carry.
size_t digests_per_manifest_packet(size_t packet_size);
// The bytes a packet's digest hashes: header and payload with the sequence bytes zeroed (empty
// when `packet` is shorter than its header says).
std::vector<uint8_t> packet_digest_input(std::span<const uint8_t> packet);
// SHA-256 (FIPS 180-4) of `data`.
std::array<uint8_t, 32> sha256(std::span<const uint8_t> data);
// A packet's digest (spec 16.1): the first 16 bytes of SHA-256 of packet_digest_input(packet).
// `packet` must hold a whole packet (its header's length is trusted: parse it first).
PacketDigest packet_digest(std::span<const uint8_t> packet);
// A public key's id (spec 16.2): the first 8 bytes of SHA-256 of its 32 bytes.
std::array<uint8_t, kKeyIdSize> key_id_of(std::span<const uint8_t, 32> public_key);
// The message a MANIFEST packet's signature signs: kManifestContext, then the packet's digest
// input without the trailing signature (empty when the packet is too short to be a MANIFEST).
std::vector<uint8_t> manifest_signed_message(std::span<const uint8_t> packet);

// ---------------------------------------------------------------------------------------------
// Repair packets (format 1.2, spec section 17): a systematic Cauchy Reed-Solomon code over GF(2^8)
// across a block of consecutive points of one object, cut into source batches of `batch` points.

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

// ---------------------------------------------------------------------------------------------
// The exact layer (format 1.3, spec section 19): an object's original triangles over its points.

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

// ---------------------------------------------------------------------------------------------
// Receiving: collects whatever packets arrive, in any order, with duplicates and damage

// An object's connectivity as it arrives (spec 19.1).
struct ReceivedConnectivity {
    uint32_t triangle_count = 0, coded_size = 0, coded_crc = 0;
    std::map<uint32_t, std::vector<uint8_t>> pieces;  // disjoint runs of bytes, emptied once complete
    uint64_t received_bytes = 0;
    bool complete = false;        // every byte arrived and the CRC matches
    std::vector<uint8_t> coded;   // once complete
    // Repair symbols held while not complete (spec 19.5): their size, rows in order, symbols.
    uint16_t symbol_size = 0;
    std::vector<uint8_t> rows;
    std::vector<std::vector<uint8_t>> symbols;
    bool recovered = false;       // completed by solving for missing symbols
};

// A repair block a receiver has heard of (spec 17.4).
struct ReceivedRepairBlock {
    RepairBlock block;
    std::vector<uint32_t> held_in_batch;    // points held of each source batch
    uint32_t batches_held = 0;              // source batches of which every point is held
    std::vector<uint8_t> rows_accepted;     // every row accepted, in order
    std::vector<std::vector<uint8_t>> symbols;  // their symbols, released once the block is complete
    bool complete = false;                  // every point of the block is held
    bool recovered = false;                 // completed by solving for missing batches
    uint32_t points_recovered = 0;
};

// A POINT_MAP fragment a receiver accepted (spec 23.3).
struct ReceivedMapFragment {
    uint32_t point_total = 0;
    std::vector<MapCell> cells;
    std::vector<uint32_t> starts;  // rank of each cell's first point, from the fragment's first rank
};

struct ReceivedObject {
    std::optional<ObjectInfo> info;                 // once its stream info entry arrived
    std::map<uint32_t, QuantizedEllipsoid> ellipsoids;  // by index; duplicates collapse
    std::map<uint32_t, QuantizedPoint> points;          // by index (a mapped object's: placed, spec 23.4)
    // Format 1.7 (spec 23): a mapped object's fragments by first rank, and the records held but not
    // placed (positions are offsets inside their cells) by index.
    std::map<uint32_t, ReceivedMapFragment> map_fragments;
    std::map<uint32_t, QuantizedPoint> unplaced;
    uint64_t map_ranks = 0;                          // ranks the fragments hold
    bool map_complete() const { return info && info->mapped() && map_ranks == info->point_count; }
    std::map<uint32_t, ReceivedRepairBlock> repair_blocks;  // by first_index (format 1.2)
    uint64_t points_recovered = 0;                  // points that came through repair packets
    std::optional<ReceivedConnectivity> connectivity;  // format 1.3, once a CONNECTIVITY packet was taken
    std::map<uint32_t, Influences> weights;         // format 1.5: influence records by point index
    // Format 1.6 (spec 22.1): the target count, attributes and scales of the first MORPH_DELTAS
    // packet accepted, and the displacement records by point index, dequantized
    // (morph_record_values floats each).
    uint8_t morph_targets = 0, morph_attributes = 0;
    std::vector<float> morph_scales;
    std::map<uint32_t, std::vector<float>> morph;
    // Format 1.8 (spec 24.2): the normal entries of an object with surface normals, by point index.
    std::map<uint32_t, NormalEntry> normal_entries;
    bool normals_complete() const { return info && normal_entries.size() == info->point_count; }
};

struct Rejection {
    uint64_t where = 0;  // packet ordinal (datagrams) or byte offset (container files)
    Error error = Error::Ok;
    std::string detail;
};

struct ReceiveCounters {
    uint64_t accepted = 0;     // packets whose content was taken in
    uint64_t duplicates = 0;   // valid packets that brought nothing new
    uint64_t skipped = 0;      // valid packets of a skippable type this decoder does not know
    uint64_t rejected = 0;     // damaged or invalid packets
    uint64_t pending = 0;      // valid packets held until their stream info arrives
};

// What one held packet costs a receiver besides its payload (header, position, container slot).
inline constexpr size_t kHeldPacketCost = 64;

class ReceivedStream {
public:
    // Limits that keep memory bounded whatever arrives.
    struct Limits {
        // Packets held while waiting for stream info: each counts its payload plus kHeldPacketCost
        // (its bookkeeping), so that empty payloads count too; and at most this many packets.
        size_t max_pending_bytes = 64u << 20;
        size_t max_pending_packets = 65536;
        // Ellipsoids + points a stream may declare. Each received one costs about 100 bytes of map
        // node, so the default bounds a hostile stream's held geometry near 800 MB.
        uint64_t max_elements = 8'000'000;
        size_t max_rejections_kept = 10'000;      // detailed rejection records kept
        // Memory for textures being received, all together: each run of bytes kept counts its
        // length plus kHeldPacketCost.
        size_t max_texture_bytes = 256u << 20;
    };

    ReceivedStream();
    explicit ReceivedStream(Limits limits);

    // Takes one packet that arrived (a datagram, or a packet read from a container). `where` is
    // reported with a rejection. The first valid packet fixes the stream id; packets of another
    // stream are rejected with StreamMismatch. Returns Ok when the packet was accepted, skipped,
    // held, or was a duplicate; the error otherwise (also recorded in rejections()).
    Error add_packet(std::span<const uint8_t> bytes, uint64_t where);
    // Same, for a packet already parsed (checksum already checked).
    Error add_parsed(const PacketView& packet, uint64_t where);

    bool has_stream_id() const { return stream_id_.has_value(); }
    uint32_t stream_id() const { return stream_id_.value_or(0); }
    // Stream-level info once any STREAM_INFO part arrived (objects are in objects()).
    const std::optional<StreamInfo>& info() const { return info_; }
    const std::vector<ReceivedObject>& objects() const { return objects_; }
    const ReceiveCounters& counters() const { return counters_; }
    const std::vector<Rejection>& rejections() const { return rejections_; }
    // Why no stream info is known (for a message): "" when one was accepted or none arrived intact;
    // otherwise how many STREAM_INFO packets were rejected and why the first was.
    std::string stream_info_problem() const;
    // Highest minor version seen among accepted packets.
    uint8_t newest_minor() const { return newest_minor_; }

    // The dequantized geometry received so far for object `index` (ellipsoids by index order,
    // points by stream order). Empty when the object's info has not arrived. For an object with
    // surface normals (format 1.8) a point's normal is the one its NORMALS entry sent, or (0, 0, 0)
    // when it is left to the surface or its entry has not arrived (spec 24.4).
    std::vector<Ellipsoid> ellipsoids(size_t index) const;
    std::vector<SurfacePoint> points(size_t index) const;

    // Scene (format 1.1): what has arrived of the node and mesh tables, materials and textures.
    struct ReceivedTexture {
        TextureInfo info;
        // Disjoint runs of bytes that arrived, offset -> bytes: memory grows with what arrives, not
        // with the size a fragment announces. Emptied once the image is complete.
        std::map<uint32_t, std::vector<uint8_t>> pieces;
        uint64_t received_bytes = 0;
        uint64_t memory = 0;         // what the pieces cost: their bytes plus kHeldPacketCost per piece
        bool complete = false;       // every byte arrived and the image CRC matches
        std::vector<uint8_t> image;  // the whole image file, once complete
    };
    bool has_scene() const { return scene_node_count_ > 0 || scene_mesh_count_ > 0; }
    uint16_t scene_node_count() const { return scene_node_count_; }
    uint16_t scene_mesh_count() const { return scene_mesh_count_; }
    const std::map<uint16_t, SceneNode>& scene_nodes() const { return scene_nodes_; }
    const std::map<uint16_t, SceneMesh>& scene_meshes() const { return scene_meshes_; }
    const std::map<uint16_t, Material>& materials() const { return materials_; }
    // Format 1.3: the patches received, by material index.
    const std::map<uint16_t, MaterialExtensions>& material_extensions() const { return material_extensions_; }
    const std::map<uint16_t, ReceivedTexture>& textures() const { return textures_; }

    // Animations (format 1.4, spec 20): what has arrived, by animation index.
    struct ReceivedAnimation {
        uint16_t track_count = 0;
        std::string name;
        uint16_t joins = kNone;  // morph animations (format 1.6): the ANIMATION it joins
        struct Track {
            AnimationTrackInfo info;
            // Disjoint runs of keys that arrived: first key -> times (and values, V per key).
            struct Run {
                std::vector<float> times, values;
            };
            std::map<uint32_t, Run> runs;
            uint32_t keys_held = 0;
            uint64_t memory = 0;  // what the runs cost: key bytes plus kHeldPacketCost per run
            bool complete = false;  // every key arrived
            bool usable = false;    // complete, and its times strictly increase (spec 20.2)
            std::vector<float> times, values;  // every key, once complete
        };
        std::map<uint16_t, Track> tracks;
        bool complete() const;  // every track 0 .. track_count - 1 complete
    };
    std::optional<uint16_t> animation_count() const { return animation_count_; }
    const std::map<uint16_t, ReceivedAnimation>& animations() const { return animations_; }

    // Skins (format 1.5, spec 21): what has arrived, by skin index.
    struct ReceivedSkin {
        uint16_t joint_count = 0;
        uint16_t skeleton = kNone;
        std::string name;
        std::map<uint16_t, SkinJoint> joints;  // by joint index
        bool complete() const { return joints.size() == joint_count; }
    };
    std::optional<uint16_t> skin_count() const { return skin_count_; }
    const std::map<uint16_t, ReceivedSkin>& skins() const { return skins_; }

    // Morph animations (format 1.6, spec 22.2): what has arrived, by morph animation index (tracks
    // of path Weights).
    std::optional<uint16_t> morph_animation_count() const { return morph_animation_count_; }
    const std::map<uint16_t, ReceivedAnimation>& morph_animations() const { return morph_animations_; }

private:
    Error take_animation(const PacketView& packet, uint64_t where);
    Error take_morph_animation(const PacketView& packet, uint64_t where);
    // The comparisons, memory cap and keeping of spec 20.1 / 22.2 for a decoded piece.
    Error take_keys(const AnimationPiece& piece, std::optional<uint16_t>& table_count,
                    std::map<uint16_t, ReceivedAnimation>& table, const char* type, uint64_t where);
    Error take_morph_deltas(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_skin(const PacketView& packet, uint64_t where);
    Error take_joint_weights(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_scene(const PacketView& packet, uint64_t where);
    Error take_material(const PacketView& packet, uint64_t where);
    Error take_material_extensions(const PacketView& packet, uint64_t where);
    std::optional<uint16_t> material_count() const;  // that of the materials and patches held
    Error take_texture_fragment(const PacketView& packet, uint64_t where);

    Error reject(uint64_t where, Error e, std::string detail);
    Error take_stream_info(const PacketView& packet, uint64_t where);
    uint64_t stream_info_rejected_ = 0;
    std::optional<Rejection> first_stream_info_rejection_;
    Error take_object_packet(const PacketView& packet, uint64_t where);
    Error take_repair(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_point_map(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_normals(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    // Takes a point record that arrived (or was recovered): placed, or held unplaced for a mapped
    // object whose fragment has not arrived. False when the index was held already.
    bool take_point_record(ReceivedObject& object, uint32_t index, const QuantizedPoint& record);
    Error take_connectivity(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_connectivity_repair(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                   uint64_t where);
    // Completes an object's connectivity from its pieces and repair symbols when it can (spec 19.1, 19.5).
    Error complete_connectivity(ReceivedConnectivity& c, const std::string& name, uint64_t where);
    // Counts newly held points [first, first + count) in the object's repair blocks and recovers the
    // blocks that can be (spec 17.4).
    void note_new_points(ReceivedObject& object, const std::vector<uint32_t>& indices);
    void try_recover(ReceivedObject& object, ReceivedRepairBlock& block);
    void release_pending();  // decodes every held packet whose object entry has arrived

    Limits limits_;
    std::optional<uint32_t> stream_id_;
    std::optional<StreamInfo> info_;
    uint16_t object_count_ = 0;
    std::vector<ReceivedObject> objects_;
    struct Pending {
        PacketHeader header;
        std::vector<uint8_t> payload;
        uint64_t where;
    };
    std::vector<Pending> pending_;
    size_t pending_bytes_ = 0;
    ReceiveCounters counters_;
    std::vector<Rejection> rejections_;
    uint8_t newest_minor_ = 0;
    uint16_t scene_node_count_ = 0, scene_mesh_count_ = 0;
    std::map<uint16_t, SceneNode> scene_nodes_;
    std::map<uint16_t, SceneMesh> scene_meshes_;
    std::map<uint16_t, Material> materials_;
    std::map<uint16_t, MaterialExtensions> material_extensions_;
    std::map<uint16_t, ReceivedTexture> textures_;
    size_t texture_bytes_ = 0;  // textures, patches and animation keys (the texture cap)
    std::optional<uint16_t> animation_count_;
    std::map<uint16_t, ReceivedAnimation> animations_;
    std::optional<uint16_t> skin_count_;
    std::map<uint16_t, ReceivedSkin> skins_;
    std::optional<uint16_t> morph_animation_count_;
    std::map<uint16_t, ReceivedAnimation> morph_animations_;
};

// The objects a receiver waits for joint weights of (spec 21.3): those of the meshes of the node
// records that name a skin, each with the smallest joint count of those skins (0x10000 for a skin
// that has not arrived). A node whose mesh record has not arrived adds nothing.
std::map<uint16_t, uint32_t> skinned_objects(const ReceivedStream& stream);

// What a receiver shows of the animations (spec 20.2): each complete animation with the tracks it
// keeps, in index order: a track is left out when it is not usable, when node_shown(its node) is
// false, or when a kept track of a smaller index of that animation has its node and path; an
// animation with no track left is not shown.
struct ShownAnimation {
    uint16_t index = 0;        // ANIMATION index, or the morph animation's when `morph_only`
    bool morph_only = false;   // format 1.6: a morph animation that stands alone
    std::vector<uint16_t> tracks;  // of the ANIMATION
    std::vector<std::pair<uint16_t, uint16_t>> morph_tracks;  // (morph animation, track), as written
};
// Format 1.6 (spec 22.4): `node_targets(node)` is the target count of the node's mesh when that
// mesh is shown with its targets, else 0 (no morph track is kept when it is not given). An ANIMATION
// is shown only once every morph animation of the table has taken a packet and those joining it are
// complete; the morph animations standing alone come after the ANIMATION table, in index order.
std::vector<ShownAnimation> shown_animations(const ReceivedStream& stream,
                                             const std::function<bool(uint16_t node)>& node_shown,
                                             const std::function<unsigned(uint16_t node)>& node_targets = {});

// The objects a receiver waits for displacement records of (spec 22.4): those of the meshes whose
// records carry targets, each with the target count of such a mesh (the smallest, when several).
std::map<uint16_t, uint8_t> morph_target_objects(const ReceivedStream& stream);
// Whether the receiver holds a point of `object` together with its displacement record (spec 22.3).
bool morphed(const ReceivedObject& object);
// Whether mesh `mesh` is shown with its targets (spec 22.4), given which of its objects are shown
// (`object_shown`): it has targets and every object it shows is morphed with that count.
bool mesh_shows_targets(const ReceivedStream& stream, const SceneMesh& mesh,
                        const std::function<bool(uint16_t object)>& object_shown);

// The exact triangle list of object `object` (spec 19.2, 19.4): Ok when every point of it and its
// whole connectivity are held and it decodes; Truncated (with `why`) while something is missing;
// MalformedPayload (with `why`) when the connectivity is unusable.
Error exact_triangles(const ReceivedStream& stream, size_t object, std::vector<Triangle>& out, std::string& why);

// For a validator (spec 19.5): whether a CONNECTIVITY_REPAIR packet's symbol is its row of the code
// over the object's complete connectivity. Ok when it is or when the connectivity is not complete;
// StreamMismatch with `why` when it is not; MalformedPayload when the packet does not decode.
Error check_connectivity_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why);

// For a validator (spec 11.5, 17.4): whether a POINTS_REPAIR packet's symbol is its row of the code
// over the points `stream` holds. Ok when it is, or when the stream does not hold every point of the
// block (nothing to compare with; the missing points are reported as such); StreamMismatch, with
// `why`, when it is not; MalformedPayload when the packet does not fit the stream.
Error check_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why);

// ---------------------------------------------------------------------------------------------
// Container files (.ellc): a recorded stream

// The container header followed by the packets in the given order.
std::vector<uint8_t> write_container(const std::vector<std::vector<uint8_t>>& packets);

// A contiguous run of bytes of a container that holds no valid packet.
struct DamagedRegion {
    uint64_t offset = 0;
    uint64_t length = 0;
    Error first_error = Error::Ok;  // why the first packet expected at `offset` did not parse
};

struct ContainerPacket {
    uint64_t offset = 0;  // byte offset of the packet in the file
    PacketView view;      // points into the bytes given to read_container
};

struct ContainerContents {
    Error header_error = Error::Ok;  // BadSignature / UnsupportedContainer / TooShort: nothing read
    std::vector<ContainerPacket> packets;
    std::vector<DamagedRegion> damaged;
};

// Reads every intact packet of a container held in memory. After damage it resynchronizes on the
// next offset where a whole packet with a valid checksum starts, so every intact packet after a
// damaged region is kept. The returned views point into `bytes`.
ContainerContents read_container(std::span<const uint8_t> bytes);

// Reads a whole file into memory. Returns IoError (with the reason in `message`) when it cannot.
Error read_file(const std::string& path, std::vector<uint8_t>& out, std::string& message);
// Writes a file through a temporary file and a rename, so a failed write leaves no partial file.
// The temporary is created in the output's folder under an unpredictable name (".NAME.XXXXXXXXXXXX
// .partial"), exclusively and without following a symlink planted there; the rename replaces
// `path` itself (a symlink at `path` is replaced, its target is not written).
Error write_file(const std::string& path, std::span<const uint8_t> bytes, std::string& message);

}  // namespace ellicast
