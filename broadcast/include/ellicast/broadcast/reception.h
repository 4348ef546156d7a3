// The receiving end of a broadcast, before any geometry: takes datagrams from anyone, keeps the
// ellicast packets of one stream, counts and drops everything else, estimates the loss from
// sequence gaps, and says when the base (and everything) has arrived.
//
// Safe to expose to a network: every datagram goes through the format's checks (magic, length,
// CRC, stream id); memory is bounded by ReceivedStream's limits plus a fixed-size window of
// sequence numbers.
#pragma once

#include <ellicast/format.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace ellicast::broadcast {

struct ReceptionCounters {
    uint64_t datagrams = 0;      // every datagram seen
    uint64_t bytes = 0;
    uint64_t accepted = 0;       // brought new content
    uint64_t duplicates = 0;     // valid, nothing new (the carousel repeats the base)
    uint64_t not_ellicast = 0;   // too short or wrong magic: someone else's traffic
    uint64_t damaged = 0;        // bad checksum, truncated, trailing bytes
    uint64_t oversized = 0;      // larger than the format's largest packet
    uint64_t other_stream = 0;   // an ellicast packet of another stream id
    uint64_t invalid = 0;        // any other rejection (unsupported version, malformed payload, ...)
    uint64_t rejected() const { return not_ellicast + damaged + oversized + other_stream + invalid; }
};

// Estimates the loss from the sequence numbers the carousel stamps on each slot: the share of
// sequence numbers in [first seen, highest seen] that never arrived. Reordering within the
// window is tolerated; memory is a fixed bitmap of `window` sequence numbers.
class LossEstimator {
public:
    explicit LossEstimator(uint32_t window = 1u << 16);
    void add(uint32_t sequence);
    uint64_t expected() const;   // sequence numbers spanned so far
    uint64_t received() const { return received_; }  // distinct sequence numbers seen
    double loss() const;         // 0 when nothing is known yet

private:
    uint32_t window_;
    std::vector<uint64_t> bits_;
    bool started_ = false;
    uint64_t first_ = 0;      // first sequence seen, unwrapped
    uint64_t highest_ = 0;    // highest sequence seen, unwrapped
    uint64_t received_ = 0;
};

class Reception {
public:
    struct Options {
        ReceivedStream::Limits limits;
        std::optional<uint32_t> stream_id;  // keep only this stream; default: the first valid one
    };
    Reception();
    explicit Reception(Options options);

    // Takes one datagram (`truncated`: it was larger than the receive buffer). Returns the error
    // the datagram was dropped for, or Ok.
    Error take(std::span<const uint8_t> datagram, bool truncated = false);

    const ReceivedStream& stream() const { return stream_; }
    const ReceptionCounters& counters() const { return counters_; }
    const LossEstimator& loss() const { return loss_; }

    // Every STREAM_INFO entry, every ellipsoid of every surface object, and (format 1.1) the
    // whole scene graph and every material have arrived: a receiver can show the base mesh.
    bool base_complete() const;
    // Everything the stream declares has arrived (every point, every texture): full quality.
    bool complete() const;
    // Points received / declared over all objects (declared is 0 before the stream info).
    uint64_t points_received() const;
    uint64_t points_declared() const;
    uint64_t ellipsoids_received() const;
    uint64_t ellipsoids_declared() const;

private:
    Options options_;
    ReceivedStream stream_;
    ReceptionCounters counters_;
    LossEstimator loss_;
};

}  // namespace ellicast::broadcast
