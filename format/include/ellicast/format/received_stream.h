// Receiving: collects whatever packets arrive, in any order, with duplicates and damage.
// ReceivedStream is the reference decoder's state: it checks each packet, holds what is missing its
// stream info, and keeps every element, scene record, texture, key and repair symbol by index; the
// functions after it say what a receiver shows and let a validator check repair symbols. Follows
// spec/format.md section 11 (Receiver behaviour: 11.1 Checking one packet; 11.2 What a decoder does
// with ...; 11.5 Completeness) and the receiver's part of each later addition: 15.4, 17.4, 18.4,
// 19.4, 20.2, 21.3, 22.4, 23.6 and 24.4.
#pragma once

#include "ellicast/format/animation.h"
#include "ellicast/format/connectivity.h"
#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"
#include "ellicast/format/extras.h"
#include "ellicast/format/material_extensions.h"
#include "ellicast/format/normals.h"
#include "ellicast/format/packet.h"
#include "ellicast/format/paged_records.h"
#include "ellicast/format/point_map.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/repair.h"
#include "ellicast/format/scene.h"
#include "ellicast/format/skin.h"
#include "ellicast/format/stream_info.h"
#include "ellicast/format/texcoords.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace ellicast {

// An object's connectivity as it arrives (spec 19.1).
struct ReceivedConnectivity {
    bool mesh = false;             // format 1.11: EXACT_MESH packets (spec 27), not CONNECTIVITY
    uint32_t triangle_count = 0, carried_count = 0, coded_size = 0, coded_crc = 0;
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

// A POINT_MAP fragment a receiver accepted (spec 23.3), held compactly: each cell's Morton code in
// 4 bytes where the map's level allows it (3 x level <= 32) and 8 where not, and the rank of its
// first point from the fragment's first rank (its count is the difference to the next cell's): 8
// bytes a cell at the levels encoders choose, 12 at deeper ones.
class ReceivedMapFragment {
public:
    // `cells` in increasing code, each count >= 1, summing to point_total.
    ReceivedMapFragment(uint32_t point_total, const std::vector<MapCell>& cells, unsigned map_level);
    uint32_t point_total() const { return point_total_; }
    size_t size() const { return starts_.size(); }
    uint64_t code(size_t i) const {
        return wide_ ? codes_[2 * i] | uint64_t(codes_[2 * i + 1]) << 32 : codes_[i];
    }
    uint32_t count(size_t i) const { return (i + 1 < starts_.size() ? starts_[i + 1] : point_total_) - starts_[i]; }
    // The cell holding the point of rank `rank` counted from the fragment's first rank (< point_total).
    size_t cell_of(uint32_t rank) const;
    // The cells as [code, count], in code order.
    std::vector<MapCell> cells() const;
    bool same_cells(const std::vector<MapCell>& cells) const;
    // Bytes held (the vectors' capacity).
    size_t memory() const { return codes_.capacity() * sizeof(uint32_t) + starts_.capacity() * sizeof(uint32_t); }

private:
    uint32_t point_total_ = 0;
    bool wide_ = false;
    std::vector<uint32_t> codes_;   // one a cell, or (low, high) pairs when wide
    std::vector<uint32_t> starts_;
};

struct ReceivedObject {
    std::optional<ObjectInfo> info;                 // once its stream info entry arrived
    PagedRecords<QuantizedEllipsoid> ellipsoids;    // by index; duplicates collapse
    // Per-point records are held compactly (paged_records.h): what they cost counts toward the
    // receiver's byte budget (spec 11.6).
    PointRecords points;          // by index (a mapped object's: placed, spec 23.4)
    // Format 1.7 (spec 23): a mapped object's fragments by first rank, and the records held but not
    // placed (positions are offsets inside their cells) by index.
    std::map<uint32_t, ReceivedMapFragment> map_fragments;
    PointRecords unplaced;
    uint64_t map_ranks = 0;                          // ranks the fragments hold
    bool map_complete() const { return info && info->mapped() && map_ranks == info->point_count; }
    std::map<uint32_t, ReceivedRepairBlock> repair_blocks;  // by first_index (format 1.2)
    uint64_t points_recovered = 0;                  // points that came through repair packets
    std::optional<ReceivedConnectivity> connectivity;  // format 1.3, once a CONNECTIVITY packet was taken
    PagedRecords<Influences> weights;               // format 1.5: influence records by point index
    // Format 1.6 (spec 22.1): the target count, attributes and scales of the first MORPH_DELTAS
    // packet accepted, and the displacement records by point index, dequantized
    // (morph_record_values floats each: the stride).
    uint8_t morph_targets = 0, morph_attributes = 0;
    std::vector<float> morph_scales;
    PagedRecords<float> morph;
    // Format 1.8 (spec 24.2): the normal entries of an object with surface normals, by point index.
    NormalEntries normal_entries;
    bool normals_complete() const { return info && normal_entries.size() == info->point_count; }
    // Format 1.14 (spec 30.1): the further texture-coordinate sets, set s at [s - 1], sized by the
    // set_count of the first TEXCOORDS packet accepted (empty before one).
    std::vector<ReceivedTexcoordSet> texcoord_sets;
    // Every point's record of every set (spec 30.2); true for an object without TEXCOORDS packets.
    bool texcoords_complete() const {
        for (const ReceivedTexcoordSet& s : texcoord_sets)
            if (!info || s.records.size() != info->point_count) return false;
        return true;
    }
    uint64_t map_memory = 0;  // what the map fragments held cost (cells, starts, bookkeeping)
    // What the object's elements and per-point records cost as held (spec 11.2, the byte budget):
    // ellipsoids, points placed and not, influences, displacements, normal entries, map fragments.
    uint64_t memory() const;
    uint64_t texcoord_memory() const {
        uint64_t m = 0;
        for (const ReceivedTexcoordSet& s : texcoord_sets) m += s.records.memory();
        return m;
    }
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

// The byte budget of spec 11.2 shared by several receivers (a network receiver's candidate streams,
// spec 11.4): what their objects hold together, against the bytes of the intact datagrams that
// reached any of them, which their owner counts (each datagram once, however many took it).
struct SharedMemoryBudget {
    uint64_t held = 0;   // kept up to date by every ReceivedStream sharing it
    uint64_t bytes = 0;  // counted by the owner
    uint64_t base = 64u << 20, per_byte = 8;
    uint64_t budget() const { return base + per_byte * bytes; }
};

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
        // The byte budget for what objects hold (ReceivedObject::memory(), spec 11.2): a packet of an
        // object is refused while they hold more than memory_base plus memory_per_byte times the
        // bytes of the intact packets given to this receiver, so that memory follows what arrived.
        uint64_t memory_base = 64u << 20;
        uint64_t memory_per_byte = 8;
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
    // The byte budget (spec 11.2): what the objects hold, the bytes of intact packets given, and
    // the budget they make.
    uint64_t held_memory() const { return held_memory_; }
    uint64_t bytes_taken() const { return bytes_taken_; }
    uint64_t memory_budget() const { return budget_in_force().budget(); }
    // Joins a budget shared with other receivers (their owner counts the bytes): from now on a packet
    // of an object is refused while all of them together hold more than it allows. What this one
    // holds already is added to it; the owner takes it back (held_memory()) when it drops this one.
    void share_memory_budget(std::shared_ptr<SharedMemoryBudget> budget);
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

