// The trials of the robustness experiment: one loss trace and one tune-in slot per trial, applied
// to every scheme by slot position; reconstructions measured at chosen times after tune-in.
#include "ellicast/compare/experiment.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>

namespace ellicast::compare {

namespace {

uint64_t splitmix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

uint64_t mix(uint64_t a, uint64_t b) { return splitmix64(a ^ splitmix64(b)); }

// Tune-in moments (bytes since the senders started) are drawn from [0, kTuneInRange): a range so
// much longer than any scheme's period that the tune-in phase is uniform in every scheme's cycle.
constexpr uint64_t kTuneInRange = uint64_t(1) << 48;

// A scheme's schedule in time: where each transmission of one period starts, in bytes.
struct Timeline {
    std::vector<uint64_t> start;  // period + 1 entries; start[period] = bytes of one period
    uint64_t period_bytes() const { return start.back(); }
};

Timeline timeline(const Scheme& s) {
    Timeline t;
    t.start.push_back(0);
    for (uint64_t n = 0; n < s.period(); ++n) t.start.push_back(t.start.back() + s.packets()[s.packet_at(n)].size());
    return t;
}

struct Outcome {
    bool shown = false;
    size_t triangles = 0;
    Distance distance;
};

// What a scheme shows from a set of held packets, measured; remembered per outcome key.
class OutcomeCache {
public:
    Outcome get(const Scheme& scheme, const std::vector<uint32_t>& held, const MeasureFn& measure) {
        std::vector<uint32_t> key = scheme.outcome_key(held);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            auto it = cache_.find(key);
            if (it != cache_.end()) return it->second;
        }
        Outcome o;
        Mesh mesh;
        o.shown = scheme.reconstruct(held, mesh);
        if (o.shown) {
            o.triangles = mesh.triangles.size();
            o.distance = measure(mesh);
        } else {
            o.distance.holes = 100;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        cache_.emplace(std::move(key), o);
        return o;
    }

private:
    std::mutex mutex_;
    std::map<std::vector<uint32_t>, Outcome> cache_;
};

bool same(double a, double b) { return std::abs(a - b) < 1e-9; }

}  // namespace

double quantile(std::vector<double> values, double q) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }), values.end());
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    const double pos = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
    const size_t i = static_cast<size_t>(std::floor(pos));
    const double f = pos - double(i);
    if (i + 1 >= values.size()) return values.back();
    return values[i] * (1 - f) + values[i + 1] * f;
}

std::vector<double> ExperimentOptions::times_at(double loss) const {
    std::vector<double> t;
    const size_t steps = std::max<size_t>(1, steps_per_cycle);
    const size_t n = static_cast<size_t>(std::llround(std::max(1.0, horizon_at(loss)) * double(steps)));
    for (size_t i = 1; i <= n; ++i) t.push_back(double(i) / double(steps));
    return t;
}

