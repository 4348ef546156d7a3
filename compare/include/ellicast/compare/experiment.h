// The robustness experiment: every scheme sends one model through the same channel at the same
// byte rate, its packets back to back, repeating its own schedule; a cycle is the same number of
// bytes for every scheme (ellicast's carousel cycle). Each trial draws one loss trace (in slots of
// one packet size of air time) and one tune-in moment, and applies them to every scheme by packet
// position in time: a packet is lost when the slot in which it starts is lost, so all schemes lose
// the very same stretches of time. At chosen times after tune-in each receiver rebuilds what it can
// from the distinct packets it holds, and the result is measured against the original.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/compare/schemes.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace ellicast::compare {

// How far a reconstruction is from the original, in percent of the original's bounding-box diagonal
// (the `ellicast diff` metric).
struct Distance {
    double rms = 0;        // RMS distance from the original's surface to the reconstruction (%)
    double rms_back = 0;   // RMS distance from the reconstruction to the original (%)
    double hausdorff = 0;  // symmetric Hausdorff distance (%)
    double holes = 0;      // fraction (%) of the original's surface farther than the hole threshold
};

// Measures a reconstruction against the original (the experiment does not know how).
using MeasureFn = std::function<Distance(const Mesh& reconstruction)>;

// Which slots a channel loses: lost[k] is true when slot k after tune-in is lost (a packet
// corrupted by bit errors counts as lost: its checksum rejects it). A slot is slot_bytes of air time.
using TraceFn = std::function<std::vector<bool>(double loss, double burst, uint64_t seed, uint64_t slots)>;

struct ExperimentOptions {
    std::vector<double> loss_rates{0, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7};
    // Mean burst lengths in slots (Gilbert-Elliott); 0 or 1: independent loss.
    std::vector<double> bursts{0};
    size_t trials = 20;
    uint64_t seed = 1;
    // Bytes per cycle of the channel (ellicast's carousel cycle); every scheme sends this many per cycle.
    uint64_t cycle_bytes = 0;
    // Air time of one slot of the loss trace, in bytes (the packet size).
    uint64_t slot_bytes = 1200;
    // Times after tune-in, in cycles, at which every loss rate of time_loss_rates is measured. Time t
    // is t * cycle_bytes + slot_bytes of air time after tune-in: the packet on the air when the
    // receiver tunes in is lost to it, so time 1 is one whole cycle after that packet.
    std::vector<double> times{0.25, 0.5, 0.75, 1, 1.5, 2, 3};
    // Loss rates at which every time is measured; at the others only one cycle is.
    std::vector<double> time_loss_rates{0.1, 0.3, 0.5};
    size_t threads = 1;
    // Progress (fraction 0..1 of the trials done). May be empty.
    std::function<void(double fraction)> progress;
};

// One scheme, at one loss setting, one trial, one time after tune-in.
struct TrialResult {
    size_t scheme = 0;            // index into the experiment's schemes
    double loss = 0;              // loss rate asked for
    double burst = 0;             // mean burst length (0: independent)
    size_t trial = 0;
    uint64_t tune_in = 0;         // moment the receiver tuned in, in bytes since the senders started
    double tune_in_phase = 0;     // tune_in modulo the channel cycle, in cycles
    double time = 0;              // cycles after tune-in
    uint64_t air_bytes = 0;       // bytes of air time after tune-in
    double trace_loss = 0;        // share of the trace's slots in that time that were lost
    uint64_t packets_received = 0;
    uint64_t bytes_received = 0;
    size_t distinct_packets = 0;  // distinct packets held
    double distinct_fraction = 0; // of the scheme's distinct packets
    double data_fraction = 0;     // Scheme::data_fraction of the packets held (ellicast: points received)
    bool shown = false;           // a surface can be shown
    size_t triangles = 0;         // of the surface shown
    Distance distance;            // meaningful when shown
};

struct SchemeSummary {
    std::string name;
    std::string description;
    size_t packets = 0;           // distinct packets
    uint64_t period = 0;          // packets after which its schedule repeats
    uint64_t period_bytes = 0;    // bytes of one period of its schedule
    uint64_t packet_bytes = 0;    // bytes of its distinct packets, once each
    uint64_t cycle_bytes = 0;     // bytes of the packets it starts sending within one channel cycle
    Distance complete;            // with every packet held
};

struct ExperimentResult {
    ExperimentOptions options;
    std::vector<SchemeSummary> schemes;
    std::vector<TrialResult> trials;  // in a fixed order: burst, loss, trial, scheme, time
};

// Runs every trial. Deterministic: the same schemes, options and seed give the same results,
// whatever the thread count. Throws CompareError on absurd options (no loss rate, a rate outside
// [0, 1), no trial, cycle_bytes or slot_bytes 0, a time <= 0).
ExperimentResult run_experiment(const std::vector<const Scheme*>& schemes, const MeasureFn& measure,
                                const TraceFn& trace, ExperimentOptions options);

// Quantile q (0..1, linear interpolation) of `values`; NaN when empty.
double quantile(std::vector<double> values, double q);

// A summary of the trials of one scheme at one setting and time.
struct Cell {
    size_t trials = 0;
    double shown_share = 0;                       // 0..1
    double rms_median = std::numeric_limits<double>::quiet_NaN(), rms_p25 = rms_median, rms_p75 = rms_median;  // over shown trials
    double hausdorff_median = std::numeric_limits<double>::quiet_NaN();                                       // over shown trials
    double holes_median = 100, holes_p25 = 100, holes_p75 = 100;  // over all trials, nothing shown = 100%
    double bytes_median = 0;
    double distinct_fraction_median = 0;
    double data_fraction_median = 0;
};

// The cell of `scheme` at (loss, burst, time), over the experiment's trials.
Cell summarize(const ExperimentResult& result, size_t scheme, double loss, double burst, double time);

}  // namespace ellicast::compare
