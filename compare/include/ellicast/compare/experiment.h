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
#include <span>
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
    std::vector<double> bursts{0, 8, 32};
    // Trials per setting for the times to first picture and to full quality (cheap: no metric).
    size_t trials = 200;
    // Of those, the first `curve_trials` also measure the error on the time grid (each reconstruction
    // measured once per distinct outcome); schemes with few outcomes (Scheme::few_outcomes) are
    // measured on the grid in every trial. At most `trials`.
    size_t curve_trials = 3;
    uint64_t seed = 1;
    // Bytes per cycle of the channel (ellicast's carousel cycle); every scheme sends this many per cycle.
    uint64_t cycle_bytes = 0;
    // Air time of one slot of the loss trace, in bytes (the packet size).
    uint64_t slot_bytes = 1200;
    // The time grid: `steps_per_cycle` points per cycle, out to `horizon` cycles after tune-in at loss
    // rates below `long_from` and to `long_horizon` cycles at the others. Time t is t * cycle_bytes +
    // slot_bytes of air time after tune-in: the packet on the air when the receiver tunes in is lost
    // to it, so time 1 is one whole cycle after that packet. The events (first picture, full quality)
    // are timed to the packet within the same horizon.
    size_t steps_per_cycle = 16;
    double horizon = 4;
    double long_horizon = 8;
    double long_from = 0.4;
    size_t threads = 1;
    // Progress (fraction 0..1 of the trials done). May be empty.
    std::function<void(double fraction)> progress;

    // The horizon, in cycles, at loss rate `loss`.
    double horizon_at(double loss) const { return loss < long_from - 1e-9 ? horizon : long_horizon; }
    // The grid times (cycles after tune-in) at loss rate `loss`, ascending; 1 is always one of them.
    std::vector<double> times_at(double loss) const;
};

// One scheme, at one loss setting, one curve trial (any trial for a scheme with few outcomes), one
// time of the grid.
struct TrialResult {
    size_t scheme = 0;            // index into the experiment's schemes
    double loss = 0;              // loss rate asked for
    double burst = 0;             // mean burst length (0: independent)
    size_t trial = 0;
    double time = 0;              // cycles after tune-in
    uint64_t bytes_received = 0;
    size_t distinct_packets = 0;  // distinct packets held
    double distinct_fraction = 0; // of the scheme's distinct packets
    double data_fraction = 0;     // Scheme::data_fraction of the packets held (ellicast: points received)
    bool shown = false;           // a surface can be shown
    size_t triangles = 0;         // of the surface shown
    Distance distance;            // meaningful when shown
};

// The moments of one trial of one scheme: when its receiver first has a picture and when it reaches
// its full quality (Scheme::complete), in cycles after tune-in, to the packet that made it; NaN when
// it did not happen within the horizon.
struct TrialEvents {
    size_t scheme = 0;
    double loss = 0, burst = 0;
    size_t trial = 0;
    uint64_t tune_in = 0;         // moment the receiver tuned in, in bytes since the senders started
    double tune_in_phase = 0;     // tune_in modulo the channel cycle, in cycles
    double trace_loss = 0;        // share of the trace's slots lost within the horizon
    double horizon = 0;           // cycles simulated
    double first_picture = std::numeric_limits<double>::quiet_NaN();
    double full_quality = std::numeric_limits<double>::quiet_NaN();
    size_t distinct_packets = 0;  // held at the horizon
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
    bool few_outcomes = false;    // Scheme::few_outcomes: on the time grid in every trial
};

struct ExperimentResult {
    ExperimentOptions options;
    std::vector<SchemeSummary> schemes;
    std::vector<TrialResult> trials;   // curve trials, in a fixed order: burst, loss, trial, scheme, time
    std::vector<TrialEvents> events;   // every trial, in a fixed order: burst, loss, trial, scheme
};

// Runs every trial. Deterministic: the same schemes, options and seed give the same results,
// whatever the thread count. Throws CompareError on absurd options (no loss rate, a rate outside
// [0, 1), no trial, cycle_bytes or slot_bytes 0, no grid step or a horizon outside (0, 1000]).
ExperimentResult run_experiment(const std::vector<const Scheme*>& schemes, const MeasureFn& measure,
                                const TraceFn& trace, ExperimentOptions options);

// Quantile q (0..1, linear interpolation) of `values`; NaN when empty.
double quantile(std::vector<double> values, double q);

// A summary of the curve trials of one scheme at one setting and time.
struct Cell {
    size_t trials = 0;
    double shown_share = 0;                       // 0..1
    double rms_median = std::numeric_limits<double>::quiet_NaN(), rms_p25 = rms_median, rms_p75 = rms_median;  // over shown trials
    double hausdorff_median = std::numeric_limits<double>::quiet_NaN();                                       // over shown trials
    double holes_median = 100, holes_p25 = 100, holes_p75 = 100;  // over all trials, nothing shown = 100%
    // The error a viewer sees: RMS over all trials, a trial that shows nothing counting as 100% (the
    // whole diagonal): median and 90th percentile.
    double error_median = 100, error_p90 = 100;
    double bytes_median = 0;
    double distinct_fraction_median = 0;
    double data_fraction_median = 0;
};

// The cell of `scheme` at (loss, burst, time), over the experiment's curve trials.
Cell summarize(const ExperimentResult& result, size_t scheme, double loss, double burst, double time);

// The cells of `scheme` at (loss, burst) at every grid time of that loss rate (times_at), in one pass.
std::vector<Cell> summarize_curve(const ExperimentResult& result, size_t scheme, double loss, double burst);

// The distribution of one event time over the trials of one scheme at one setting.
struct EventSummary {
    size_t trials = 0;
    double never_share = 0;  // 0..1: did not happen within the horizon
    // Cycles after tune-in; a trial where it never happened counts as later than any, so a quantile
    // is NaN (shown as "never") when more trials than its rank missed it.
    double median = std::numeric_limits<double>::quiet_NaN(), p90 = median, p99 = median;
};

// First picture (`full` false) or full quality (`full` true) of `scheme` at (loss, burst).
EventSummary summarize_events(const ExperimentResult& result, size_t scheme, double loss, double burst, bool full);

// The first grid time at which the median error (Cell::error_median) of `scheme` at (loss, burst)
// is at most `level` percent and stays so until the horizon; NaN when it never gets there.
double time_to_error(const ExperimentResult& result, size_t scheme, double loss, double burst, double level);
// The same for several levels at once, from one pass over the curve.
std::vector<double> times_to_errors(const ExperimentResult& result, size_t scheme, double loss, double burst,
                                    std::span<const double> levels);

}  // namespace ellicast::compare
