// Repair packets (format 1.2, spec section 17): GF(2^8) arithmetic, the systematic Cauchy code over a
// block's source symbols, the POINTS_REPAIR payload, and the reference encoder's blocks.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <array>

namespace ellicast {

using namespace detail;

namespace {

// log / exp tables of GF(2^8) over 0x11D with generator 2 (2 is primitive for this polynomial).
struct Gf256Tables {
    std::array<uint8_t, 512> exp{};
    std::array<uint8_t, 256> log{};
    Gf256Tables() {
        unsigned x = 1;
        for (unsigned i = 0; i < 255; ++i) {
            exp[i] = static_cast<uint8_t>(x);
            log[x] = static_cast<uint8_t>(i);
            x <<= 1;
            if (x & 0x100) x ^= 0x11D;
        }
        for (unsigned i = 255; i < 512; ++i) exp[i] = exp[i - 255];
    }
};

const Gf256Tables& gf() {
    static const Gf256Tables tables;
    return tables;
}

// out[t] ^= c * in[t] for every t: through the 256 products of c, made once a call (a symbol is
// hundreds of bytes), one lookup a byte instead of two and a test.
void add_scaled(std::vector<uint8_t>& out, const std::vector<uint8_t>& in, uint8_t c) {
    if (c == 0) return;
    const Gf256Tables& g = gf();
    const unsigned lc = g.log[c];
    std::array<uint8_t, 256> product;
    product[0] = 0;
    for (unsigned x = 1; x < 256; ++x) product[x] = g.exp[g.log[x] + lc];
    const size_t n = std::min(out.size(), in.size());
    for (size_t t = 0; t < n; ++t) out[t] ^= product[in[t]];
}

void scale(std::vector<uint8_t>& v, uint8_t c) {
    const Gf256Tables& g = gf();
    const unsigned lc = g.log[c];
    for (uint8_t& b : v)
        if (b) b = g.exp[g.log[b] + lc];
}

}  // namespace

uint8_t gf256_mul(uint8_t a, uint8_t b) {
    if (a == 0 || b == 0) return 0;
    const Gf256Tables& g = gf();
    return g.exp[g.log[a] + g.log[b]];
}

uint8_t gf256_inv(uint8_t a) {
    if (a == 0) return 0;  // not defined; never asked for by the code (row XOR j != 0)
    const Gf256Tables& g = gf();
    return g.exp[255 - g.log[a]];
}

size_t repair_symbol_bytes(const RepairBlock& block, const StreamInfo& info, const ObjectInfo& object) {
    return (size_t{block.batch} * point_record_bits(info, object) + 7) / 8;
}

std::vector<uint8_t> encode_repair_payload(const RepairPacket& packet) {
    std::vector<uint8_t> out;
    out.reserve(kRepairHeaderSize + packet.symbol.size());
    put_u32(out, packet.block.first_index);
    put_u16(out, packet.block.batch);
    put_u8(out, packet.block.sources);
    put_u8(out, packet.row);
    out.insert(out.end(), packet.symbol.begin(), packet.symbol.end());
    return out;
}

Error decode_repair_payload(std::span<const uint8_t> payload, RepairPacket& out) {
    if (payload.size() < kRepairHeaderSize + 1) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    RepairPacket r;
    r.block.first_index = get_u32(p);
    r.block.batch = get_u16(p + 4);
    r.block.sources = p[6];
    r.row = p[7];
    if (r.block.batch == 0 || r.block.sources == 0) return Error::MalformedPayload;
    if (r.row < r.block.sources || r.row > kMaxRepairRow) return Error::MalformedPayload;
    if (uint64_t{r.block.first_index} + uint64_t(r.block.sources - 1) * r.block.batch > 0xFFFFFFFFull)
        return Error::MalformedPayload;
    r.block.point_count = static_cast<uint32_t>(
        std::min<uint64_t>(uint64_t(r.block.sources) * r.block.batch, 0x100000000ull - r.block.first_index));
    r.symbol.assign(payload.begin() + kRepairHeaderSize, payload.end());
    out = std::move(r);
    return Error::Ok;
}

std::vector<uint8_t> repair_source_symbol(const RepairBlock& block, std::span<const QuantizedPoint> batch_points,
                                          const StreamInfo& info, const ObjectInfo& object) {
    PointBatch batch;
    batch.points.assign(batch_points.begin(), batch_points.end());
    std::vector<uint8_t> payload = encode_points_payload(batch, info, object);
    std::vector<uint8_t> symbol(payload.begin() + 8, payload.end());  // the records, zero-padded
    symbol.resize(repair_symbol_bytes(block, info, object), 0);
    return symbol;
}

std::vector<uint8_t> repair_symbol(const std::vector<std::vector<uint8_t>>& sources, unsigned row) {
    std::vector<uint8_t> out(sources.empty() ? 0 : sources[0].size(), 0);
    for (size_t j = 0; j < sources.size(); ++j) add_scaled(out, sources[j], repair_coefficient(row, unsigned(j)));
    return out;
}

bool recover_source_symbols(std::vector<std::vector<uint8_t>>& sources, const std::vector<uint8_t>& rows,
                            const std::vector<std::vector<uint8_t>>& symbols) {
    std::vector<size_t> unknown;
    size_t length = 0;
    for (size_t j = 0; j < sources.size(); ++j) {
        if (sources[j].empty()) unknown.push_back(j);
        else length = sources[j].size();
    }
    const size_t u = unknown.size();
    if (u == 0) return true;
    if (rows.size() < u || symbols.size() < u) return false;
    if (length == 0) length = symbols[0].size();
    // y_a = R_{rows[a]} - sum over known j of C(rows[a], j) s_j; M[a][b] = C(rows[a], unknown[b]).
    std::vector<std::vector<uint8_t>> y(u), m(u, std::vector<uint8_t>(u));
    for (size_t a = 0; a < u; ++a) {
        y[a] = symbols[a];
        y[a].resize(length, 0);
        for (size_t j = 0; j < sources.size(); ++j)
            if (!sources[j].empty()) add_scaled(y[a], sources[j], repair_coefficient(rows[a], unsigned(j)));
        for (size_t b = 0; b < u; ++b) m[a][b] = repair_coefficient(rows[a], unsigned(unknown[b]));
    }
    // Gauss-Jordan elimination; a Cauchy matrix is invertible, so a pivot always exists.
    for (size_t col = 0; col < u; ++col) {
        size_t pivot = col;
        while (pivot < u && m[pivot][col] == 0) ++pivot;
        if (pivot == u) return false;
        std::swap(m[pivot], m[col]);
        std::swap(y[pivot], y[col]);
        const uint8_t inv = gf256_inv(m[col][col]);
        for (uint8_t& v : m[col]) v = gf256_mul(v, inv);
        scale(y[col], inv);
        for (size_t r = 0; r < u; ++r) {
            if (r == col || m[r][col] == 0) continue;
            const uint8_t f = m[r][col];
            for (size_t b = 0; b < u; ++b) m[r][b] ^= gf256_mul(f, m[col][b]);
            add_scaled(y[r], y[col], f);
        }
    }
    for (size_t b = 0; b < u; ++b) sources[unknown[b]] = std::move(y[b]);
    return true;
}

std::vector<RepairBlock> plan_repair_blocks(uint32_t point_count, uint16_t batch, size_t max_sources) {
    std::vector<RepairBlock> out;
    max_sources = std::min<size_t>(max_sources, kMaxRepairRow);
    if (point_count == 0 || batch == 0 || max_sources == 0) return out;
    // An object smaller than a packet: one batch of its points, so that the repair symbol is no
    // longer than the one POINTS packet it protects.
    if (point_count < batch) batch = uint16_t(point_count);
    const uint64_t batches = (uint64_t{point_count} + batch - 1) / batch;
    const uint64_t blocks = (batches + max_sources - 1) / max_sources;
    uint64_t next = 0;
    for (uint64_t b = 0; b < blocks; ++b) {
        const uint64_t end = batches * (b + 1) / blocks;  // batches [next, end)
        RepairBlock block;
        block.first_index = static_cast<uint32_t>(next * batch);
        block.batch = batch;
        block.sources = static_cast<uint8_t>(end - next);
        block.clip(point_count);
        out.push_back(block);
        next = end;
    }
    return out;
}

Error packetize_repairs(const StreamInfo& info, uint16_t object_id, const std::vector<QuantizedPoint>& points,
                        const std::vector<RepairBlock>& blocks, size_t repairs, uint32_t stream_id,
                        uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out) {
    if (object_id >= info.objects.size()) return Error::UnknownObject;
    const ObjectInfo& object = info.objects[object_id];
    uint32_t sequence = first_sequence;
    for (const RepairBlock& block : blocks) {
        const uint32_t k = block.source_count();
        if (k == 0 || k > kMaxRepairRow || uint64_t{block.first_index} + block.point_count > points.size())
            return Error::MalformedPayload;
        if (kPacketOverhead + kRepairHeaderSize + repair_symbol_bytes(block, info, object) > info.packet_size)
            return Error::MalformedPayload;
        std::vector<std::vector<uint8_t>> sources(k);
        for (uint32_t i = 0; i < k; ++i)
            sources[i] = repair_source_symbol(
                block, std::span<const QuantizedPoint>(points).subspan(block.first_index + size_t{i} * block.batch, block.batch_points(i)),
                info, object);
        for (unsigned row = k; row < k + repairs && row <= kMaxRepairRow; ++row) {
            RepairPacket packet;
            packet.block = block;
            packet.row = static_cast<uint8_t>(row);
            packet.symbol = repair_symbol(sources, row);
            out.push_back(write_packet(skippable_header(PacketType::PointsRepair, kRepairMinor, stream_id, sequence++,
                                                        object_id),
                                       encode_repair_payload(packet)));
        }
    }
    return Error::Ok;
}

Error check_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why) {
    return RepairPacketChecker(stream, false).check(packet, why);
}

