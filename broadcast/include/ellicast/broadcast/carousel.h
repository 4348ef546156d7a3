// The carousel: the order in which a sender repeats a stream's packets for receivers that tune in
// at any moment and never ask for anything.
//
// After Bischoff & Kobbelt (spec/format.md section 12, Sender behaviour): the base (what a receiver
// needs before it can show anything: STREAM_INFO, ELLIPSOIDS, SCENE, MATERIAL, MATERIAL_EXTENSIONS,
// SKIN, and every type is_base_packet does not call detail) is repeated between chunks of detail
// packets (POINTS or MAPPED_POINTS, TEXTURE_FRAGMENT, ANIMATION, MORPH_ANIMATION, JOINT_WEIGHTS,
// MORPH_DELTAS, NORMALS, CONNECTIVITY, CONNECTIVITY_REPAIR), b d1 b d2 ... b dn, and the whole cycle
// repeats. POINT_MAP packets are spread over the repetitions of the base (section 23.7), a repair
// block's POINTS_REPAIR packets take turns with its POINTS packets (17.5), and a MANIFEST part goes
// with the packets it lists (16.4). A receiver that tunes in anywhere holds a complete base after at most one chunk plus one
// base (without loss; counted from the first whole packet received), and every packet after at
// most one cycle. Inside each chunk the stream info comes again every few POINTS packets
// (CarouselOptions::stream_info_every), since a receiver can show nothing without it.
//
// The same carousel drives the schedule file, the channel simulator and the UDP sender: slot k of a
// transmission is cycle entry k mod cycle length, with its sequence number restamped to k so that a
// receiver can estimate its loss from gaps.
#pragma once

#include <ellicast/format.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast::broadcast {

// True for a packet a receiver needs before it can show anything: every type but POINTS and
// TEXTURE_FRAGMENT (detail, sent once per cycle rather than with every repetition of the base).
bool is_base_packet(const PacketHeader& header);

struct CarouselOptions {
    // POINTS packets per chunk (between two repetitions of the base); 0: derived from base_share.
    size_t chunk_packets = 0;
    // Wanted share of the cycle's bytes spent on the base (0 < share < 1), used when chunk_packets
    // is 0. The chunk count is rounded, so the achieved share is close to, not exactly, this.
    double base_share = 0.15;
    // With base_share: at least this many repetitions of the base per cycle (fewer only when there
    // are fewer POINTS packets). A small model's base is a few hundred bytes; repeated only twice,
    // its STREAM_INFO is lost in both copies at 30% loss one cycle in eleven.
    size_t min_base_repetitions = 4;
    // Inside each chunk, a STREAM_INFO part again after every this many POINTS packets (the parts in
    // turn when the stream info has several), and (format 1.7) when the map is no larger than the
    // rest of the base, its next POINT_MAP fragment in turn with it; 0: only with the base. A receiver needs the stream
    // info and one ELLIPSOIDS packet to show anything: with the base alone, the bunny's 100-byte
    // stream info came 9 times a cycle, and at 50% loss a quarter of receivers still had none a
    // quarter of a cycle after tuning in. Every 8 packets costs about 1% of the cycle.
    size_t stream_info_every = 8;
    // Restamp each transmitted packet's sequence number with its slot number (and its CRC).
    bool restamp_sequence = true;
    // Repair packets (format 1.2) sent per POINTS packet of a block: the first ceil(ratio * k) rows
    // of those the stream holds. Negative: every one it holds. 0: none (the POINTS packets repeat).
    double repair_ratio = -1;
    // Format 1.7 (spec 23): the POINT_MAP packets go this many times a cycle, the fragments in turn,
    // spread over the repetitions of the base (each carries its share). A receiver needs the map to
    // place points but not to show the base: sent whole with every base, the bunny's map (8 packets
    // at level 6) would make the base more than twice as large and the first picture half as frequent.
    // At 50% loss on the bunny, 2 rounds left the last points for 3.88 cycles (p90), 3 for 3.22, 4
    // for 2.37 (bench_full_quality), 6 for 2.43 with a cycle 11% longer. A map no larger than the
    // rest of the base goes whole with every repetition instead (a small object's one fragment: sent
    // only four times a cycle, at 60% loss the trefoil's receiver of one cycle placed none of its points).
    size_t map_rounds = 4;
};

// One slot of the cycle: which input packet is sent there.
struct CarouselEntry {
    uint32_t packet = 0;  // index into the packet list the carousel was built from
    bool base = false;
    bool stream_info_repeat = false;  // a STREAM_INFO part inside a chunk, or the MANIFEST part after it (base is true too)
    uint32_t chunk = 0;   // chunk index (0..chunk_count-1) of the base repetition or data chunk
};

// A repair block (spec 17) as the carousel sends it: its source POINTS packets and its
// POINTS_REPAIR packets; a receiver holds every point of it once it holds any `needed` of them.
struct CarouselBlock {
    std::vector<uint32_t> symbols;  // input indices: the sources (in stream order), then the repairs (by row)
    size_t sources = 0;             // how many of `symbols` are POINTS packets
    size_t needed = 0;              // k: the block's source count
};

