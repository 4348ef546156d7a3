// Baseline 2: the Draco file protected by a Reed-Solomon erasure code (Intel ISA-L). Each block of
// k data shards gets m parity shards; a block is recovered from any k of its k + m shards, and the
// file decodes once every block is recovered.
#include "ellicast/compare/erasure_code.h"
#include "ellicast/compare/schemes.h"

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

}  // namespace

DracoFec::DracoFec(const Mesh& mesh, const DracoSettings& settings, size_t packet_size, double redundancy)
    : redundancy_(redundancy) {
    if (!(redundancy >= 0) || redundancy > 10)
        throw CompareError("erasure-code redundancy " + std::to_string(redundancy) + " is outside [0, 10]");
    draco_ = draco_encode(mesh, settings);
    const size_t capacity = payload_capacity(packet_size);
    shard_bytes_ = capacity - kShardHeader;
    const size_t k_total = std::max<size_t>(1, (draco_.size() + shard_bytes_ - 1) / shard_bytes_);
    // Blocks of at most 255 shards, data shards spread evenly over them.
    const double per_block_data = std::floor(kMaxErasureShards / (1.0 + redundancy));
    const size_t block_count =
        std::max<size_t>(1, static_cast<size_t>(std::ceil(double(k_total) / std::max(1.0, per_block_data))));
    if (block_count > 0xFFFF) throw CompareError("Draco file too large for the erasure code's block count");
    size_t next_data = 0;
    std::vector<std::vector<std::vector<uint8_t>>> block_shards(block_count);
    for (size_t b = 0; b < block_count; ++b) {
        const size_t k = k_total / block_count + (b < k_total % block_count ? 1 : 0);
        size_t m = static_cast<size_t>(std::ceil(double(k) * redundancy - 1e-9));
        m = std::min<size_t>(m, kMaxErasureShards - k);
        blocks_.push_back({int(k), int(m)});
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
    // Interleave: shard 0 of every block, then shard 1 of every block, ...
    size_t max_shards = 0;
    for (const auto& b : blocks_) max_shards = std::max<size_t>(max_shards, size_t(b.data + b.parity));
    uint32_t sequence = 0;
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

size_t DracoFec::data_shards() const {
    size_t n = 0;
    for (const auto& b : blocks_) n += size_t(b.data);
    return n;
}

size_t DracoFec::parity_shards() const {
    size_t n = 0;
    for (const auto& b : blocks_) n += size_t(b.parity);
    return n;
}

std::pair<int, int> DracoFec::shard_of(uint32_t packet) const {
    auto payload = baseline_payload(packets_.at(packet), kDracoShardType);
    if (payload.size() < kShardHeader) return {-1, -1};
    return {int(payload[4] | payload[5] << 8), int(payload[10])};
}

std::string DracoFec::describe() const {
    std::ostringstream s;
    s << "Draco file of " << draco_.size() << " bytes as " << data_shards() << " data + " << parity_shards()
      << " Reed-Solomon parity packets (ISA-L, " << blocks_.size() << " block" << (blocks_.size() == 1 ? "" : "s")
      << ", redundancy " << redundancy_ << ") sent round robin; decodable from any k packets of each block";
    return s.str();
}

bool DracoFec::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
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

}  // namespace ellicast::compare
