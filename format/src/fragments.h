// Internal to the format library: byte runs of a file that arrives in fragments at byte offsets
// (TEXTURE_FRAGMENT, spec 15.3; EXTRAS, spec 28.1), kept as disjoint runs keyed by their offset so
// that memory grows with what arrives, not with the size a fragment announces.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace ellicast::detail {

using ByteRuns = std::map<uint32_t, std::vector<uint8_t>>;

// The parts of [begin, end) that no run of `runs` holds, in order.
inline std::vector<std::pair<uint32_t, uint32_t>> missing_runs(const ByteRuns& runs, uint32_t begin, uint32_t end) {
    std::vector<std::pair<uint32_t, uint32_t>> gaps;
    uint32_t cursor = begin;
    auto run = runs.upper_bound(begin);
    if (run != runs.begin()) --run;
    for (; run != runs.end() && run->first < end; ++run) {
        const uint32_t run_end = static_cast<uint32_t>(run->first + run->second.size());
        if (run_end <= cursor) continue;
        if (run->first > cursor) gaps.emplace_back(cursor, run->first);
        cursor = std::max(cursor, run_end);
    }
    if (cursor < end) gaps.emplace_back(cursor, end);
    return gaps;
}

// The runs one after the other: the whole file, once every byte has arrived.
inline std::vector<uint8_t> join_runs(const ByteRuns& runs) {
    size_t size = 0;
    for (const auto& [offset, bytes] : runs) size += bytes.size();
    std::vector<uint8_t> out;
    out.reserve(size);
    for (const auto& [offset, bytes] : runs) out.insert(out.end(), bytes.begin(), bytes.end());
    return out;
}

}  // namespace ellicast::detail
