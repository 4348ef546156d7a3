// Small bit tricks shared by the format and the codec.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ellicast {

// Bits set in w, by the parallel sum: the portable build has no POPCNT instruction, and
// std::popcount there becomes a call into libgcc several times slower.
inline size_t ones(uint64_t w) {
    w = w - ((w >> 1) & 0x5555555555555555ull);
    w = (w & 0x3333333333333333ull) + ((w >> 2) & 0x3333333333333333ull);
    w = (w + (w >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return size_t((w * 0x0101010101010101ull) >> 56);
}

}  // namespace ellicast