ExperimentResult run_experiment(const std::vector<const Scheme*>& schemes, const MeasureFn& measure,
                                const TraceFn& trace, ExperimentOptions options) {
    if (schemes.empty()) throw CompareError("no scheme to compare");
    if (options.loss_rates.empty()) throw CompareError("no loss rate given");
    for (double p : options.loss_rates)
        if (!(p >= 0 && p < 1)) throw CompareError("loss rate " + std::to_string(p) + " is outside [0, 1)");
    if (options.bursts.empty()) options.bursts = {0};
    for (double b : options.bursts)
        if (!(b >= 0 && b <= 1e6)) throw CompareError("burst length " + std::to_string(b) + " is outside [0, 1e6]");
    if (options.trials == 0 || options.trials > 100000)
        throw CompareError("trial count " + std::to_string(options.trials) + " is outside [1, 100000]");
    if (options.curve_trials > options.trials)
        throw CompareError("curve trials (" + std::to_string(options.curve_trials) + ") exceed the trials (" +
                           std::to_string(options.trials) + ")");
    if (options.cycle_bytes == 0) throw CompareError("the channel cycle has no byte");
    if (options.slot_bytes == 0) throw CompareError("the loss trace's slots have no length");
    if (options.steps_per_cycle == 0 || options.steps_per_cycle > 1024)
        throw CompareError("grid steps per cycle " + std::to_string(options.steps_per_cycle) + " is outside [1, 1024]");
    for (double h : {options.horizon, options.long_horizon})
        if (!(h >= 1 && h <= 1000)) throw CompareError("horizon " + std::to_string(h) + " cycles is outside [1, 1000]");
    if (!(options.long_from >= 0 && options.long_from <= 1))
        throw CompareError("long-horizon loss " + std::to_string(options.long_from) + " is outside [0, 1]");
    if (double(options.cycle_bytes) * std::max(options.horizon, options.long_horizon) / double(options.slot_bytes) > 5e7)
        throw CompareError("the horizon spans more than 50 million slots");
    for (const Scheme* s : schemes)
        if (s == nullptr || s->packets().empty()) throw CompareError("a scheme sends no packet");
    const uint64_t cycle = options.cycle_bytes;
    const uint64_t slot_bytes = options.slot_bytes;
    std::vector<Timeline> timelines;
    for (const Scheme* s : schemes) timelines.push_back(timeline(*s));

    ExperimentResult result;
    result.options = options;
    for (const Scheme* s : schemes) {
        SchemeSummary summary;
        summary.name = s->name();
        summary.description = s->describe();
        summary.packets = s->packets().size();
        summary.period = s->period();
        summary.period_bytes = s->period_bytes();
        summary.few_outcomes = s->few_outcomes();
        for (const auto& p : s->packets()) summary.packet_bytes += p.size();
        for (uint64_t n = 0, at = 0; at < cycle; ++n) {
            const uint64_t size = s->packets()[s->packet_at(n)].size();
            summary.cycle_bytes += size;
            at += size;
        }
        std::vector<uint32_t> all(s->packets().size());
        for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
        Mesh mesh;
        if (s->reconstruct(all, mesh)) summary.complete = measure(mesh);
        result.schemes.push_back(summary);
    }

    struct Job {
        size_t burst, loss, trial;
        bool curve;
    };
    // Curve trials first: they cost the most, and starting them first keeps the threads busy to the end.
    std::vector<Job> jobs;
    for (int pass = 0; pass < 2; ++pass)
        for (size_t b = 0; b < options.bursts.size(); ++b)
            for (size_t l = 0; l < options.loss_rates.size(); ++l)
                for (size_t t = 0; t < options.trials; ++t)
                    if ((t < options.curve_trials) == (pass == 0)) jobs.push_back({b, l, t, pass == 0});
    constexpr double kCurveWeight = 50;  // progress units of a curve trial against an event-only one
    double total_weight = 0;
    for (const Job& j : jobs) total_weight += j.curve ? kCurveWeight : 1;

    std::vector<OutcomeCache> caches(schemes.size());
    std::vector<std::vector<TrialResult>> rows(jobs.size());
    std::vector<std::vector<TrialEvents>> events(jobs.size());
    std::atomic<size_t> next{0};
    double done_weight = 0;
    std::mutex progress_mutex;

    auto work = [&]() {
        for (size_t j = next++; j < jobs.size(); j = next++) {
            const Job& job = jobs[j];
            const double loss = options.loss_rates[job.loss], burst = options.bursts[job.burst];
            const uint64_t trial_seed = mix(mix(mix(options.seed, job.burst), job.loss), job.trial);
            const uint64_t tune_in = splitmix64(trial_seed ^ 0x7475AE1Eull) % kTuneInRange;
            const std::vector<double> grid = options.times_at(loss), none;
            const double horizon_cycles = options.horizon_at(loss);
            // Each time is counted from the end of the packet on the air at tune-in (lost to the
            // receiver, whatever the scheme): t cycles after tune-in = t * cycle + one slot.
            auto air = [&](double t) { return static_cast<uint64_t>(std::llround(t * double(cycle))) + slot_bytes; };
            const uint64_t horizon_bytes = air(horizon_cycles);
            const uint64_t horizon = horizon_bytes / slot_bytes + 1;
            const std::vector<bool> lost = trace(loss, burst, trial_seed, horizon);
            if (lost.size() < horizon) throw CompareError("the loss trace is shorter than asked");
            uint64_t lost_slots = 0;
            for (uint64_t k = 0; k < horizon; ++k) lost_slots += lost[k] ? 1 : 0;

            for (size_t s = 0; s < schemes.size(); ++s) {
                const Scheme& scheme = *schemes[s];
                const Timeline& line = timelines[s];
                const std::vector<double>& times = job.curve || scheme.few_outcomes() ? grid : none;
                const uint64_t period = scheme.period(), pbytes = line.period_bytes();
                // The first transmission that starts at or after the tune-in moment.
                uint64_t q = tune_in / pbytes;
                const uint64_t r = tune_in % pbytes;
                uint64_t n = static_cast<uint64_t>(std::lower_bound(line.start.begin(), line.start.end() - 1, r) -
                                                   line.start.begin());
                if (n == period) {
                    n = 0;
                    ++q;
                }
                TrialEvents ev;
                ev.scheme = s;
                ev.loss = loss;
                ev.burst = burst;
                ev.trial = job.trial;
                ev.tune_in = tune_in;
                ev.tune_in_phase = double(tune_in % cycle) / double(cycle);
                ev.trace_loss = double(lost_slots) / double(horizon);
                ev.horizon = horizon_cycles;
                bool shown = false, full = false;
                std::vector<bool> have(scheme.packets().size(), false);
                std::vector<uint32_t> held;  // ascending
                uint64_t bytes = 0;
                size_t next_time = 0;
                auto emit_until = [&](uint64_t end) {  // grid rows for the times before `end`
                    for (; next_time < times.size() && air(times[next_time]) < end; ++next_time) {
                        Outcome o = caches[s].get(scheme, held, measure);
                        TrialResult row;
                        row.scheme = s;
                        row.loss = loss;
                        row.burst = burst;
                        row.trial = job.trial;
                        row.time = times[next_time];
                        row.bytes_received = bytes;
                        row.distinct_packets = held.size();
                        row.distinct_fraction = double(held.size()) / double(scheme.packets().size());
                        row.data_fraction = scheme.data_fraction(held);
                        row.shown = o.shown;
                        row.triangles = o.triangles;
                        row.distance = o.distance;
                        rows[j].push_back(row);
                    }
                };
                for (;;) {
                    const uint64_t begin = q * pbytes + line.start[n] - tune_in;  // relative to tune-in
                    const uint64_t size = line.start[n + 1] - line.start[n];
                    const uint64_t end = begin + size;
                    if (end > horizon_bytes) break;  // not whole within the horizon
                    emit_until(end);
                    const uint32_t p = scheme.packet_at(q * period + n);
                    if (!lost[begin / slot_bytes]) {
                        bytes += size;
                        if (!have[p]) {
                            have[p] = true;
                            held.insert(std::upper_bound(held.begin(), held.end(), p), p);
                            // Seen at grid time t once end <= t * cycle + slot_bytes (see air()).
                            const double t = double(end > slot_bytes ? end - slot_bytes : 0) / double(cycle);
                            if (!shown && scheme.can_show(held)) {
                                shown = true;
                                ev.first_picture = t;
                            }
                            if (!full && scheme.complete(held)) {
                                full = true;
                                ev.full_quality = t;
                            }
                        }
                    }
                    if (++n == period) {
                        n = 0;
                        ++q;
                    }
                }
                emit_until(UINT64_MAX);
                ev.distinct_packets = held.size();
                events[j].push_back(ev);
            }
            if (options.progress) {
                std::lock_guard<std::mutex> lock(progress_mutex);
                done_weight += job.curve ? kCurveWeight : 1;
                options.progress(done_weight / total_weight);
            }
        }
    };
    const size_t threads = std::clamp<size_t>(options.threads, 1, 64);
    if (threads == 1) {
        work();
    } else {
        std::vector<std::thread> pool;
        std::exception_ptr failure;
        std::mutex failure_mutex;
        for (size_t i = 0; i < threads; ++i)
            pool.emplace_back([&]() {
                try {
                    work();
                } catch (...) {
                    std::lock_guard<std::mutex> lock(failure_mutex);
                    if (!failure) failure = std::current_exception();
                    next = jobs.size();
                }
            });
        for (auto& t : pool) t.join();
        if (failure) std::rethrow_exception(failure);
    }
    // In the fixed order: burst, loss, trial (then scheme and time inside each job).
    std::vector<size_t> order(jobs.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return std::tie(jobs[a].burst, jobs[a].loss, jobs[a].trial) < std::tie(jobs[b].burst, jobs[b].loss, jobs[b].trial);
    });
    for (size_t i : order) {
        result.trials.insert(result.trials.end(), rows[i].begin(), rows[i].end());
        result.events.insert(result.events.end(), events[i].begin(), events[i].end());
    }
    return result;
}

