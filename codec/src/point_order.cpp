// The order in which surface points are sent: coarse to fine over an octree of the quantized
// positions. Level L keeps one point per occupied cell of edge 2^(bits-L) that holds no point of an
// earlier level, so every prefix of the stream covers the surface evenly; within a level the points
// are in a seeded random order, so any subset of packets (each a run of consecutive points) is an
// even random sample of that level rather than one region.
#include "encoder_internal.h"

#include "ellicast/format/key_set.h"

#include <algorithm>
#include <numeric>

namespace ellicast::detail {

std::vector<uint32_t> spread_order(const std::vector<std::array<uint32_t, 3>>& positions, int bits, uint32_t seed) {
    const size_t n = positions.size();
    std::vector<uint32_t> shuffled(n);
    std::iota(shuffled.begin(), shuffled.end(), 0u);
    Random rng(seed ^ 0x9E3779B9u);
    for (size_t i = n; i > 1; --i) std::swap(shuffled[i - 1], shuffled[rng.below(uint32_t(i))]);

    std::vector<uint32_t> order;
    order.reserve(n);
    std::vector<bool> taken(n, false);
    KeySet occupied;  // a level's cells (keys below 2^63)
    for (int level = 1; level <= bits && order.size() < n; ++level) {
        const int shift = bits - level;
        auto key = [&](uint32_t i) {
            const auto& p = positions[i];
            return (uint64_t(p[0] >> shift) << 42) | (uint64_t(p[1] >> shift) << 21) | uint64_t(p[2] >> shift);
        };
        occupied.clear();  // membership only: the order does not depend on it
        for (uint32_t i : order) occupied.insert(key(i));
        for (uint32_t i : shuffled)
            if (!taken[i] && occupied.insert(key(i))) {
                taken[i] = true;
                order.push_back(i);
            }
    }
    for (uint32_t i : shuffled)
        if (!taken[i]) order.push_back(i);  // same cell at full depth: only for duplicate positions
    return order;
}

}  // namespace ellicast::detail
