// Reed-Solomon erasure coding through Intel ISA-L: encode with the generator's parity rows,
// decode by inverting the k x k submatrix of the rows that arrived.
#include "ellicast/compare/erasure_code.h"

#include "ellicast/compare/compare_error.h"
#include "ellicast/converters/draco_mesh.h"

#include <isa-l/erasure_code.h>

#include <string>

namespace ellicast::compare {

ErasureCode::ErasureCode(int data_shards, int parity_shards) : k_(data_shards), m_(parity_shards) {
    if (k_ < 1 || m_ < 0 || k_ + m_ > kMaxErasureShards)
        throw CompareError("erasure code: " + std::to_string(k_) + " data + " + std::to_string(m_) +
                           " parity shards is not a valid code (need k >= 1, m >= 0, k + m <= 255)");
    matrix_.resize(size_t(k_ + m_) * k_);
    gf_gen_cauchy1_matrix(matrix_.data(), k_ + m_, k_);
}

std::vector<std::vector<uint8_t>> ErasureCode::encode(const std::vector<std::vector<uint8_t>>& data) const {
    if (data.size() != size_t(k_))
        throw CompareError("erasure code: expected " + std::to_string(k_) + " data shards, got " +
                           std::to_string(data.size()));
    const size_t len = data[0].size();
    for (const auto& d : data)
        if (d.size() != len) throw CompareError("erasure code: data shards of different lengths");
    std::vector<std::vector<uint8_t>> parity(m_, std::vector<uint8_t>(len));
    if (m_ == 0 || len == 0) return parity;
    std::vector<uint8_t> tables(size_t(32) * k_ * m_);
    ec_init_tables(k_, m_, const_cast<uint8_t*>(matrix_.data()) + size_t(k_) * k_, tables.data());
    std::vector<uint8_t*> in(k_), out(m_);
    for (int i = 0; i < k_; ++i) in[i] = const_cast<uint8_t*>(data[i].data());
    for (int i = 0; i < m_; ++i) out[i] = parity[i].data();
    ec_encode_data(static_cast<int>(len), k_, m_, tables.data(), in.data(), out.data());
    return parity;
}

bool ErasureCode::decode(const std::vector<std::vector<uint8_t>>& shards, std::vector<std::vector<uint8_t>>& data) const {
    data.clear();
    if (shards.size() != size_t(k_ + m_)) return false;
    // The first k shards that arrived, data shards first (they need no arithmetic).
    std::vector<int> rows;
    size_t len = 0;
    for (int i = 0; i < k_ + m_ && int(rows.size()) < k_; ++i) {
        if (shards[i].empty()) continue;
        if (!rows.empty() && shards[i].size() != len) return false;
        len = shards[i].size();
        rows.push_back(i);
    }
    if (int(rows.size()) < k_) return false;
    std::vector<int> missing;
    for (int i = 0; i < k_; ++i)
        if (shards[i].empty()) missing.push_back(i);
    data.resize(k_);
    for (int i = 0; i < k_; ++i)
        if (!shards[i].empty()) data[i] = shards[i];
    if (missing.empty()) return true;

    // B: the k x k rows of the generator that arrived; B^-1 maps them back to the data.
    std::vector<uint8_t> b(size_t(k_) * k_), inverse(size_t(k_) * k_);
    for (int r = 0; r < k_; ++r)
        for (int c = 0; c < k_; ++c) b[size_t(r) * k_ + c] = matrix_[size_t(rows[r]) * k_ + c];
    if (gf_invert_matrix(b.data(), inverse.data(), k_) != 0) {
        data.clear();
        return false;  // cannot happen for a Cauchy code; kept as a guard
    }
    const int lost = static_cast<int>(missing.size());
    std::vector<uint8_t> decode_rows(size_t(lost) * k_);
    for (int e = 0; e < lost; ++e)
        for (int c = 0; c < k_; ++c) decode_rows[size_t(e) * k_ + c] = inverse[size_t(missing[e]) * k_ + c];
    std::vector<uint8_t> tables(size_t(32) * k_ * lost);
    ec_init_tables(k_, lost, decode_rows.data(), tables.data());
    std::vector<uint8_t*> in(k_), out(lost);
    for (int r = 0; r < k_; ++r) in[r] = const_cast<uint8_t*>(shards[rows[r]].data());
    for (int e = 0; e < lost; ++e) {
        data[missing[e]].assign(len, 0);
        out[e] = data[missing[e]].data();
    }
    ec_encode_data(static_cast<int>(len), k_, lost, tables.data(), in.data(), out.data());
    return true;
}

}  // namespace ellicast::compare
