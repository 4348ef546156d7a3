// `ellicast simulate IN.ellc -o RECEIVED.ellc`: sends the carousel through a simulated channel
// (loss, bursts, reordering, duplication, bit errors) to a receiver that tunes in at a given slot,
// and writes what that receiver got: every intact packet in arrival order.
#include "broadcast_cli.h"
#include "commands.h"

#include <ellicast/broadcast/reception.h>
#include <ellicast/format.h>

#include <cmath>
#include <iostream>

namespace ellicast::cli {
namespace {

struct SimulateArgs {
    std::string input;
    std::string output;
    CarouselCli carousel;
    ChannelCli channel;
    double cycles = 1;
    uint64_t tune_in = 0;
    bool tune_in_random = false;
};

int run_simulate(const SimulateArgs& a) {
    if (output_clobbers_input(a.output, {a.input})) return kExitUsage;
    if (!a.channel.trace_out.empty() && output_clobbers_input(a.channel.trace_out, {a.input})) return kExitUsage;
    std::vector<std::vector<uint8_t>> packets;
    broadcast::Carousel carousel;
    if (int code = load_carousel(a.input, a.carousel, packets, carousel); code != kExitOk) return code;
    std::string error;
    const uint64_t slots = static_cast<uint64_t>(std::ceil(a.cycles * carousel.slots_per_cycle()));
    if (slots > broadcast::kMaxTraceSlots)
        return fail(kExitUsage, "--cycles " + std::to_string(a.cycles) + " means " + with_commas(slots) +
                                    " packets, more than the simulator's cap of " +
                                    with_commas(broadcast::kMaxTraceSlots));
    uint64_t tune_in = a.tune_in;
    if (a.tune_in_random) tune_in = (a.channel.seed * 0x9E3779B97F4A7C15ull >> 17) % carousel.cycle.size();
    size_t packet_bytes = 0;
    for (uint32_t size : carousel.sizes) packet_bytes = std::max<size_t>(packet_bytes, size);
    broadcast::LossTrace trace;
    if (!a.channel.trace(slots, packet_bytes, trace, error)) return fail(kExitUsage, error);
    if (!a.channel.trace_in.empty() && trace.packet_bytes() != packet_bytes)
        std::cerr << "ellicast: note: the trace was drawn for " << trace.packet_bytes() << "-byte packets, this stream's "
                  << "largest is " << packet_bytes << " bytes; bit positions apply modulo each packet's size\n";

    // Transmit: slot tune_in + k of the carousel meets the fate of trace slot k.
    std::vector<std::vector<uint8_t>> sent;
    sent.reserve(slots);
    for (uint64_t k = 0; k < slots; ++k) sent.push_back(broadcast::carousel_packet(carousel, packets, tune_in + k));
    broadcast::Reception reception;
    std::vector<std::vector<uint8_t>> kept;
    std::vector<bool> received(slots, false);
    int64_t base_at = -1, full_at = -1;  // arrival index at which the base / everything was complete
    uint64_t reordered = 0, arrivals = 0;
    uint64_t highest = 0;
    for (const broadcast::Arrival& arrival : broadcast::arrival_order(trace, slots)) {
        std::vector<uint8_t> bytes =
            arrival.corrupted ? broadcast::damage_packet(trace, arrival.slot, sent[arrival.slot]) : sent[arrival.slot];
        if (arrivals > 0 && arrival.slot < highest && !arrival.duplicate) ++reordered;
        highest = std::max(highest, arrival.slot);
        ++arrivals;
        if (reception.take(bytes) != Error::Ok) continue;
        received[arrival.slot] = true;
        kept.push_back(std::move(bytes));
        if (base_at < 0 && reception.base_complete()) base_at = static_cast<int64_t>(arrival.slot);
        if (full_at < 0 && reception.complete()) full_at = static_cast<int64_t>(arrival.slot);
    }
    std::string message;
    if (write_file(a.output, write_container(kept), message) != Error::Ok)
        return fail(kExitFailure, "cannot write " + a.output + ": " + message);

    const auto& counters = reception.counters();
    std::printf("channel: %s\n", trace.description().c_str());
    std::printf("sent: %s packets, slots %s..%s of the carousel (%g cycles of %zu packets)\n",
                with_commas(slots).c_str(), with_commas(tune_in).c_str(), with_commas(tune_in + slots - 1).c_str(),
                a.cycles, size_t(carousel.slots_per_cycle()));
    std::printf("channel did: %s lost (%.1f%%), %s corrupted, %s duplicated, %s reordered\n",
                with_commas(trace.lost_count()).c_str(), 100.0 * double(trace.lost_count()) / double(slots),
                with_commas(trace.corrupted_count()).c_str(), with_commas(trace.duplicated_count()).c_str(),
                with_commas(reordered).c_str());
    std::printf("receiver: %s datagrams, %s kept (%s new, %s repeats), %s rejected (%s damaged)\n",
                with_commas(counters.datagrams).c_str(), with_commas(kept.size()).c_str(),
                with_commas(counters.accepted).c_str(), with_commas(counters.duplicates).c_str(),
                with_commas(counters.rejected()).c_str(), with_commas(counters.damaged).c_str());
    std::printf("estimated loss from sequence gaps: %.1f%%\n", 100.0 * reception.loss().loss());
    auto when = [&](int64_t slot) {
        if (slot < 0) return std::string("not within the simulated time");
        uint64_t bytes = carousel.bytes_before(tune_in + slot + 1) - carousel.bytes_before(tune_in);
        return "after " + with_commas(uint64_t(slot) + 1) + " packets (" + with_commas(bytes) + " bytes)";
    };
    std::printf("base complete: %s\n", when(base_at).c_str());
    std::printf("points: %s of %s (%.1f%%); everything: %s\n", with_commas(reception.points_received()).c_str(),
                with_commas(reception.points_declared()).c_str(),
                reception.points_declared() ? 100.0 * double(reception.points_received()) /
                                                  double(reception.points_declared())
                                            : 0.0,
                when(full_at).c_str());
    broadcast::CarouselStats stats = broadcast::carousel_stats(carousel);
    // The expectation at the channel's loss rate (--loss), not at what one short run happened to lose;
    // a recorded trace has no rate of its own but what it lost.
    const bool from_trace = !a.channel.trace_in.empty();
    double rate = from_trace ? double(trace.lost_count()) / double(slots) : a.channel.loss;
    if (!from_trace && a.channel.gilbert_elliott.size() == 4) {  // its long-run rate
        const auto& ge = a.channel.gilbert_elliott;  // good_to_bad, bad_to_good, loss_good, loss_bad
        const double bad = ge[0] + ge[1] > 0 ? ge[0] / (ge[0] + ge[1]) : 0;
        rate = (1 - bad) * ge[2] + bad * ge[3];
    }
    std::printf("schedule: worst-case base wait without loss %s bytes; expected at %s %.1f%% loss %s bytes\n",
                with_commas(stats.worst_base_wait_bytes).c_str(), from_trace ? "the trace's" : "the channel's",
                100.0 * rate,
                with_commas(static_cast<uint64_t>(
                                broadcast::expected_wait_bytes(carousel, broadcast::WaitFor::Base, rate, 256)))
                    .c_str());
    std::printf("wrote %s: %s packets\n", a.output.c_str(), with_commas(kept.size()).c_str());
    if (!a.channel.trace_out.empty()) std::printf("wrote the trace to %s\n", a.channel.trace_out.c_str());
    return kExitOk;
}

const RegisterCommand kRegisterSimulate{{61, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<SimulateArgs>();
    auto* cmd = app.add_subcommand("simulate", "Send a stream's carousel through a simulated lossy channel");
    cmd->add_option("input", args->input, "stream file (.ellc)")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", args->output, "stream file of what the receiver got (.ellc)")->required();
    args->carousel.add(cmd);
    args->channel.add(cmd, true);
    cmd->add_option("--cycles", args->cycles, "how long the receiver listens, in carousel cycles (default 1)")
        ->check(CLI::Range(0.001, 1e6));
    auto* tune = cmd->add_option("--tune-in", args->tune_in, "carousel slot at which the receiver tunes in (default 0)");
    cmd->add_flag("--tune-in-random", args->tune_in_random, "tune in at a slot of the first cycle drawn from --seed")
        ->excludes(tune);
    cmd->callback([args, &exit_code] { exit_code = run_simulate(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli
