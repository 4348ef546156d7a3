// Surface normals (format 1.8): the NORMALS packets that send the normals a receiver should not take
// from the surface, and the surface normal it computes for every other point from the exact layer.
// Follows spec/format.md section 24 (Format 1.8 addition: surface normals): 24.2 NORMALS payload;
// 24.3 The surface normal of a point; 24.4 What a receiver shows, completeness and conformance.
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/stream_info.h"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace ellicast {

// Surface normals (format 1.8, spec 24): a point's normal entry says whether its normal is sent
// (then its octahedral normal, normal_bits per component) or left to the surface.
struct NormalEntry {
    bool sent = false;
    std::array<uint32_t, 2> normal{};  // when sent
    bool operator==(const NormalEntry&) const = default;
};

// The normal entries a receiver holds, by point index, in memory near what they cost on the wire: a
// "surface" entry is one bit in a NORMALS packet, so it is a bit here too (a map node per entry made
// 1 MB of such entries cost 509 MB). Pages of 512 points, made when an entry of theirs arrives: a
// bit per point held, a bit per point whose normal is sent, and the sent normals in index order
// (16 bits a component: normal_bits is at most 16). Iterates as (index, entry) pairs in index order.
inline constexpr uint32_t kNormalPagePoints = 512;
struct NormalPage {
    std::array<uint64_t, kNormalPagePoints / 64> held{}, sent{};
    // The sent normals of the page's points in index order: offset in the page, then u and v.
    std::vector<std::pair<uint16_t, std::array<uint16_t, 2>>> normals;
};
class NormalEntries {
public:
    static constexpr uint32_t kPagePoints = kNormalPagePoints;
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    bool contains(uint32_t index) const;
    std::optional<NormalEntry> find(uint32_t index) const;
    // Keeps the entry of a point not held yet; returns false (and changes nothing) when one is held.
    bool insert(uint32_t index, const NormalEntry& entry);
    // What the held entries cost: the pages, their sent normals and their bookkeeping.
    uint64_t memory() const { return memory_; }

    class const_iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = std::pair<uint32_t, NormalEntry>;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = value_type;
        value_type operator*() const;
        const_iterator& operator++();
        bool operator==(const const_iterator& o) const { return page_ == o.page_ && bit_ == o.bit_; }

    private:
        friend class NormalEntries;
        const_iterator(const NormalEntries* owner, std::map<uint32_t, NormalPage>::const_iterator page,
                       uint32_t bit)
            : owner_(owner), page_(page), bit_(bit) {}
        void settle();  // forward to the next held bit (or the end)
        const NormalEntries* owner_;
        std::map<uint32_t, NormalPage>::const_iterator page_;
        uint32_t bit_;
    };
    const_iterator begin() const;
    const_iterator end() const;

private:
    std::map<uint32_t, NormalPage> pages_;  // by page number (index / kPagePoints)
    size_t size_ = 0;
    uint64_t memory_ = 0;
};

// Surface normals (format 1.8, spec 24): NORMALS packets.
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

}  // namespace ellicast