namespace {

struct CellValues {
    std::vector<double> rms, hausdorff, holes, error, bytes, fraction, data;
    size_t trials = 0, shown = 0;
    void add(const TrialResult& r) {
        ++trials;
        if (r.shown) {
            ++shown;
            rms.push_back(r.distance.rms);
            hausdorff.push_back(r.distance.hausdorff);
        }
        holes.push_back(r.shown ? r.distance.holes : 100.0);
        error.push_back(r.shown ? r.distance.rms : 100.0);
        bytes.push_back(double(r.bytes_received));
        fraction.push_back(r.distinct_fraction);
        data.push_back(r.data_fraction);
    }
    Cell cell() const {
        Cell c;
        c.trials = trials;
        if (trials == 0) return c;
        c.shown_share = double(shown) / double(trials);
        c.rms_median = quantile(rms, 0.5);
        c.rms_p25 = quantile(rms, 0.25);
        c.rms_p75 = quantile(rms, 0.75);
        c.hausdorff_median = quantile(hausdorff, 0.5);
        c.holes_median = quantile(holes, 0.5);
        c.holes_p25 = quantile(holes, 0.25);
        c.holes_p75 = quantile(holes, 0.75);
        c.error_median = quantile(error, 0.5);
        c.error_p90 = quantile(error, 0.9);
        c.bytes_median = quantile(bytes, 0.5);
        c.distinct_fraction_median = quantile(fraction, 0.5);
        c.data_fraction_median = quantile(data, 0.5);
        return c;
    }
};

}  // namespace

