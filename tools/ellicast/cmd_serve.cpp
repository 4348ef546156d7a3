// `ellicast serve IN.ellc --to ADDRESS:PORT --rate BITS_PER_SECOND`: sends the carousel as UDP
// datagrams (one packet each) at a steady rate, to a unicast or multicast address, IPv4 or IPv6.
#include "broadcast_cli.h"
#include "commands.h"

#include <ellicast/broadcast/udp.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>

namespace ellicast::cli {
namespace {

std::atomic<bool> g_serve_stop{false};
void on_serve_interrupt(int) { g_serve_stop.store(true); }

struct ServeArgs {
    std::string input;
    std::string to;
    double rate = 0;
    double cycles = 0;
    int ttl = 1;
    std::string interface;
    bool quiet = false;
    CarouselCli carousel;
    ChannelCli channel;
};

int run_serve(const ServeArgs& a) {
    std::vector<std::vector<uint8_t>> packets;
    broadcast::Carousel carousel;
    if (int code = load_carousel(a.input, a.carousel, packets, carousel); code != kExitOk) return code;
    std::string error;
    broadcast::Endpoint to;
    if (!broadcast::parse_endpoint(a.to, to, error)) return fail(kExitUsage, "--to: " + error);
    if (to.port() == 0) return fail(kExitUsage, "--to: port 0 is not a destination");
    broadcast::SenderOptions sender_options;
    sender_options.multicast_ttl = a.ttl;
    sender_options.interface = a.interface;
    broadcast::UdpSender sender;
    if (!sender.open(to, sender_options, error)) return fail(kExitFailure, error);

    broadcast::LossTrace trace;
    broadcast::ServeOptions options;
    options.bits_per_second = a.rate;
    options.cycles = a.cycles;
    if (a.channel.active()) {
        size_t packet_bytes = 0;
        for (uint32_t size : carousel.sizes) packet_bytes = std::max<size_t>(packet_bytes, size);
        // The simulated channel repeats its trace when the sending outlasts it.
        uint64_t slots = a.cycles > 0 ? static_cast<uint64_t>(std::ceil(a.cycles * carousel.slots_per_cycle()))
                                      : 100 * carousel.cycle.size();
        slots = std::min<uint64_t>(std::max<uint64_t>(slots, 1), 1'000'000);
        if (!a.channel.trace_in.empty()) {
            broadcast::LossTrace whole;
            if (!broadcast::read_trace(a.channel.trace_in, whole, error)) return fail(kExitUsage, error);
            trace = std::move(whole);
            if (!a.channel.trace_out.empty() && !broadcast::write_trace(a.channel.trace_out, trace, error))
                return fail(kExitFailure, error);
        } else if (!a.channel.trace(slots, packet_bytes, trace, error)) {
            return fail(kExitUsage, error);
        }
        options.trace = &trace;
    }
    std::fprintf(stderr, "serving %s to %s at %s bit/s%s\n", a.input.c_str(), a.to.c_str(),
                 with_commas(static_cast<uint64_t>(a.rate)).c_str(),
                 a.cycles > 0 ? (", " + std::to_string(a.cycles) + " cycles").c_str() : ", until interrupted");
    print_carousel(stderr, carousel, a.rate);
    if (options.trace) std::fprintf(stderr, "sender-side simulated channel: %s\n", trace.description().c_str());

    std::signal(SIGINT, on_serve_interrupt);
    std::signal(SIGTERM, on_serve_interrupt);
    const bool tty = isatty(fileno(stderr)) != 0;
    auto start = std::chrono::steady_clock::now();
    auto last_line = start;
    auto progress = [&](const broadcast::ServeCounters& c) {
        if (a.quiet) return;
        auto now = std::chrono::steady_clock::now();
        double elapsed = std::chrono::duration<double>(now - start).count();
        if (!tty && now - last_line < std::chrono::seconds(5)) return;
        last_line = now;
        std::fprintf(stderr, "%ssent %s datagrams, %s bytes, cycle %.2f, %.3f Mbit/s%s%s", tty ? "\r" : "",
                     with_commas(c.datagrams).c_str(), with_commas(c.bytes).c_str(),
                     double(c.slots) / carousel.slots_per_cycle(),
                     elapsed > 0 ? double(c.bytes) * 8 / elapsed / 1e6 : 0.0,
                     options.trace ? (", dropped " + with_commas(c.dropped)).c_str() : "", tty ? "   " : "\n");
        std::fflush(stderr);
    };
    broadcast::ServeCounters counters;
    bool ok = broadcast::serve_carousel(carousel, packets, sender, options, counters, error, progress, &g_serve_stop);
    if (tty && !a.quiet) std::fprintf(stderr, "\n");
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (!ok) return fail(kExitFailure, error);
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "done: %s slots, %s datagrams, %s bytes in %s (%.3f Mbit/s)%s\n",
                 with_commas(counters.slots).c_str(), with_commas(counters.datagrams).c_str(),
                 with_commas(counters.bytes).c_str(), seconds_text(elapsed).c_str(),
                 elapsed > 0 ? double(counters.bytes) * 8 / elapsed / 1e6 : 0.0,
                 g_serve_stop.load() ? " (interrupted)" : "");
    return kExitOk;
}

const RegisterCommand kRegisterServe{{62, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ServeArgs>();
    auto* cmd = app.add_subcommand("serve", "Broadcast a stream's carousel as UDP datagrams at a steady rate");
    cmd->add_option("input", args->input, "stream file (.ellc)")->required()->check(CLI::ExistingFile);
    cmd->add_option("--to", args->to, "destination ADDRESS:PORT, unicast or multicast, e.g. 239.255.0.1:5000 or [::1]:5000")
        ->required();
    cmd->add_option("--rate", args->rate, "bits per second of ellicast packet bytes")
        ->required()
        ->check(CLI::Range(1000.0, 1e11));
    cmd->add_option("--cycles", args->cycles, "carousel cycles to send (fractions allowed; default: until interrupted)")
        ->check(CLI::Range(0.0, 1e9));
    cmd->add_option("--ttl", args->ttl, "multicast TTL / hop limit (0: this host only; default 1)")
        ->check(CLI::Range(0, 255));
    cmd->add_option("--interface", args->interface, "network interface for multicast, e.g. lo");
    cmd->add_flag("-q,--quiet", args->quiet, "no progress on stderr");
    args->carousel.add(cmd);
    args->channel.add(cmd, true);
    cmd->callback([args, &exit_code] { exit_code = run_serve(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli
