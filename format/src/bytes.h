// Little-endian integers and LSB-first bit packing, private to the format library.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace ellicast::detail {

static_assert(sizeof(float) == 4, "IEEE-754 binary32 floats are required");

inline void put_u8(std::vector<uint8_t>& out, uint8_t v) { out.push_back(v); }
inline void put_u16(std::vector<uint8_t>& out, uint16_t v) {
    out.push_back(static_cast<uint8_t>(v));
    out.push_back(static_cast<uint8_t>(v >> 8));
}
inline void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
inline void put_f32(std::vector<uint8_t>& out, float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    put_u32(out, v);
}

inline uint16_t get_u16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint32_t get_u32(const uint8_t* p) {
    return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) | (static_cast<uint32_t>(p[2]) << 16) |
           (static_cast<uint32_t>(p[3]) << 24);
}
inline float get_f32(const uint8_t* p) {
    uint32_t v = get_u32(p);
    float f;
    std::memcpy(&f, &v, 4);
    return f;
}
inline void set_u32(uint8_t* p, uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

// Appends values of 1..32 bits, least significant bit first, into bytes (bit 0 of byte 0 first).
class BitWriter {
public:
    explicit BitWriter(std::vector<uint8_t>& out) : out_(out) {}
    void put(uint32_t value, int bits) {
        for (int i = 0; i < bits; ++i) {
            if (used_ == 0) out_.push_back(0);
            if ((value >> i) & 1u) out_.back() = static_cast<uint8_t>(out_.back() | (1u << used_));
            used_ = (used_ + 1) & 7;
        }
    }

private:
    std::vector<uint8_t>& out_;
    int used_ = 0;  // bits used in out_.back(); 0 means a new byte is needed
};

// Reads what BitWriter wrote. The caller checks the total size beforehand; reading past the end
// returns zero bits rather than touching memory outside the span.
class BitReader {
public:
    explicit BitReader(std::span<const uint8_t> in) : in_(in) {}
    // The next `bits` bits, LSB-first (a field of at most 32: the value keeps the first 32 of a longer
    // one); bits past the end read as 0 (and still count).
    uint32_t get(int bits) {
        if (bits <= 0) return 0;
        const int n = bits > 32 ? 32 : bits;
        // The (up to) five bytes holding them, gathered into one word: a field is at most 32 bits
        // and starts at most 7 bits into its first byte.
        const size_t first = pos_ >> 3;
        uint64_t word = 0;
        for (size_t k = 0; k < 5 && first + k < in_.size(); ++k) word |= uint64_t(in_[first + k]) << (8 * k);
        const uint64_t v = (word >> (pos_ & 7)) & ((uint64_t(1) << n) - 1);
        pos_ += size_t(bits);
        return uint32_t(v);
    }
    size_t position() const { return pos_; }           // bits read so far
    size_t size_bits() const { return in_.size() * 8; }
    bool exhausted() const { return pos_ > in_.size() * 8; }  // read past the end

private:
    std::span<const uint8_t> in_;
    size_t pos_ = 0;
};

}  // namespace ellicast::detail
