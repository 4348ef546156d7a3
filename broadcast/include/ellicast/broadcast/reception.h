// The receiving end of a broadcast, before any geometry: takes datagrams from anyone, keeps the
// ellicast packets of one stream (of the candidate streams it hears, the one that brings the most,
// spec/format.md section 11.4; with the sender's key, only packets a MANIFEST signed with it lists,
// section 16.3), counts and drops everything else, estimates the loss from sequence gaps, and says
// when the base (and everything) has arrived.
//
// Safe to expose to a network: every datagram goes through the format's checks (magic, length,
// CRC, stream id); what the candidate streams' objects hold is under one byte budget for all of them
// (spec 11.2: Limits::memory_base plus memory_per_byte times the bytes of the intact datagrams
// routed to candidates, each counted once); everything else is bounded by ReceivedStream's limits
// for each candidate stream (at most Options::max_candidates), the authenticator's limits with a
// key, and a fixed-size window of sequence numbers.
#pragma once

#include <ellicast/auth.h>
#include <ellicast/format.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
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
    // With a key (signed streams, spec 16.3): packets no verified MANIFEST lists, and MANIFESTs that
    // fail verification or are malformed; and packets held now for the MANIFEST that lists them.
    uint64_t unauthenticated = 0;
    uint64_t awaiting_manifest = 0;
    uint64_t rejected() const { return not_ellicast + damaged + oversized + other_stream + invalid + unauthenticated; }
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

// A receiver cannot tell a sender from a forger without a key, so it does not let the first packet
// decide: each stream id it hears, and each STREAM_INFO that contradicts the one a candidate holds
// for its stream id, starts a candidate stream of its own. When Options::max_candidates are held, a
// new one takes the place of the weakest candidate other than the one shown (the fewest packets
// accepted, then the longest since it accepted one), so that a few forged datagrams sent before the
// real stream cannot hold every place for good. Every packet goes to every candidate of its
// stream id. The stream shown and written is the candidate that has accepted the most packets (the
// first one on a tie): a real carousel repeats its stream info and base every cycle, so one early
// forged STREAM_INFO cannot lock it out (spec 11.4). A key is the only defence against a forger
// that sends more: with Options::key, every packet goes through an auth::Authenticator first and
// only packets a MANIFEST signed with that key lists reach the candidates (spec 16).
class Reception {
public:
    struct Options {
        ReceivedStream::Limits limits;      // for each candidate; memory_base and memory_per_byte for all together
        std::optional<uint32_t> stream_id;  // keep only this stream id; default: every one, as candidates
        size_t max_candidates = 4;          // memory is at most this many times the limits
        std::optional<auth::PublicKey> key;  // accept only the stream this key signs
        auth::Authenticator::Limits auth_limits;
    };
    Reception();
    explicit Reception(Options options);

    // Takes one datagram (`truncated`: it was larger than the receive buffer). Returns the error
    // the datagram was dropped for, or Ok.
    Error take(std::span<const uint8_t> datagram, bool truncated = false);

    // The chosen candidate (an empty stream before any valid packet).
    const ReceivedStream& stream() const;
    // Counters as seen from the chosen candidate: packets that went to other candidates count as
    // another stream's.
    ReceptionCounters counters() const;
    const LossEstimator& loss() const { return loss_; }

    // The candidates, in the order they started; which one is chosen (SIZE_MAX before any); and
    // which candidates took new content from the last datagram (bit i: candidate i).
    size_t candidate_count() const { return candidates_.size(); }
    const ReceivedStream& candidate(size_t i) const { return candidates_.at(i).stream; }
    size_t chosen() const { return chosen_; }
    uint64_t last_accepted_by() const { return last_accepted_by_; }
    // The candidates the last take() dropped to make room for a new one (bit i: candidate i; that
    // place now holds another stream), and a number that tells candidates apart over time (a
    // place reused by another candidate gets a new serial). Evictions so far, in all.
    uint64_t last_evicted() const { return last_evicted_; }
    uint64_t candidate_serial(size_t i) const { return candidates_.at(i).serial; }
    uint64_t evictions() const { return evictions_; }
    // With a key: the packets held for their MANIFEST that the last take() released and that brought
    // something new, each with the candidates that took it (as last_accepted_by()). Moved out.
    std::vector<std::pair<uint64_t, std::vector<uint8_t>>> take_released_accepted() {
        return std::exchange(released_accepted_, {});
    }
    // The byte budget every candidate shares (spec 11.2): what their objects hold together, the bytes
    // of intact datagrams routed to them, and the budget those make.
    const SharedMemoryBudget& memory() const { return *budget_; }
    // The signature filter, when Options::key was given.
    const auth::Authenticator* authenticator() const { return authenticator_ ? &*authenticator_ : nullptr; }

    // Every STREAM_INFO entry, every ellipsoid of every surface object, and (format 1.1) the
    // whole scene graph and every material have arrived: a receiver can show the base mesh.
    bool base_complete() const;
    // Everything the stream declares has arrived (every point, every texture): full quality.
    bool complete() const;
    // complete() for every candidate. Without a key, a receiver that heard more than one stream
    // waits for this: a small forged stream that completes first must not end the reception while
    // the real one, which may overtake it, is still arriving.
    bool every_candidate_complete() const;
    // Points received / declared over all objects (declared is 0 before the stream info).
    uint64_t points_received() const;
    uint64_t points_declared() const;
    uint64_t ellipsoids_received() const;
    uint64_t ellipsoids_declared() const;

private:
    struct Candidate {
        uint32_t stream_id = 0;
        ReceivedStream stream;
        uint64_t routed = 0;      // valid datagrams of its stream id
        uint64_t accepted = 0;    // of those, brought new content
        uint64_t duplicates = 0;  // of those, brought nothing new
        uint64_t invalid = 0;     // of those, rejected (a contradicting STREAM_INFO included)
        uint64_t serial = 0;      // the order in which candidates started
        uint64_t last_accepted_at = 0;  // valid datagrams seen when it last accepted new content
        Candidate(uint32_t id, const ReceivedStream::Limits& limits, uint64_t serial_number)
            : stream_id(id), stream(limits), serial(serial_number) {}
    };
    // Gives an intact packet to the candidates of its stream id (starting one if there is room).
    // nullopt when there was none and no room: the caller counts it as another stream's.
    std::optional<Error> route(const PacketView& view, uint64_t where);

    Options options_;
    std::optional<auth::Authenticator> authenticator_;
    std::vector<std::pair<uint64_t, std::vector<uint8_t>>> released_accepted_;
    std::vector<Candidate> candidates_;
    std::shared_ptr<SharedMemoryBudget> budget_;
    size_t chosen_ = SIZE_MAX;
    uint64_t last_accepted_by_ = 0;
    ReceptionCounters counters_;  // datagrams dropped before reaching any candidate
    uint64_t valid_ = 0;          // datagrams that reached a candidate
    uint64_t next_serial_ = 0;
    uint64_t last_evicted_ = 0;
    uint64_t evictions_ = 0;
    // A place for a new candidate: appended while there is room, else the place of the weakest
    // candidate but the chosen one. SIZE_MAX when none can be given.
    size_t place_for_new_candidate(uint32_t id);
    ReceivedStream empty_;
    LossEstimator loss_;
};

}  // namespace ellicast::broadcast