Error RepairPacketChecker::check(const PacketView& packet, std::string& why) {
    RepairPacket repair;
    if (decode_repair_payload(packet.payload, repair) != Error::Ok) {
        why = "malformed POINTS_REPAIR payload";
        return Error::MalformedPayload;
    }
    const uint16_t id = packet.header.object_id;
    if (!stream_.info() || id >= stream_.objects().size() || !stream_.objects()[id].info) {
        why = "no stream info entry for object " + std::to_string(id);
        return Error::MalformedPayload;
    }
    const ReceivedObject& object = stream_.objects()[id];
    const ObjectInfo& oi = *object.info;
    RepairBlock& block = repair.block;
    if (!block.clip(oi.point_count) || repair.symbol.size() != repair_symbol_bytes(block, *stream_.info(), oi)) {
        why = "the block does not fit object " + std::to_string(id);
        return Error::MalformedPayload;
    }
    // A block other than the one the receiver holds at that index was rejected there (and reported).
    if (held_blocks_only_) {
        const auto held = object.repair_blocks.find(block.first_index);
        if (held == object.repair_blocks.end() || !held->second.block.same_block(block)) return Error::Ok;
    } else {
        blocks_.clear();  // one packet, any block: nothing to keep
    }
    auto [it, fresh] = blocks_.try_emplace({id, block.first_index});
    BlockState& state = it->second;
    if (fresh) {
        state.sources.resize(block.source_count());
        std::vector<QuantizedPoint> points;
        state.complete = true;
        for (uint32_t i = 0; i < block.source_count() && state.complete; ++i) {
            points.clear();
            const uint32_t first = block.first_index + i * block.batch;
            for (uint32_t n = 0; n < block.batch_points(i); ++n) {
                std::optional<QuantizedPoint> p = object.points.find(first + n);
                if (!p) {
                    state.complete = false;  // incomplete: nothing to compare
                    break;
                }
                points.push_back(*p);
            }
            if (state.complete) state.sources[i] = repair_source_symbol(block, points, *stream_.info(), oi);
        }
        if (!state.complete) state.sources.clear();
    }
    if (!state.complete) return Error::Ok;
    auto row = state.rows.find(repair.row);
    if (row == state.rows.end()) row = state.rows.emplace(repair.row, repair_symbol(state.sources, repair.row)).first;
    if (row->second != repair.symbol) {
        why = "row " + std::to_string(repair.row) + " of the block at point " + std::to_string(block.first_index) +
              " of object " + std::to_string(id) + " is not the repair symbol of the block's points";
        return Error::StreamMismatch;
    }
    return Error::Ok;
}

}  // namespace ellicast
