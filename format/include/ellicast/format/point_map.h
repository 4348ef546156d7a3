// Mapped points (format 1.7): the map of an object's occupied cells that POINT_MAP packets carry, the
// ranks by which MAPPED_POINTS records are placed in its cells, and the encoder's choice of a map
// level. Follows spec/format.md section 23 (Format 1.7 addition: mapped points): 23.2 Cells, ranks
// and indices; 23.3 POINT_MAP payload; 23.7 Sender behaviour.
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

}  // namespace ellicast