    // Cameras and punctual lights (format 1.10, spec 26): what has arrived, by index, and the table
    // sizes of the CAMERA and LIGHT packets accepted.
    std::optional<uint16_t> camera_count() const { return camera_count_; }
    const std::map<uint16_t, SceneCamera>& cameras() const { return cameras_; }
    std::optional<uint16_t> light_count() const { return light_count_; }
    const std::map<uint16_t, SceneLight>& lights() const { return lights_; }

    // Extras (format 1.12, spec 28): the text of each target that has taken a fragment, and the
    // text count of the EXTRAS packets accepted.
    struct ReceivedExtras {
        uint32_t text_size = 0, text_crc = 0;  // the description (spec 28.1)
        std::map<uint32_t, std::vector<uint8_t>> pieces;  // disjoint runs of bytes, until complete
        uint64_t received_bytes = 0;
        uint64_t memory = 0;    // what its runs (then its text) count toward the texture cap
        bool complete = false;  // every byte arrived, the CRC-32C matches and the text is JSON
        std::string text;       // the whole text, once complete
    };
    using ExtrasKey = std::pair<ExtrasTarget, uint16_t>;
    std::optional<uint16_t> extras_count() const { return extras_count_; }
    const std::map<ExtrasKey, ReceivedExtras>& extras() const { return extras_; }

