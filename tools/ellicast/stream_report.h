// What `ellicast inspect` shows and `ellicast validate` judges: a recorded stream (.ellc) read the way
// a decoder reads it (spec/format.md sections 10 and 11), with every conformance violation found on the
// way, each with its byte offset.
#pragma once

#include "ellicast/format.h"

#include <ellicast/auth.h>

#include <cstdint>
#include <map>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace ellicast::cli {

// One packet of the file as the decoder took it.
struct ReportPacket {
    uint64_t offset = 0;
    PacketHeader header;
    size_t size = 0;
    std::string result;  // accepted, duplicate, skipped, held, or the rejection reason
};

// A conformance violation. `offset` is absent for violations of the stream as a whole
// (for example: elements that never arrived).
struct Violation {
    std::optional<uint64_t> offset;
    std::string message;
    // Something the stream declares that did not arrive (a lossy recording lacks it) rather than
    // something wrong in what did: `validate --received` accepts a recording whose every violation
    // is of this kind.
    bool missing = false;
};

struct TypeCount {
    uint64_t packets = 0;
    uint64_t bytes = 0;
};

// "1.2" before "1.10": major, then minor, as numbers.
struct VersionOrder {
    bool operator()(const std::string& a, const std::string& b) const;
};

struct StreamReport {
    std::string path;
    uint64_t file_size = 0;
    Error container_error = Error::Ok;
    uint8_t container_version = 0;
    std::vector<ReportPacket> packets;
    std::vector<DamagedRegion> damaged;
    ReceivedStream stream;
    std::map<uint8_t, TypeCount> per_type;      // by packet type
    std::map<std::string, uint64_t, VersionOrder> versions;   // "1.0" -> packets, in version order
    std::map<uint32_t, uint64_t> stream_ids;    // every stream id seen in an intact packet
    uint64_t stream_info_parts = 0;             // STREAM_INFO packets taken (accepted or duplicate)
    // Repair packets (POINTS_REPAIR, CONNECTIVITY_REPAIR) that brought nothing because what they
    // protect was already whole: counted by the receiver as duplicates, reported as repair.
    uint64_t repair_not_needed = 0;
    std::vector<Violation> violations;
    // Signed streams (spec 16.4): the manifest's structure, and its signatures when a key was given.
    auth::SignedRecordingCheck signing;

    bool conforms() const { return violations.empty(); }
    // Every violation is missing data: a conforming stream that did not all arrive.
    bool only_missing() const {
        return std::all_of(violations.begin(), violations.end(), [](const Violation& v) { return v.missing; });
    }
};

// Reads and checks the container held in `bytes` (read from `path`, used in messages only). With
// `key`, the stream must be signed with it (every MANIFEST signature is checked).
StreamReport analyze_stream(const std::string& path, const std::vector<uint8_t>& bytes,
                            const auth::PublicKey* key = nullptr);

// Index ranges in [0, count) that are not keys of `received`: "0..9, 21..39" (at most `max_ranges`
// ranges, then "and N more ranges"). Empty when nothing is missing.
template <class Map>
std::string missing_ranges(const Map& received, uint64_t count, size_t max_ranges = 8);

// "12 bytes" style helpers shared by the two commands.
std::string hex32(uint32_t v);
std::string attribute_names(uint8_t attributes);

// ------------------------------------------------------------------------------------------------

template <class Map>
std::string missing_ranges(const Map& received, uint64_t count, size_t max_ranges) {
    std::string out;
    size_t ranges = 0, extra = 0;
    auto add = [&](uint64_t a, uint64_t b) {  // [a, b)
        if (a >= b) return;
        if (ranges == max_ranges) {
            ++extra;
            return;
        }
        if (!out.empty()) out += ", ";
        out += b - a == 1 ? std::to_string(a) : std::to_string(a) + ".." + std::to_string(b - 1);
        ++ranges;
    };
    uint64_t next = 0;
    for (const auto& entry : received) {
        uint64_t index = entry.first;
        if (index >= count) break;
        add(next, index);
        next = index + 1;
    }
    add(next, count);
    if (extra > 0) out += " and " + std::to_string(extra) + " more range" + (extra > 1 ? "s" : "");
    return out;
}

}  // namespace ellicast::cli
