// Baselines 2 and 3: the Draco file protected by a Reed-Solomon erasure code (Intel ISA-L). Each
// block of k data shards gets m parity shards; a block is recovered from any k of its k + m shards,
// and the file decodes once every block is recovered. draco-rs-repeat gives each block a little
// parity and repeats it; draco-mds fills each block to the 255 symbols GF(2^8) allows, so that a
// carousel sends distinct symbols for as long as possible.
#include "ellicast/compare/erasure_code.h"
#include "ellicast/compare/schemes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace ellicast::compare {

namespace {

// u32 file size, u16 block, u16 block count, u8 k, u8 m, u8 shard index, u8 zero
constexpr size_t kShardHeader = 12;

void put_u32(uint8_t* p, uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
uint32_t get_u32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// k_total data shards spread evenly over `count` blocks.
std::vector<size_t> spread(size_t k_total, size_t count) {
    std::vector<size_t> k(count);
    for (size_t b = 0; b < count; ++b) k[b] = k_total / count + (b < k_total % count ? 1 : 0);
    return k;
}

}  // namespace

DracoErasure::DracoErasure(const Mesh& mesh, const DracoSettings& settings, size_t packet_size,
                           const std::function<std::vector<Block>(size_t k_total)>& plan) {
    draco_ = draco_encode(mesh, settings);
    const size_t capacity = payload_capacity(packet_size);
    if (capacity <= kShardHeader) throw CompareError("packets too small for an erasure-code shard");
    shard_bytes_ = capacity - kShardHeader;
    const size_t k_total = std::max<size_t>(1, (draco_.size() + shard_bytes_ - 1) / shard_bytes_);
    blocks_ = plan(k_total);
    if (blocks_.empty() || blocks_.size() > 0xFFFF)
        throw CompareError("Draco file too large for the erasure code's block count");
    size_t next_data = 0;
    std::vector<std::vector<std::vector<uint8_t>>> block_shards(blocks_.size());
    for (size_t b = 0; b < blocks_.size(); ++b) {
        const size_t k = size_t(blocks_[b].data), m = size_t(blocks_[b].parity);
        std::vector<std::vector<uint8_t>> data(k, std::vector<uint8_t>(shard_bytes_, 0));
        for (size_t i = 0; i < k; ++i, ++next_data) {
            const size_t first = next_data * shard_bytes_;
            if (first < draco_.size())
                std::memcpy(data[i].data(), draco_.data() + first, std::min(shard_bytes_, draco_.size() - first));
        }
        ErasureCode code{int(k), int(m)};
        auto parity = code.encode(data);
        for (auto& p : parity) data.push_back(std::move(p));
        block_shards[b] = std::move(data);
    }
    if (next_data != k_total) throw CompareError("erasure-code blocks do not hold the Draco file");
    // Interleave: shard 0 of every block, then shard 1 of every block, ...
    size_t max_shards = 0;
    for (const auto& b : blocks_) max_shards = std::max<size_t>(max_shards, size_t(b.data + b.parity));
    uint32_t sequence = 0;
    const size_t block_count = blocks_.size();
    for (size_t s = 0; s < max_shards; ++s) {
        for (size_t b = 0; b < block_count; ++b) {
            if (s >= block_shards[b].size()) continue;
            std::vector<uint8_t> payload(kShardHeader + shard_bytes_);
            put_u32(payload.data(), static_cast<uint32_t>(draco_.size()));
            payload[4] = uint8_t(b);
            payload[5] = uint8_t(b >> 8);
            payload[6] = uint8_t(block_count);
            payload[7] = uint8_t(block_count >> 8);
            payload[8] = uint8_t(blocks_[b].data);
            payload[9] = uint8_t(blocks_[b].parity);
            payload[10] = uint8_t(s);
            payload[11] = 0;
            std::memcpy(payload.data() + kShardHeader, block_shards[b][s].data(), shard_bytes_);
            packets_.push_back(baseline_packet(kDracoShardType, sequence++, payload));
        }
    }
}

size_t DracoErasure::data_shards() const {
    size_t n = 0;
    for (const auto& b : blocks_) n += size_t(b.data);
    return n;
}

size_t DracoErasure::parity_shards() const {
    size_t n = 0;
    for (const auto& b : blocks_) n += size_t(b.parity);
    return n;
}

std::pair<int, int> DracoErasure::shard_of(uint32_t packet) const {
    auto payload = baseline_payload(packets_.at(packet), kDracoShardType);
    if (payload.size() < kShardHeader) return {-1, -1};
    return {int(payload[4] | payload[5] << 8), int(payload[10])};
}

std::string DracoErasure::layout() const {
    std::ostringstream s;
    s << data_shards() << " data + " << parity_shards() << " parity packets in " << blocks_.size() << " block"
      << (blocks_.size() == 1 ? "" : "s");
    return s.str();
}

bool DracoErasure::decodable(const std::vector<uint32_t>& held) const {
    std::vector<int> count(blocks_.size(), 0);
    std::vector<std::vector<bool>> seen(blocks_.size());
    for (size_t b = 0; b < blocks_.size(); ++b) seen[b].assign(size_t(blocks_[b].data + blocks_[b].parity), false);
    for (uint32_t index : held) {
        if (index >= packets_.size()) continue;
        auto [b, s] = shard_of(index);
        if (b < 0 || size_t(b) >= blocks_.size() || size_t(s) >= seen[size_t(b)].size() || seen[size_t(b)][size_t(s)]) continue;
        seen[size_t(b)][size_t(s)] = true;
        ++count[size_t(b)];
    }
    for (size_t b = 0; b < blocks_.size(); ++b)
        if (count[b] < blocks_[b].data) return false;
    return true;
}

std::vector<uint32_t> DracoErasure::outcome_key(const std::vector<uint32_t>& held) const {
    return {decodable(held) ? 1u : 0u};
}

bool DracoErasure::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
    out = Mesh{};
    // Gather shards by their headers, as a receiver would.
    std::vector<std::vector<std::vector<uint8_t>>> shards(blocks_.size());
    for (size_t b = 0; b < blocks_.size(); ++b) shards[b].resize(size_t(blocks_[b].data + blocks_[b].parity));
    size_t total = SIZE_MAX;
    for (uint32_t index : held) {
        if (index >= packets_.size()) continue;
        auto payload = baseline_payload(packets_[index], kDracoShardType);
        if (payload.size() <= kShardHeader) continue;
        const size_t b = payload[4] | payload[5] << 8, s = payload[10];
        if (b >= blocks_.size() || payload[8] != blocks_[b].data || payload[9] != blocks_[b].parity ||
            s >= shards[b].size())
            continue;
        total = get_u32(payload.data());
        shards[b][s].assign(payload.begin() + kShardHeader, payload.end());
    }
    if (total == SIZE_MAX) return false;
    std::vector<uint8_t> file;
    file.reserve(data_shards() * shard_bytes_);
    for (size_t b = 0; b < blocks_.size(); ++b) {
        ErasureCode code(blocks_[b].data, blocks_[b].parity);
        std::vector<std::vector<uint8_t>> data;
        if (!code.decode(shards[b], data)) return false;
        for (const auto& d : data) file.insert(file.end(), d.begin(), d.end());
    }
    if (total > file.size()) return false;
    file.resize(total);
    std::string error;
    return draco_decode(file, out, error) && !out.triangles.empty();
}

