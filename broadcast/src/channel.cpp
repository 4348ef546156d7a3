// Channel models and the loss traces they draw.
#include <ellicast/broadcast/channel.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace ellicast::broadcast {

namespace {

// SplitMix64: seeds the per-phenomenon streams; also a good small generator on its own.
uint64_t splitmix64(uint64_t& state) {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// xoshiro256**: the random stream of one phenomenon. Defined bit for bit (unlike the standard
// library's distributions), so a seed gives the same trace on every platform.
class Random {
public:
    Random(uint64_t seed, uint64_t stream) {
        uint64_t s = seed ^ (stream * 0xD1B54A32D192ED03ull);
        for (auto& word : state_) word = splitmix64(s);
    }
    uint64_t next() {
        const uint64_t result = rotl(state_[1] * 5, 7) * 9;
        const uint64_t t = state_[1] << 17;
        state_[2] ^= state_[0];
        state_[3] ^= state_[1];
        state_[1] ^= state_[2];
        state_[0] ^= state_[3];
        state_[2] ^= t;
        state_[3] = rotl(state_[3], 45);
        return result;
    }
    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    bool chance(double p) { return p > 0 && uniform() < p; }
    // Uniform in [lo, hi].
    uint64_t between(uint64_t lo, uint64_t hi) { return lo + next() % (hi - lo + 1); }

private:
    static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    uint64_t state_[4];
};

bool probability(double p) { return p >= 0 && p <= 1; }

}  // namespace

ChannelModel ChannelModel::gilbert(double rate, double burst, uint64_t seed) {
    ChannelModel m;
    m.bursty = true;
    m.loss_good = 0;
    m.loss_bad = 1;
    m.bad_to_good = burst >= 1 ? 1.0 / burst : 1.0;
    // Stationary P(bad) = g / (g + b) = rate  =>  g = rate b / (1 - rate).
    m.good_to_bad = rate < 1 ? std::min(1.0, rate * m.bad_to_good / (1.0 - rate)) : 1.0;
    m.seed = seed;
    return m;
}

double ChannelModel::mean_loss() const {
    if (!bursty) return loss;
    double sum = good_to_bad + bad_to_good;
    double p_bad = sum > 0 ? good_to_bad / sum : 0;
    return p_bad * loss_bad + (1 - p_bad) * loss_good;
}

std::string ChannelModel::describe() const {
    char buffer[512];
    if (bursty)
        std::snprintf(buffer, sizeof buffer,
                      "gilbert-elliott good_to_bad=%.6g bad_to_good=%.6g loss_good=%.6g loss_bad=%.6g (mean loss %.4g)",
                      good_to_bad, bad_to_good, loss_good, loss_bad, mean_loss());
    else
        std::snprintf(buffer, sizeof buffer, "independent loss=%.6g", loss);
    std::string text = buffer;
    std::snprintf(buffer, sizeof buffer, " reorder=%.6g window=%u duplicate=%.6g bit_error_rate=%.6g seed=%llu",
                  reorder, reorder_window, duplicate, bit_error_rate, static_cast<unsigned long long>(seed));
    return text + buffer;
}

std::string check_channel_model(const ChannelModel& m) {
    auto bad = [](const char* name, double value) {
        return std::string(name) + " must be a probability in [0, 1] (got " + std::to_string(value) + ")";
    };
    if (!probability(m.loss)) return bad("loss", m.loss);
    if (!probability(m.good_to_bad)) return bad("good-to-bad transition", m.good_to_bad);
    if (!probability(m.bad_to_good)) return bad("bad-to-good transition", m.bad_to_good);
    if (!probability(m.loss_good)) return bad("loss in the good state", m.loss_good);
    if (!probability(m.loss_bad)) return bad("loss in the bad state", m.loss_bad);
    if (!probability(m.reorder)) return bad("reorder", m.reorder);
    if (!probability(m.duplicate)) return bad("duplicate", m.duplicate);
    if (!probability(m.bit_error_rate)) return bad("bit error rate", m.bit_error_rate);
    if (m.reorder > 0 && m.reorder_window == 0) return "reordering needs a window of at least 1 slot";
    if (m.reorder_window > 1'000'000) return "the reorder window is absurdly large (at most 1000000 slots)";
    if (m.bursty && m.good_to_bad > 0 && m.bad_to_good == 0)
        return "the bad state of the Gilbert-Elliott model must be left (bad-to-good transition > 0)";
    return {};
}

LossTrace::LossTrace(uint64_t slots, size_t packet_bytes, std::string description)
    : packet_bytes_(packet_bytes), description_(std::move(description)), lost_(slots, 0), duplicated_(slots, 0),
      delay_(slots, 0) {}

SlotFate LossTrace::fate(uint64_t slot) const {
    SlotFate f;
    f.lost = lost_[slot] != 0;
    f.duplicated = duplicated_[slot] != 0;
    f.delay = delay_[slot];
    auto it = flips_.find(slot);
    if (it != flips_.end()) f.flipped_bits = it->second;
    return f;
}

void LossTrace::set_fate(uint64_t slot, const SlotFate& fate) {
    lost_[slot] = fate.lost ? 1 : 0;
    duplicated_[slot] = fate.duplicated ? 1 : 0;
    delay_[slot] = fate.delay;
    if (fate.flipped_bits.empty())
        flips_.erase(slot);
    else
        flips_[slot] = fate.flipped_bits;
}

uint64_t LossTrace::lost_count() const { return static_cast<uint64_t>(std::count(lost_.begin(), lost_.end(), 1)); }
uint64_t LossTrace::duplicated_count() const {
    return static_cast<uint64_t>(std::count(duplicated_.begin(), duplicated_.end(), 1));
}
uint64_t LossTrace::delayed_count() const {
    return static_cast<uint64_t>(std::count_if(delay_.begin(), delay_.end(), [](uint32_t d) { return d > 0; }));
}

LossTrace LossTrace::slice(uint64_t first, uint64_t count) const {
    first = std::min<uint64_t>(first, slots());
    count = std::min<uint64_t>(count, slots() - first);
    LossTrace out(count, packet_bytes_, description_);
    for (uint64_t k = 0; k < count; ++k) out.set_fate(k, fate(first + k));
    return out;
}

bool generate_trace(const ChannelModel& model, uint64_t slots, size_t packet_bytes, LossTrace& out,
                    std::string& error) {
    error = check_channel_model(model);
    if (!error.empty()) return false;
    if (slots > kMaxTraceSlots) {
        error = "a trace of " + std::to_string(slots) + " slots exceeds the cap of " + std::to_string(kMaxTraceSlots);
        return false;
    }
    if (packet_bytes == 0) {
        error = "the packet size of a trace must be positive";
        return false;
    }
    out = LossTrace(slots, packet_bytes, model.describe());
    Random loss_rng(model.seed, 1), state_rng(model.seed, 2), reorder_rng(model.seed, 3), dup_rng(model.seed, 4),
        bit_rng(model.seed, 5);
    bool bad = false;
    const uint64_t bits = static_cast<uint64_t>(packet_bytes) * 8;
    // Bit errors: the gap to the next flipped bit is geometric; drawing gaps rather than testing
    // every bit keeps low error rates cheap.
    const bool bit_errors = model.bit_error_rate > 0;
    const double log_keep = bit_errors && model.bit_error_rate < 1 ? std::log1p(-model.bit_error_rate) : 0;
    for (uint64_t k = 0; k < slots; ++k) {
        SlotFate f;
        if (model.bursty) {
            f.lost = loss_rng.chance(bad ? model.loss_bad : model.loss_good);
            bad = bad ? !state_rng.chance(model.bad_to_good) : state_rng.chance(model.good_to_bad);
        } else {
            f.lost = loss_rng.chance(model.loss);
        }
        if (reorder_rng.chance(model.reorder)) f.delay = static_cast<uint32_t>(reorder_rng.between(1, model.reorder_window));
        f.duplicated = dup_rng.chance(model.duplicate);
        if (bit_errors) {
            if (model.bit_error_rate >= 1) {
                for (uint64_t b = 0; b < bits && b < 64; ++b) f.flipped_bits.push_back(static_cast<uint32_t>(b));
            } else {
                uint64_t position = 0;
                while (f.flipped_bits.size() < 64) {
                    double u = 1.0 - bit_rng.uniform();  // (0, 1]
                    double gap = std::floor(std::log(u) / log_keep);
                    if (gap >= double(bits - position)) break;
                    position += static_cast<uint64_t>(gap);
                    f.flipped_bits.push_back(static_cast<uint32_t>(position));
                    if (++position >= bits) break;
                }
            }
        }
        if (f.lost) {
            f.duplicated = false;
            f.delay = 0;
            f.flipped_bits.clear();
        }
        out.set_fate(k, f);
    }
    return true;
}

std::vector<Arrival> arrival_order(const LossTrace& trace, uint64_t count) {
    count = std::min<uint64_t>(count, trace.slots());
    struct Keyed {
        uint64_t time;
        uint32_t delay;
        Arrival arrival;
    };
    std::vector<Keyed> keyed;
    keyed.reserve(count);
    for (uint64_t k = 0; k < count; ++k) {
        SlotFate f = trace.fate(k);
        if (f.lost) continue;
        keyed.push_back({k + f.delay, f.delay, {k, f.corrupted(), false}});
        if (f.duplicated) keyed.push_back({k + f.delay, f.delay, {k, f.corrupted(), true}});
    }
    // A packet delayed by d slots arrives right after the packet sent d slots later.
    std::stable_sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
        return a.time != b.time ? a.time < b.time : a.delay < b.delay;
    });
    std::vector<Arrival> out;
    out.reserve(keyed.size());
    for (const auto& k : keyed) out.push_back(k.arrival);
    return out;
}

std::vector<uint8_t> damage_packet(const LossTrace& trace, uint64_t slot, std::span<const uint8_t> packet) {
    std::vector<uint8_t> out(packet.begin(), packet.end());
    if (out.empty()) return out;
    SlotFate f = trace.fate(slot);
    const uint64_t bits = out.size() * 8;
    for (uint32_t bit : f.flipped_bits) {
        uint64_t b = bit % bits;
        out[b / 8] ^= static_cast<uint8_t>(1u << (b % 8));
    }
    return out;
}

std::vector<std::vector<uint8_t>> apply_trace(const LossTrace& trace, const std::vector<std::vector<uint8_t>>& sent) {
    std::vector<std::vector<uint8_t>> out;
    for (const Arrival& a : arrival_order(trace, sent.size())) {
        if (a.corrupted)
            out.push_back(damage_packet(trace, a.slot, sent[a.slot]));
        else
            out.push_back(sent[a.slot]);
    }
    return out;
}

}  // namespace ellicast::broadcast
