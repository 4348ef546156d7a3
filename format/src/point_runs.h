// Runs of per-point records (JOINT_WEIGHTS, NORMALS): how a receiver compares and keeps them, and
// how the packetizer cuts an object's NORMALS entries into runs. Internal to the format library.
#pragma once

#include "ellicast/format.h"

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace ellicast::detail {

// The comparisons of a run of records for points first, first + 1, ... against those held (spec
// 21.2, 24.2, step 15): the index of the first point whose record differs from the one held (the
// run is then rejected whole), or none. `news` tells whether the run brings a record not held.
template <class Record>
std::optional<uint32_t> compare_run(const PagedRecords<Record>& held, uint32_t first, const std::vector<Record>& records,
                                    bool& news) {
    news = false;
    for (size_t i = 0; i < records.size(); ++i) {
        const uint32_t index = static_cast<uint32_t>(first + i);
        const Record* it = held.find(index);
        if (!it) news = true;
        else if (!(*it == records[i])) return index;
    }
    return std::nullopt;
}

// Keeps the records of points not held yet (the first copy of a record is kept).
template <class Record>
void keep_run(PagedRecords<Record>& held, uint32_t first, const std::vector<Record>& records) {
    for (size_t i = 0; i < records.size(); ++i) held.insert(static_cast<uint32_t>(first + i), &records[i]);
}

// The NORMALS payloads of one object's entries (one per point): runs of as many points as fit a
// packet of `packet_size` bytes. Empty when an entry cannot fit (not at 128 bytes and 16 bits).
// The TEXCOORDS payloads of one object's further sets (spec 30.1): set by set, runs of as many records
// as fit a packet of `packet_size` bytes. Empty when a set is not what spec 30.1 allows (a record per
// point, bits 4..16, a finite range with a finite end, at most 7 sets).
std::vector<std::vector<uint8_t>> texcoords_payloads(const std::vector<TexcoordSet>& sets, uint32_t point_count,
                                                     size_t packet_size);

std::vector<std::vector<uint8_t>> normals_payloads(const std::vector<NormalEntry>& entries, size_t packet_size,
                                                   unsigned normal_bits);

}  // namespace ellicast::detail
