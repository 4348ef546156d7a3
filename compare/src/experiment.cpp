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
    double data_fraction = 0;
    Distance distance;
};

// What a scheme shows from a set of held packets, measured; remembered per distinct set.
class OutcomeCache {
public:
    Outcome get(const Scheme& scheme, const std::vector<uint32_t>& held, const MeasureFn& measure) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            auto it = cache_.find(held);
            if (it != cache_.end()) return it->second;
        }
        Outcome o;
        Mesh mesh;
        o.shown = scheme.reconstruct(held, mesh);
        o.data_fraction = scheme.data_fraction(held);
        if (o.shown) {
            o.triangles = mesh.triangles.size();
            o.distance = measure(mesh);
        } else {
            o.distance.holes = 100;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        cache_.emplace(held, o);
        return o;
    }

private:
    std::mutex mutex_;
    std::map<std::vector<uint32_t>, Outcome> cache_;
};

bool contains(const std::vector<double>& values, double v) {
    for (double x : values)
        if (std::abs(x - v) < 1e-9) return true;
    return false;
}

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
    if (options.cycle_bytes == 0) throw CompareError("the channel cycle has no byte");
    if (options.slot_bytes == 0) throw CompareError("the loss trace's slots have no length");
    if (options.times.empty()) throw CompareError("no time after tune-in to measure at");
    for (double t : options.times)
        if (!(t > 0 && t <= 1000)) throw CompareError("time " + std::to_string(t) + " cycles is outside (0, 1000]");
    if (!contains(options.times, 1.0)) options.times.push_back(1.0);
    std::sort(options.times.begin(), options.times.end());
    options.times.erase(std::unique(options.times.begin(), options.times.end()), options.times.end());
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
    };
    std::vector<Job> jobs;
    for (size_t b = 0; b < options.bursts.size(); ++b)
        for (size_t l = 0; l < options.loss_rates.size(); ++l)
            for (size_t t = 0; t < options.trials; ++t) jobs.push_back({b, l, t});

    std::vector<OutcomeCache> caches(schemes.size());
    std::vector<std::vector<TrialResult>> rows(jobs.size());
    std::atomic<size_t> next{0}, done{0};
    std::mutex progress_mutex;

    auto work = [&]() {
        for (size_t j = next++; j < jobs.size(); j = next++) {
            const Job& job = jobs[j];
            const double loss = options.loss_rates[job.loss], burst = options.bursts[job.burst];
            const uint64_t trial_seed = mix(mix(mix(options.seed, job.burst), job.loss), job.trial);
            const uint64_t tune_in = splitmix64(trial_seed ^ 0x7475AE1Eull) % kTuneInRange;
            std::vector<double> times;
            for (double t : options.times)
                if (t == 1.0 || contains(options.time_loss_rates, loss)) times.push_back(t);
            // Each time is counted from the end of the packet on the air at tune-in (lost to the
            // receiver, whatever the scheme): t cycles after tune-in = t * cycle + one slot.
            const uint64_t horizon_bytes = static_cast<uint64_t>(std::llround(times.back() * double(cycle))) + slot_bytes;
            const uint64_t horizon = horizon_bytes / slot_bytes + 1;
            const std::vector<bool> lost = trace(loss, burst, trial_seed, horizon);
            if (lost.size() < horizon) throw CompareError("the loss trace is shorter than asked");
            std::vector<uint64_t> lost_before(horizon + 1, 0);  // lost slots among the first k
            for (uint64_t k = 0; k < horizon; ++k) lost_before[k + 1] = lost_before[k] + (lost[k] ? 1 : 0);

            for (size_t s = 0; s < schemes.size(); ++s) {
                const Scheme& scheme = *schemes[s];
                const Timeline& line = timelines[s];
                const uint64_t period = scheme.period(), pbytes = line.period_bytes();
                // The first transmission that starts at or after the tune-in moment.
                uint64_t q = tune_in / pbytes, n = 0;
                const uint64_t r = tune_in % pbytes;
                n = static_cast<uint64_t>(std::lower_bound(line.start.begin(), line.start.end() - 1, r) - line.start.begin());
                if (n == period) {
                    n = 0;
                    ++q;
                }
                std::vector<bool> have(scheme.packets().size(), false);
                size_t distinct = 0;
                uint64_t received = 0, bytes = 0;
                for (double t : times) {
                    const uint64_t until = static_cast<uint64_t>(std::llround(t * double(cycle))) + slot_bytes;
                    for (;;) {
                        const uint64_t begin = q * pbytes + line.start[n] - tune_in;  // relative to tune-in
                        const uint64_t size = line.start[n + 1] - line.start[n];
                        if (begin + size > until) break;  // not whole yet at this time
                        const uint32_t p = scheme.packet_at(q * period + n);
                        if (!lost[begin / slot_bytes]) {
                            ++received;
                            bytes += size;
                            if (!have[p]) {
                                have[p] = true;
                                ++distinct;
                            }
                        }
                        if (++n == period) {
                            n = 0;
                            ++q;
                        }
                    }
                    std::vector<uint32_t> held;
                    held.reserve(distinct);
                    for (size_t i = 0; i < have.size(); ++i)
                        if (have[i]) held.push_back(uint32_t(i));
                    Outcome o = caches[s].get(scheme, held, measure);
                    const uint64_t slots = std::min<uint64_t>(horizon, (until + slot_bytes - 1) / slot_bytes);
                    TrialResult r;
                    r.scheme = s;
                    r.loss = loss;
                    r.burst = burst;
                    r.trial = job.trial;
                    r.tune_in = tune_in;
                    r.tune_in_phase = double(tune_in % cycle) / double(cycle);
                    r.time = t;
                    r.air_bytes = until;
                    r.trace_loss = slots ? double(lost_before[slots]) / double(slots) : 0;
                    r.packets_received = received;
                    r.bytes_received = bytes;
                    r.distinct_packets = distinct;
                    r.distinct_fraction = double(distinct) / double(scheme.packets().size());
                    r.data_fraction = o.data_fraction;
                    r.shown = o.shown;
                    r.triangles = o.triangles;
                    r.distance = o.distance;
                    rows[j].push_back(r);
                }
            }
            const size_t finished = ++done;
            if (options.progress) {
                std::lock_guard<std::mutex> lock(progress_mutex);
                options.progress(double(finished) / double(jobs.size()));
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
    for (auto& r : rows) result.trials.insert(result.trials.end(), r.begin(), r.end());
    return result;
}

Cell summarize(const ExperimentResult& result, size_t scheme, double loss, double burst, double time) {
    Cell cell;
    std::vector<double> rms, hausdorff, holes, bytes, fraction, data;
    size_t shown = 0;
    for (const auto& r : result.trials) {
        if (r.scheme != scheme || std::abs(r.loss - loss) > 1e-9 || std::abs(r.burst - burst) > 1e-9 ||
            std::abs(r.time - time) > 1e-9)
            continue;
        ++cell.trials;
        if (r.shown) {
            ++shown;
            rms.push_back(r.distance.rms);
            hausdorff.push_back(r.distance.hausdorff);
        }
        holes.push_back(r.shown ? r.distance.holes : 100.0);
        bytes.push_back(double(r.bytes_received));
        fraction.push_back(r.distinct_fraction);
        data.push_back(r.data_fraction);
    }
    if (cell.trials == 0) return cell;
    cell.shown_share = double(shown) / double(cell.trials);
    cell.rms_median = quantile(rms, 0.5);
    cell.rms_p25 = quantile(rms, 0.25);
    cell.rms_p75 = quantile(rms, 0.75);
    cell.hausdorff_median = quantile(hausdorff, 0.5);
    cell.holes_median = quantile(holes, 0.5);
    cell.holes_p25 = quantile(holes, 0.25);
    cell.holes_p75 = quantile(holes, 0.75);
    cell.bytes_median = quantile(bytes, 0.5);
    cell.distinct_fraction_median = quantile(fraction, 0.5);
    cell.data_fraction_median = quantile(data, 0.5);
    return cell;
}

}  // namespace ellicast::compare
