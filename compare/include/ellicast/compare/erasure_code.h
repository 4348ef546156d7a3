// A systematic Reed-Solomon erasure code over GF(2^8), from Intel ISA-L (Cauchy generator matrix):
// k data shards and m parity shards of one length; any k of the k + m shards give the data back.
#pragma once

#include <cstdint>
#include <vector>

namespace ellicast::compare {

inline constexpr int kMaxErasureShards = 255;  // k + m: GF(2^8) Cauchy matrices stay invertible up to here

class ErasureCode {
public:
    // A code of `data_shards` (k >= 1) and `parity_shards` (m >= 0) shards, k + m <= 255.
    // Throws CompareError otherwise.
    ErasureCode(int data_shards, int parity_shards);

    int data_shards() const { return k_; }
    int parity_shards() const { return m_; }

    // The m parity shards of `data` (exactly k shards, all of one length). Throws CompareError when
    // the shard count or lengths do not fit.
    std::vector<std::vector<uint8_t>> encode(const std::vector<std::vector<uint8_t>>& data) const;

    // Rebuilds the k data shards from the shards that arrived: `shards` has k + m entries in code
    // order (data first, then parity), an empty entry for each shard that was lost, all present
    // shards of one length. Returns false (and leaves `data` empty) when fewer than k arrived.
    bool decode(const std::vector<std::vector<uint8_t>>& shards, std::vector<std::vector<uint8_t>>& data) const;

private:
    int k_;
    int m_;
    std::vector<uint8_t> matrix_;  // (k + m) x k generator: identity on top, Cauchy rows below
};

}  // namespace ellicast::compare
