// Mapped points (format 1.7, spec 23): ranks and indices, cells and their Morton codes, the
// POINT_MAP tree, and the encoder's choice of a map level.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <numeric>

namespace ellicast {

using namespace detail;

uint32_t mapped_rank(uint32_t index, uint32_t point_count, uint32_t batch) {
    const uint64_t n = batch, batches = (uint64_t(point_count) + n - 1) / n;
    const uint64_t last = point_count - (batches - 1) * n;  // points in the last batch, 1..n
    const uint64_t t = index / n, j = index % n;
    return uint32_t(j * batches + t - (j > last ? j - last : 0));
}

uint32_t mapped_index(uint32_t rank, uint32_t point_count, uint32_t batch) {
    const uint64_t n = batch, batches = (uint64_t(point_count) + n - 1) / n;
    const uint64_t last = point_count - (batches - 1) * n;
    uint64_t t, j;
    if (rank < last * batches) {
        j = rank / batches;
        t = rank % batches;
    } else {  // the rows past the last batch's end hold batches - 1 points each
        const uint64_t rest = rank - last * batches;
        j = last + rest / (batches - 1);
        t = rest % (batches - 1);
    }
    return uint32_t(t * n + j);
}

namespace {
// The low 21 bits of v spread to every third bit: bit i goes to bit 3i.
uint64_t spread3(uint32_t v) {
    uint64_t x = v & 0x1FFFFFu;
    x = (x | x << 32) & 0x1F00000000FFFFull;
    x = (x | x << 16) & 0x1F0000FF0000FFull;
    x = (x | x << 8) & 0x100F00F00F00F00Full;
    x = (x | x << 4) & 0x10C30C30C30C30C3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

// The inverse of spread3: every third bit of x (bits 0, 3, 6, ...) gathered into the low 21 bits.
uint32_t compact3(uint64_t x) {
    x &= 0x1249249249249249ull;
    x = (x | x >> 2) & 0x10C30C30C30C30C3ull;
    x = (x | x >> 4) & 0x100F00F00F00F00Full;
    x = (x | x >> 8) & 0x1F0000FF0000FFull;
    x = (x | x >> 16) & 0x1F00000000FFFFull;
    x = (x | x >> 32) & 0x1FFFFFull;
    return uint32_t(x);
}
}  // namespace

// Bit b of the cell's coordinate on axis a (bit position_bits - level + b of q[a]) is bit 3b + a.
uint64_t morton_cell(const std::array<uint32_t, 3>& q, unsigned position_bits, unsigned level) {
    if (level == 0) return 0;
    const unsigned shift = position_bits - level;
    const uint32_t mask = level >= 21 ? 0x1FFFFFu : (1u << level) - 1;
    return spread3((q[0] >> shift) & mask) | spread3((q[1] >> shift) & mask) << 1 | spread3((q[2] >> shift) & mask) << 2;
}

std::array<uint32_t, 3> cell_corner(uint64_t code, unsigned position_bits, unsigned level) {
    // Bits 3b + a for b < level only (level <= 21: 63 bits).
    if (level < 21) code &= (uint64_t(1) << (3 * level)) - 1;
    std::array<uint32_t, 3> c{compact3(code), compact3(code >> 1), compact3(code >> 2)};
    for (auto& v : c) v <<= (position_bits - level);
    return c;
}

namespace {

size_t rice_bits(uint64_t v, unsigned k) { return size_t(v >> k) + 1 + k; }

// The cells [a, b) share the code prefix of `level`; writes their node (spec 23.3).
void put_node(BitWriter& w, const std::vector<MapCell>& cells, size_t a, size_t b, unsigned level, unsigned map_level,
              unsigned rice) {
    if (level == map_level) {
        const uint64_t v = cells[a].count - 1u;
        for (uint64_t q = v >> rice; q > 0;) {
            const int run = int(std::min<uint64_t>(q, 32));
            w.put(run == 32 ? 0xFFFFFFFFu : (1u << run) - 1u, run);
            q -= uint64_t(run);
        }
        w.put(0, 1);
        if (rice > 0) w.put(uint32_t(v & ((1u << rice) - 1u)), int(rice));
        return;
    }
    const unsigned shift = 3 * (map_level - level - 1);
    uint32_t mask = 0;
    for (size_t i = a; i < b; ++i) mask |= 1u << ((cells[i].code >> shift) & 7u);
    w.put(mask, 8);
    for (size_t i = a; i < b;) {
        const uint64_t child = cells[i].code >> shift;
        size_t e = i;
        while (e < b && (cells[e].code >> shift) == child) ++e;
        put_node(w, cells, i, e, level + 1, map_level, rice);
        i = e;
    }
}

}  // namespace

size_t point_map_tree_bits(std::span<const MapCell> cells, unsigned map_level, unsigned root_level, unsigned rice) {
    size_t bits = 0;
    for (size_t i = 0; i < cells.size(); ++i) {
        bits += rice_bits(cells[i].count - 1u, rice);
        // A node of level l above the cells starts where the code prefix of level l changes.
        for (unsigned l = root_level; l < map_level; ++l) {
            const unsigned shift = 3 * (map_level - l);
            if (i == 0 || (cells[i].code >> shift) != (cells[i - 1].code >> shift)) bits += 8;
        }
        const unsigned root_shift = 3 * (map_level - root_level);
        if (i == 0 || (cells[i].code >> root_shift) != (cells[i - 1].code >> root_shift)) bits += 3 * root_level;
    }
    return bits;
}

std::vector<uint8_t> encode_point_map_payload(const PointMapFragment& fragment, unsigned map_level) {
    const std::vector<MapCell>& cells = fragment.cells;
    const unsigned F = fragment.root_level, shift = 3 * (map_level - F);
    size_t roots = 0;
    for (size_t i = 0; i < cells.size(); ++i) roots += i == 0 || (cells[i].code >> shift) != (cells[i - 1].code >> shift);
    std::vector<uint8_t> out;
    put_u32(out, fragment.first_rank);
    put_u32(out, fragment.point_total);
    put_u8(out, fragment.root_level);
    put_u8(out, fragment.rice);
    put_u16(out, uint16_t(roots));
    BitWriter w(out);
    for (size_t i = 0; i < cells.size();) {
        const uint64_t root = cells[i].code >> shift;
        size_t e = i;
        while (e < cells.size() && (cells[e].code >> shift) == root) ++e;
        for (unsigned b = 0; b < 3 * F; b += 32) w.put(uint32_t(root >> b), int(std::min(32u, 3 * F - b)));
        put_node(w, cells, i, e, F, map_level, fragment.rice);
        i = e;
    }
    return out;
}

Error decode_point_map_header(std::span<const uint8_t> payload, PointMapFragment& out) {
    if (payload.size() < kPointMapHeaderSize) return Error::MalformedPayload;
    PointMapFragment f;
    f.first_rank = get_u32(payload.data());
    f.point_total = get_u32(payload.data() + 4);
    f.root_level = payload[8];
    f.rice = payload[9];
    f.root_count = get_u16(payload.data() + 10);
    if (f.point_total == 0 || f.rice > 15 || f.root_count == 0) return Error::MalformedPayload;
    out = std::move(f);
    return Error::Ok;
}

namespace {

struct TreeReader {
    BitReader r;
    unsigned map_level, rice;
    uint64_t total = 0, limit = 0;
    std::vector<MapCell>& cells;
    std::string why;

    bool fail(std::string text) {
        if (why.empty()) why = std::move(text);
        return false;
    }
    bool node(uint64_t code, unsigned level) {
        if (level == map_level) {
            uint64_t q = 0;
            while (true) {
                if (r.position() >= r.size_bits()) return fail("the bits end inside a count");
                if (r.get(1) == 0) break;
                ++q;
            }
            if (r.position() + rice > r.size_bits()) return fail("the bits end inside a count");
            const uint64_t v = (q << rice) | (rice > 0 ? r.get(int(rice)) : 0u);
            total += v + 1;
            if (total > limit) return fail("the counts add up to more than point_total " + std::to_string(limit));
            cells.push_back({code, uint32_t(v + 1)});
            return true;
        }
        if (r.position() + 8 > r.size_bits()) return fail("the bits end inside a mask");
        const uint32_t mask = r.get(8);
        if (mask == 0) return fail("a mask of 0 at level " + std::to_string(level));
        for (unsigned c = 0; c < 8; ++c)
            if ((mask >> c) & 1u)
                if (!node(code * 8 + c, level + 1)) return false;
        return true;
    }
};

}  // namespace

Error decode_point_map_payload(std::span<const uint8_t> payload, unsigned position_bits, unsigned map_level,
                               PointMapFragment& out, std::string* why) {
    PointMapFragment f;
    auto fail = [&](std::string text) {
        if (why) *why = std::move(text);
        return Error::MalformedPayload;
    };
    if (Error e = decode_point_map_header(payload, f); e != Error::Ok)
        return fail("shorter than 12 bytes, or point_total 0, rice above 15 or root_count 0");
    if (map_level == 0 || map_level >= position_bits) return fail("the object has no map (map_level 0)");
    if (f.root_level > map_level)
        return fail("root_level " + std::to_string(f.root_level) + " above the map level " + std::to_string(map_level));
    TreeReader t{BitReader(payload.subspan(kPointMapHeaderSize)), map_level, f.rice, 0, f.point_total, f.cells, {}};
    const unsigned F = f.root_level;
    uint64_t previous = 0;
    for (size_t i = 0; i < f.root_count; ++i) {
        if (t.r.position() + 3 * F > t.r.size_bits()) return fail("the bits end inside root " + std::to_string(i));
        uint64_t root = 0;
        for (unsigned b = 0; b < 3 * F; b += 32) root |= uint64_t(t.r.get(int(std::min(32u, 3 * F - b)))) << b;
        if (i > 0 && root <= previous) return fail("root " + std::to_string(i) + " is not above the one before it");
        previous = root;
        if (!t.node(root, F)) return fail(t.why + " (root " + std::to_string(i) + ")");
    }
    if (t.total != f.point_total)
        return fail("the counts add up to " + std::to_string(t.total) + ", not point_total " + std::to_string(f.point_total));
    const size_t expected = kPointMapHeaderSize + (t.r.position() + 7) / 8;
    if (payload.size() != expected)
        return fail("payload_length " + std::to_string(payload.size()) + " where the tree takes " + std::to_string(expected));
    out = std::move(f);
    return Error::Ok;
}

bool point_map_cells(const std::vector<QuantizedPoint>& points, const StreamInfo& info, const ObjectInfo& object,
                     std::vector<MapCell>& cells) {
    cells.clear();
    const uint32_t n = uint32_t(points.size());
    if (!object.mapped() || n == 0) return n == 0;
    std::vector<uint64_t> by_rank(n);
    for (uint32_t i = 0; i < n; ++i)
        by_rank[mapped_rank(i, n, object.map_batch)] = morton_cell(points[i].position, info.position_bits, object.map_level);
    for (uint32_t r = 0; r < n; ++r) {
        if (r > 0 && by_rank[r] < by_rank[r - 1]) return false;
        if (r > 0 && by_rank[r] == by_rank[r - 1])
            ++cells.back().count;
        else
            cells.push_back({by_rank[r], 1});
    }
    return true;
}

namespace {

// The Rice parameter that codes the counts of `cells` in the fewest bits.
unsigned best_rice(std::span<const MapCell> cells) {
    unsigned best = 0;
    size_t best_bits = SIZE_MAX;
    for (unsigned k = 0; k <= 15; ++k) {
        size_t bits = 0;
        for (const MapCell& c : cells) bits += rice_bits(c.count - 1u, k);
        if (bits < best_bits) best_bits = bits, best = k;
    }
    return best;
}

}  // namespace

std::vector<PointMapFragment> plan_point_map(const std::vector<MapCell>& cells, unsigned map_level, size_t packet_size) {
    std::vector<PointMapFragment> out;
    if (cells.empty()) return out;
    const size_t cap_bits = (std::min(packet_size, kMaxPacketSize) - kPacketOverhead - kPointMapHeaderSize) * 8;
    const unsigned k = best_rice(cells);
    for (unsigned F = 0; F <= map_level; ++F) {
        // The roots of level F: runs of cells with one prefix, and the bits of each.
        const unsigned shift = 3 * (map_level - F);
        std::vector<std::pair<size_t, size_t>> roots;  // [begin, end) of cells
        for (size_t i = 0; i < cells.size();) {
            size_t e = i;
            while (e < cells.size() && (cells[e].code >> shift) == (cells[i].code >> shift)) ++e;
            roots.emplace_back(i, e);
            i = e;
        }
        std::vector<size_t> bits(roots.size());
        bool fits = true;
        for (size_t r = 0; r < roots.size() && fits; ++r) {
            bits[r] = point_map_tree_bits(std::span(cells).subspan(roots[r].first, roots[r].second - roots[r].first),
                                          map_level, F, k);
            fits = bits[r] <= cap_bits && roots[r].second - roots[r].first <= 0xFFFF;
        }
        if (!fits) continue;
        uint64_t rank = 0;
        for (size_t r = 0; r < roots.size();) {
            size_t used = 0, e = r;
            while (e < roots.size() && used + bits[e] <= cap_bits && e - r < 0xFFFF) used += bits[e++];
            PointMapFragment f;
            f.first_rank = uint32_t(rank);
            f.root_level = uint8_t(F);
            f.root_count = uint16_t(e - r);
            f.cells.assign(cells.begin() + long(roots[r].first), cells.begin() + long(roots[e - 1].second));
            uint64_t total = 0;
            for (const MapCell& c : f.cells) total += c.count;
            f.point_total = uint32_t(total);
            // The fragment's own best parameter never makes it longer than the shared one did.
            const unsigned own = best_rice(f.cells);
            f.rice = uint8_t(point_map_tree_bits(f.cells, map_level, F, own) <= point_map_tree_bits(f.cells, map_level, F, k) ? own : k);
            rank += total;
            out.push_back(std::move(f));
            r = e;
        }
        return out;
    }
    return out;  // not reached: at F = map_level every root is one cell
}

namespace {

uint64_t batches_bytes(uint64_t points, size_t per_packet, size_t record_bits) {
    if (points == 0) return 0;
    const uint64_t full = points / per_packet, rest = points % per_packet;
    const uint64_t packet = kPacketOverhead + 8;
    uint64_t bytes = full * (packet + (per_packet * record_bits + 7) / 8);
    if (rest > 0) bytes += packet + (rest * record_bits + 7) / 8;
    return bytes;
}

}  // namespace

PointMapChoice choose_point_map(const std::vector<QuantizedPoint>& points, const StreamInfo& info,
                                const ObjectInfo& object_in, double map_weight) {
    PointMapChoice choice;
    ObjectInfo object = object_in;
    object.map_level = 0;
    object.map_batch = 0;
    const size_t plain_per = points_per_packet(info.packet_size, info, object);
    choice.plain_bytes = batches_bytes(points.size(), plain_per, point_record_bits(info, object));
    if (points.empty() || points.size() > 0xFFFFFFFFull) return choice;
    double best = double(choice.plain_bytes);
    std::vector<uint64_t> codes(points.size());
    for (unsigned L = 1; L < info.position_bits; ++L) {
        object.map_level = uint8_t(L);
        for (size_t i = 0; i < points.size(); ++i) codes[i] = morton_cell(points[i].position, info.position_bits, L);
        std::sort(codes.begin(), codes.end());
        std::vector<MapCell> cells;
        for (size_t i = 0; i < codes.size(); ++i) {
            if (i > 0 && codes[i] == codes[i - 1])
                ++cells.back().count;
            else
                cells.push_back({codes[i], 1});
        }
        uint64_t map_bytes = 0;
        for (const PointMapFragment& f : plan_point_map(cells, L, info.packet_size))
            map_bytes += kPacketOverhead + kPointMapHeaderSize + (point_map_tree_bits(f.cells, L, f.root_level, f.rice) + 7) / 8;
        // An object smaller than a packet is one batch of its own size (the same ranks, spec 23.2,
        // and a repair symbol no longer than its one MAPPED_POINTS packet).
        const size_t per = std::min<size_t>({points_per_packet(info.packet_size, info, object), 0xFFFF, points.size()});
        if (per == 0) continue;
        const uint64_t point_bytes = batches_bytes(points.size(), per, point_record_bits(info, object));
        if (map_weight * double(map_bytes) + double(point_bytes) < best) {
            best = map_weight * double(map_bytes) + double(point_bytes);
            choice.level = uint8_t(L);
            choice.batch = uint16_t(per);
            choice.map_bytes = map_bytes;
            choice.point_bytes = point_bytes;
        }
    }
    return choice;
}

std::vector<uint32_t> mapped_order(const std::vector<QuantizedPoint>& points, unsigned position_bits, unsigned level,
                                   uint32_t batch) {
    const uint32_t n = uint32_t(points.size());
    std::vector<uint64_t> code(n);
    for (uint32_t i = 0; i < n; ++i) code[i] = morton_cell(points[i].position, position_bits, level);
    std::vector<uint32_t> by_rank(n);
    std::iota(by_rank.begin(), by_rank.end(), 0u);
    std::stable_sort(by_rank.begin(), by_rank.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
    std::vector<uint32_t> out(n);
    for (uint32_t i = 0; i < n; ++i) out[i] = by_rank[mapped_rank(i, n, batch)];
    return out;
}

}  // namespace ellicast