struct Carousel {
    std::vector<uint32_t> base;      // input indices of the base packets, in input order
    std::vector<uint32_t> stream_info;  // input indices of the STREAM_INFO parts (also in `base`)
    std::vector<uint32_t> data;      // input indices of the POINTS packets, in input order
    std::vector<uint32_t> maps;      // format 1.7: input indices of the POINT_MAP packets, in input order
    // Signed streams: input indices of the MANIFEST parts that list only detail packets; each goes
    // just before the first packet it lists and again half-way through them (its bytes count in
    // repeat_bytes). MANIFEST parts that list base packets are in `base`.
    std::vector<uint32_t> detail_manifests;
    // Repair (format 1.2): the blocks, and the input indices of the POINTS_REPAIR packets scheduled.
    // A block's data slots carry its sources and repairs in turn, so the schedule repeats only after
    // `period_cycles` cycles; `cycle` and `cycle_bytes` are that whole period.
    std::vector<CarouselBlock> blocks;
    std::vector<uint32_t> repairs;
    size_t period_cycles = 1;
    std::vector<uint32_t> sizes;     // byte size of every input packet
    size_t chunk_packets = 0;        // POINTS packets per chunk (the last chunk may hold fewer)
    size_t chunk_count = 0;          // n: number of base repetitions per cycle
    std::vector<CarouselEntry> cycle;
    std::vector<uint64_t> cycle_offsets;  // bytes of the cycle before each entry (size: cycle + 1)
    bool restamp_sequence = true;

    uint64_t base_bytes = 0;         // B: one copy of the base
    uint64_t map_bytes = 0;          // every POINT_MAP packet once (sent a slice with each base)
    uint64_t data_bytes = 0;         // D: every POINTS packet once
    uint64_t repeat_bytes = 0;       // R: the STREAM_INFO parts (and detail MANIFEST parts) sent inside chunks
    uint64_t cycle_bytes = 0;        // n * B + D + R, times period_cycles
    // Bytes of one cycle (b d1 .. b dn) on average over the period: the unit of "cycles after tune-in".
    double bytes_per_cycle() const { return double(cycle_bytes) / double(period_cycles ? period_cycles : 1); }
    // Slots of one cycle, on average over the period.
    double slots_per_cycle() const { return double(cycle.size()) / double(period_cycles ? period_cycles : 1); }
    uint64_t max_chunk_bytes = 0;    // the largest chunk

    // Input index of the packet sent in slot `slot` (slot 0 is the first packet the sender sends).
    uint32_t packet_at(uint64_t slot) const { return cycle[slot % cycle.size()].packet; }
    // Bytes sent before slot `slot` starts.
    uint64_t bytes_before(uint64_t slot) const;
};

// Figures of a carousel, without loss unless stated.
struct CarouselStats {
    size_t base_packets = 0;
    size_t data_packets = 0;
    size_t cycle_packets = 0;
    uint64_t base_bytes = 0;
    uint64_t data_bytes = 0;
    uint64_t cycle_bytes = 0;
    // Extra bytes spent on repeating the base, relative to sending the stream once:
    // (n - 1) B / (B + D). The paper reports about 15%.
    double repetition_overhead = 0;
    // Share of the cycle's bytes that are base: n B / (n B + D).
    double base_share = 0;
    // Worst case, over every tune-in moment, of the bytes that go by until a complete base has
    // been received: one chunk plus one base plus the packet cut by the tune-in (tuning in just
    // after the base's largest packet started: the rest of the base, a chunk, the base again up
    // to that packet), B + max chunk + max base packet.
    uint64_t worst_base_wait_bytes = 0;
    // Same until every packet has been received (full quality).
    uint64_t worst_full_wait_bytes = 0;
    // Mean over uniformly random tune-in moments, without loss.
    double mean_base_wait_bytes = 0;
    double mean_full_wait_bytes = 0;
};

// Builds the carousel of `packets` (each one whole valid packet, e.g. from a container). Every
// packet must parse; `error` names the first that does not, or an absurd option.
bool build_carousel(const std::vector<std::vector<uint8_t>>& packets, const CarouselOptions& options,
                    Carousel& out, std::string& error);

// The bytes sent in slot `slot`: the scheduled packet, its sequence number restamped to the slot
// (modulo 2^32) when the carousel says so.
std::vector<uint8_t> carousel_packet(const Carousel& carousel, const std::vector<std::vector<uint8_t>>& packets,
                                     uint64_t slot);

// The no-loss figures above (exact: every tune-in moment of a cycle is examined).
CarouselStats carousel_stats(const Carousel& carousel);

// Which packets a receiver waits for.
enum class WaitFor { Base, Everything };

// Expected bytes that go by from a uniformly random tune-in moment until every packet of `what`
// has been received at least once, when each transmitted packet is lost independently with
// probability `loss` (0 <= loss < 1). Exact for the schedule (not an approximation of it), averaged
// over `tune_in_samples` tune-in moments spread evenly over the cycle (0: every slot). With
// `at_slot_start`, the receiver tunes in exactly as a slot starts (it gets that slot; each slot is
// equally likely), as when a sender starts at a random slot; otherwise at a uniformly random moment
// in time (the slot being sent is lost to it).
double expected_wait_bytes(const Carousel& carousel, WaitFor what, double loss, size_t tune_in_samples = 0,
                           bool at_slot_start = false);

// Slot (counted from `first_slot`, the slot at which the receiver tuned in) after which the packets
// of `what` have all been received, given `received[k]` = whether slot first_slot + k arrived
// intact; -1 when that never happens within received.size() slots.
int64_t completion_slot(const Carousel& carousel, WaitFor what, uint64_t first_slot, const std::vector<bool>& received);

}  // namespace ellicast::broadcast