Cell summarize(const ExperimentResult& result, size_t scheme, double loss, double burst, double time) {
    CellValues v;
    for (const auto& r : result.trials)
        if (r.scheme == scheme && same(r.loss, loss) && same(r.burst, burst) && same(r.time, time)) v.add(r);
    return v.cell();
}

std::vector<Cell> summarize_curve(const ExperimentResult& result, size_t scheme, double loss, double burst) {
    const std::vector<double> times = result.options.times_at(loss);
    std::vector<CellValues> values(times.size());
    for (const auto& r : result.trials) {
        if (r.scheme != scheme || !same(r.loss, loss) || !same(r.burst, burst)) continue;
        const auto it = std::lower_bound(times.begin(), times.end(), r.time - 1e-9);
        if (it != times.end() && same(*it, r.time)) values[size_t(it - times.begin())].add(r);
    }
    std::vector<Cell> cells;
    for (const auto& v : values) cells.push_back(v.cell());
    return cells;
}

namespace {
constexpr double kNever = 1e300;  // a missed event, later than any time (finite, so that it interpolates)
}  // namespace

EventSummary summarize_events(const ExperimentResult& result, size_t scheme, double loss, double burst, bool full) {
    EventSummary e;
    std::vector<double> times;
    size_t never = 0;
    for (const auto& ev : result.events) {
        if (ev.scheme != scheme || !same(ev.loss, loss) || !same(ev.burst, burst)) continue;
        ++e.trials;
        const double t = full ? ev.full_quality : ev.first_picture;
        if (std::isnan(t)) ++never;
        times.push_back(std::isnan(t) ? kNever : t);
    }
    if (e.trials == 0) return e;
    e.never_share = double(never) / double(e.trials);
    auto q = [&](double p) {
        double v = quantile(times, p);
        return v > kNever / 1e100 ? std::numeric_limits<double>::quiet_NaN() : v;
    };
    // A quantile that interpolates towards a missed trial is "never".
    e.median = q(0.5);
    e.p90 = q(0.9);
    e.p99 = q(0.99);
    return e;
}

std::vector<double> times_to_errors(const ExperimentResult& result, size_t scheme, double loss, double burst,
                                    std::span<const double> levels) {
    const std::vector<double> times = result.options.times_at(loss);
    const std::vector<Cell> cells = summarize_curve(result, scheme, loss, burst);
    std::vector<double> reached(levels.size(), std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < times.size(); ++i) {
        if (cells[i].trials == 0) return std::vector<double>(levels.size(), std::numeric_limits<double>::quiet_NaN());
        for (size_t k = 0; k < levels.size(); ++k) {
            if (cells[i].error_median > levels[k]) reached[k] = std::numeric_limits<double>::quiet_NaN();
            else if (std::isnan(reached[k])) reached[k] = times[i];
        }
    }
    return reached;
}

double time_to_error(const ExperimentResult& result, size_t scheme, double loss, double burst, double level) {
    return times_to_errors(result, scheme, loss, burst, std::span<const double>(&level, 1))[0];
}

}  // namespace ellicast::compare