    // Required extensions (format 1.13, spec 29): the names held, by name_index, and the name count of
    // the REQUIRED_EXTENSION packets accepted.
    std::optional<uint8_t> required_extension_count() const { return required_extension_count_; }
    const std::map<uint8_t, std::string>& required_extensions() const { return required_extensions_; }

private:
    Error take_animation(const PacketView& packet, uint64_t where);
    Error take_morph_animation(const PacketView& packet, uint64_t where);
    // The comparisons, memory cap and keeping of spec 20.1 / 22.2 for a decoded piece.
    Error take_keys(const AnimationPiece& piece, std::optional<uint16_t>& table_count,
                    std::map<uint16_t, ReceivedAnimation>& table, const char* type, uint64_t where);
    Error take_morph_deltas(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_skin(const PacketView& packet, uint64_t where);
    Error take_camera(const PacketView& packet, uint64_t where);
    Error take_light(const PacketView& packet, uint64_t where);
    Error take_extras(const PacketView& packet, uint64_t where);
    Error take_required_extension(const PacketView& packet, uint64_t where);
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
    Error take_object_content(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_repair(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_point_map(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_normals(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_texcoords(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    // Takes a point record that arrived (or was recovered): placed, or held unplaced for a mapped
    // object whose fragment has not arrived. False when the index was held already.
    bool take_point_record(ReceivedObject& object, uint32_t index, const QuantizedPoint& record);
    Error take_connectivity(ReceivedObject& object, const PacketView& packet, const std::string& name, uint64_t where);
    Error take_layer_kind(const ReceivedObject& object, bool mesh, uint32_t carried_count, const std::string& name,
                          uint64_t where);
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
    uint64_t held_memory_ = 0, bytes_taken_ = 0;  // the byte budget (spec 11.2)
    std::shared_ptr<SharedMemoryBudget> shared_budget_;
    // The budget a packet is checked against: the shared one, or this receiver's own figures.
    SharedMemoryBudget budget_in_force() const;
    ReceiveCounters counters_;
    std::vector<Rejection> rejections_;
    uint8_t newest_minor_ = 0;
    uint16_t scene_node_count_ = 0, scene_mesh_count_ = 0;
    std::map<uint16_t, SceneNode> scene_nodes_;
    std::map<uint16_t, SceneMesh> scene_meshes_;
    std::map<uint16_t, Material> materials_;
    std::map<uint16_t, MaterialExtensions> material_extensions_;
    std::map<uint16_t, ReceivedTexture> textures_;
    size_t texture_bytes_ = 0;  // textures, patches, animation keys, cameras, lights and extras (the texture cap)
    uint64_t carried_elements_ = 0;  // format 1.11: carried vertices of the exact layers taken (spec 27.1)
    std::optional<uint16_t> animation_count_;
    std::map<uint16_t, ReceivedAnimation> animations_;
    std::optional<uint16_t> skin_count_;
    std::map<uint16_t, ReceivedSkin> skins_;
    std::optional<uint16_t> morph_animation_count_;
    std::map<uint16_t, ReceivedAnimation> morph_animations_;
    std::optional<uint16_t> camera_count_, light_count_;
    std::map<uint16_t, SceneCamera> cameras_;
    std::map<uint16_t, SceneLight> lights_;
    std::optional<uint16_t> extras_count_;
    std::map<ExtrasKey, ReceivedExtras> extras_;
    std::optional<uint8_t> required_extension_count_;
    std::map<uint8_t, std::string> required_extensions_;
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

// The exact triangle list of object `object` (spec 19.2, 19.4; 27.2): Ok when every point of it and
// its whole exact layer are held and it decodes; Truncated (with `why`) while something is missing;
// MalformedPayload (with `why`) when the layer is unusable. The triangles name vertices: the points
// 0 .. point_count - 1, then (format 1.11) the `carried` vertices.
Error exact_layer(const ReceivedStream& stream, size_t object, std::vector<Triangle>& out,
                  std::vector<QuantizedPoint>& carried, std::string& why);
// The same without the carried vertices (for an object whose exact layer carries none, the triangles
// name points only).
Error exact_triangles(const ReceivedStream& stream, size_t object, std::vector<Triangle>& out, std::string& why);

// For a validator (spec 19.5): whether a CONNECTIVITY_REPAIR packet's symbol is its row of the code
// over the object's complete connectivity. Ok when it is or when the connectivity is not complete;
// StreamMismatch with `why` when it is not; MalformedPayload when the packet does not decode.
Error check_connectivity_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why);

// The same check over a whole recording: each row's symbol is computed once per object, and a packet
// whose symbol size differs from the first one checked for its object is a mismatch itself (spec
// 19.5: one symbol size), so that many forged rows over a large exact layer cost one pass over its
// bytes a row, not one a packet.
class ConnectivityRepairChecker {
public:
    explicit ConnectivityRepairChecker(const ReceivedStream& stream) : stream_(stream) {}
    Error check(const PacketView& packet, std::string& why);

private:
    struct ObjectState {
        uint16_t symbol_size = 0;
        std::vector<std::vector<uint8_t>> sources;     // the coded connectivity cut into symbols
        std::map<uint8_t, std::vector<uint8_t>> rows;  // the symbols of rows computed so far
    };
    const ReceivedStream& stream_;
    std::map<uint16_t, ObjectState> objects_;
};

// For a validator (spec 11.5, 17.4): whether a POINTS_REPAIR packet's symbol is its row of the code
// over the points `stream` holds. Ok when it is, or when the stream does not hold every point of the
// block (nothing to compare with; the missing points are reported as such); StreamMismatch, with
// `why`, when it is not; MalformedPayload when the packet does not fit the stream.
Error check_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why);

// The same check over a whole recording: each block's source symbols are built once and each row's
// verdict is kept, so that many repair packets over one large block cost one pass over its points
// (checking each packet alone took 39.5 s for 2.6 MB of rows over a 0.87M-point block, issue 29).
// Only a packet whose block is the one the stream holds for its object at that index is compared (a
// block that contradicts it was rejected by the receiver, which reports it), so the work is bounded
// by the object's points, whatever the packets declare.
class RepairPacketChecker {
public:
    // `held_blocks_only` false: compare any block that fits the object (check_repair_packet's way,
    // for one packet against a stream that may not have taken it).
    explicit RepairPacketChecker(const ReceivedStream& stream, bool held_blocks_only = true)
        : stream_(stream), held_blocks_only_(held_blocks_only) {}
    Error check(const PacketView& packet, std::string& why);

private:
    struct BlockState {
        bool complete = false;                     // every point of the block is held
        std::vector<std::vector<uint8_t>> sources;  // its source symbols, once built
        std::map<uint8_t, std::vector<uint8_t>> rows;  // the symbols of rows computed so far
    };
    const ReceivedStream& stream_;
    bool held_blocks_only_;
    std::map<std::pair<uint16_t, uint32_t>, BlockState> blocks_;  // by object and first index
};

}  // namespace ellicast
