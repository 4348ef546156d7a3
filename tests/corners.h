// Triangles as quantized corner records, for comparing exact layers whatever the point indices:
// the tests of the exact layer (format 1.3) and of carried vertices (format 1.11).
#pragma once

#include "ellicast/format.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <tuple>

namespace ellicast::test {

using Corner = std::tuple<std::array<uint32_t, 3>, std::array<uint32_t, 2>, std::array<uint32_t, 2>, std::array<uint32_t, 4>>;
using CornerTriangle = std::array<Corner, 3>;

inline Corner corner_of(const QuantizedPoint& q) { return {q.position, q.normal, q.texcoord, q.color}; }

// A triangle up to rotation (its winding kept): the rotation that starts at its smallest corner.
inline CornerTriangle canonical(CornerTriangle t) {
    const size_t k = size_t(std::min_element(t.begin(), t.end()) - t.begin());
    std::rotate(t.begin(), t.begin() + long(k), t.end());
    return t;
}

}  // namespace ellicast::test