// ---------------------------------------------------------------------------------------------

DracoRsRepeat::DracoRsRepeat(const Mesh& mesh, const DracoSettings& settings, size_t packet_size, double redundancy)
    : DracoErasure(mesh, settings, packet_size,
                   [redundancy](size_t k_total) {
                       if (!(redundancy >= 0) || redundancy > 10)
                           throw CompareError("erasure-code redundancy " + std::to_string(redundancy) +
                                              " is outside [0, 10]");
                       // Blocks of at most 255 shards, data shards spread evenly over them.
                       const double per_block = std::max(1.0, std::floor(kMaxErasureShards / (1.0 + redundancy)));
                       const size_t count = size_t(std::ceil(double(k_total) / per_block));
                       std::vector<Block> blocks;
                       for (size_t k : spread(k_total, count)) {
                           size_t m = static_cast<size_t>(std::ceil(double(k) * redundancy - 1e-9));
                           m = std::min<size_t>(m, kMaxErasureShards - k);
                           blocks.push_back({int(k), int(m)});
                       }
                       return blocks;
                   }),
      redundancy_(redundancy) {}

std::string DracoRsRepeat::describe() const {
    std::ostringstream s;
    s << "Draco file of " << draco_.size() << " bytes as " << layout() << " (Reed-Solomon, ISA-L, redundancy "
      << redundancy_ << ") sent round robin; decodable from any k packets of each block";
    return s.str();
}

DracoMds::DracoMds(const Mesh& mesh, const DracoSettings& settings, size_t packet_size, int max_block_data)
    : DracoErasure(mesh, settings, packet_size,
                   [max_block_data](size_t k_total) {
                       if (max_block_data < 1 || max_block_data >= kMaxErasureShards)
                           throw CompareError("MDS block data count " + std::to_string(max_block_data) +
                                              " is outside [1, 254]");
                       const size_t count = (k_total + size_t(max_block_data) - 1) / size_t(max_block_data);
                       std::vector<Block> blocks;
                       for (size_t k : spread(k_total, count)) blocks.push_back({int(k), kMaxErasureShards - int(k)});
                       return blocks;
                   }),
      max_block_data_(max_block_data) {}

std::string DracoMds::describe() const {
    std::ostringstream s;
    s << "Draco file of " << draco_.size() << " bytes as " << layout()
      << " of 255 symbols (MDS Reed-Solomon, ISA-L, at most " << max_block_data_
      << " data per block), blocks interleaved, every symbol of a block sent before any again; decodable from any "
         "k packets of each block";
    return s.str();
}

}  // namespace ellicast::compare
