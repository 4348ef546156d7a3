// Channel simulation: what a lossy one-way channel does to a sequence of transmitted packets.
//
// A channel model (independent or Gilbert-Elliott bursty loss, reordering within a window,
// duplication, bit errors) and a seed produce a LossTrace: the fate of every transmission slot
// (delivered, lost, corrupted at given bits, duplicated, delayed). The trace is a value of its own:
// the same seed gives the same trace, it can be written to a file and read back, and it applies to
// ANY sequence of packets by slot position, so that several schemes (ellicast, Draco baselines)
// can see the very same losses. Slot 0 is the first packet sent after the receiver tuned in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace ellicast::broadcast {

struct ChannelModel {
    // Independent loss: each slot is lost with probability `loss`. Ignored when bursty.
    double loss = 0;

    // Gilbert-Elliott bursty loss: a two-state Markov chain stepped once per slot.
    bool bursty = false;
    double good_to_bad = 0;   // P(good -> bad) per slot
    double bad_to_good = 1;   // P(bad -> good) per slot; mean burst length 1 / bad_to_good
    double loss_good = 0;     // loss probability in the good state
    double loss_bad = 1;      // loss probability in the bad state

    // Reordering: each slot is held back with probability `reorder` by 1..reorder_window slots.
    double reorder = 0;
    uint32_t reorder_window = 0;

    // Duplication: each delivered slot arrives twice with probability `duplicate`.
    double duplicate = 0;

    // Bit errors: each bit of a delivered packet flips with probability `bit_error_rate`.
    // A receiver's CRC check turns a corrupted packet into a loss.
    double bit_error_rate = 0;

    uint64_t seed = 1;

    // The Gilbert model (loss 0 in good, 1 in bad) with mean loss `rate` and mean burst length
    // `burst` slots (>= 1).
    static ChannelModel gilbert(double rate, double burst, uint64_t seed);
    // Long-run loss rate (before bit errors) of the model.
    double mean_loss() const;
    // One line describing the model, for reports and trace files.
    std::string describe() const;
};

// Empty when the model is usable; otherwise what is wrong with it (a probability outside [0,1], ...).
std::string check_channel_model(const ChannelModel& model);

// What the channel did to one slot.
struct SlotFate {
    bool lost = false;
    bool duplicated = false;              // a second copy arrives right after the first
    uint32_t delay = 0;                   // slots by which the packet is held back
    std::vector<uint32_t> flipped_bits;   // bit positions (modulo the packet's bit length)
    bool corrupted() const { return !lost && !flipped_bits.empty(); }
    bool intact() const { return !lost && flipped_bits.empty(); }
};

inline constexpr uint64_t kMaxTraceSlots = 20'000'000;  // a hard cap on a trace's length

class LossTrace {
public:
    LossTrace() = default;
    // A trace of `slots` slots, all delivered intact.
    LossTrace(uint64_t slots, size_t packet_bytes, std::string description);

    uint64_t slots() const { return lost_.size(); }
    // The packet size the bit errors were drawn for.
    size_t packet_bytes() const { return packet_bytes_; }
    const std::string& description() const { return description_; }

    SlotFate fate(uint64_t slot) const;
    bool lost(uint64_t slot) const { return lost_[slot] != 0; }
    bool intact(uint64_t slot) const { return lost_[slot] == 0 && flips_.find(slot) == flips_.end(); }
    void set_fate(uint64_t slot, const SlotFate& fate);

    // Counts over the whole trace.
    uint64_t lost_count() const;
    uint64_t corrupted_count() const { return flips_.size(); }
    uint64_t duplicated_count() const;
    uint64_t delayed_count() const;

    // The trace restricted to slots [first, first + count) (clamped), renumbered from 0.
    LossTrace slice(uint64_t first, uint64_t count) const;

private:
    size_t packet_bytes_ = 0;
    std::string description_;
    std::vector<uint8_t> lost_;        // 1 = lost
    std::vector<uint8_t> duplicated_;  // 1 = duplicated
    std::vector<uint32_t> delay_;
    std::map<uint64_t, std::vector<uint32_t>> flips_;
};

// Draws the fate of `slots` slots. Each phenomenon has its own random stream derived from the seed,
// so that, e.g., turning on duplication does not change which slots are lost.
// Returns false with `error` for a bad model or more than kMaxTraceSlots slots.
bool generate_trace(const ChannelModel& model, uint64_t slots, size_t packet_bytes, LossTrace& out,
                    std::string& error);

// One packet as it comes out of the channel.
struct Arrival {
    uint64_t slot = 0;          // the slot it was sent in
    bool corrupted = false;     // bits were flipped
    bool duplicate = false;     // the second copy of a duplicated slot
};

// The order in which slots [0, count) arrive (count <= trace.slots()): lost slots are missing,
// delayed ones later, duplicated ones twice.
std::vector<Arrival> arrival_order(const LossTrace& trace, uint64_t count);

// Flips the trace's bits of `slot` in a copy of `packet` (bit k mod the packet's bit length;
// bit 0 is the least significant bit of byte 0).
std::vector<uint8_t> damage_packet(const LossTrace& trace, uint64_t slot, std::span<const uint8_t> packet);

// Applies the trace to `sent` (sent[k] went out in slot k; sent.size() <= trace.slots()): the
// packets in arrival order, corrupted where the trace says so.
std::vector<std::vector<uint8_t>> apply_trace(const LossTrace& trace, const std::vector<std::vector<uint8_t>>& sent);

// Text file: a header naming the format, the slot count, the packet size and the model, then one
// line per slot that was not delivered intact ("<slot> lost", "<slot> delay 3 dup flip 17,902").
// Reading checks every line and names the first bad one.
bool write_trace(const std::string& path, const LossTrace& trace, std::string& error);
bool read_trace(const std::string& path, LossTrace& out, std::string& error);

}  // namespace ellicast::broadcast
