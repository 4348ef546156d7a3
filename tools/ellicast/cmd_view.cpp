// `ellicast view IN.ellc [--loss P] [--burst B] [--rate BITS/S]`: plays a recorded stream's
// carousel through the channel simulator in real time, to a receiver that tunes in at a slot, and
// shows what that receiver shows in a local web page (live_view.h): the base as soon as it is
// whole, refined as points arrive, exact when the exact layer is whole.
#include "broadcast_cli.h"
#include "commands.h"
#include "live_reconstruction.h"
#include "live_view.h"
#include "region_option.h"

#include <ellicast/broadcast/reception.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>

namespace ellicast::cli {
namespace {

std::atomic<bool> g_view_stop{false};
void on_view_interrupt(int) { g_view_stop.store(true); }

struct ViewArgs {
    std::string input;
    CarouselCli carousel;
    ChannelCli channel;
    double rate = 1'000'000;
    double cycles = 20;
    uint64_t tune_in = 0;
    bool tune_in_random = false;
    int grid = 0;
    std::string bind = "127.0.0.1";
    uint16_t port = 8765;
    std::string three;
    std::string reference;
    double linger = -1;
    double wait_for_viewer = 0;
    bool quiet = false;
};

int run_view(const ViewArgs& a) {
    std::vector<std::vector<uint8_t>> packets;
    broadcast::Carousel carousel;
    if (int code = load_carousel(a.input, a.carousel, packets, carousel); code != kExitOk) return code;
    const uint64_t slots = static_cast<uint64_t>(std::ceil(a.cycles * carousel.slots_per_cycle()));
    if (slots > broadcast::kMaxTraceSlots)
        return fail(kExitUsage, "--cycles " + std::to_string(a.cycles) + " means " + with_commas(slots) +
                                    " packets, more than the simulator's cap of " + with_commas(broadcast::kMaxTraceSlots));
    size_t packet_bytes = 0;
    for (uint32_t size : carousel.sizes) packet_bytes = std::max<size_t>(packet_bytes, size);
    std::string error;
    broadcast::LossTrace trace;
    if (!a.channel.trace(slots, packet_bytes, trace, error)) return fail(kExitUsage, error);
    uint64_t tune_in = a.tune_in;
    if (a.tune_in_random) tune_in = (a.channel.seed * 0x9E3779B97F4A7C15ull >> 17) % carousel.cycle.size();

    LiveViewOptions options;
    options.bind = a.bind;
    options.port = a.port;
    options.three_dir = a.three;
    options.reference = a.reference;
    char title[512];
    std::snprintf(title, sizeof title, "%s: %s at %s bit/s, tuned in at slot %llu",
                  std::filesystem::path(a.input).filename().string().c_str(), trace.description().c_str(),
                  with_commas(static_cast<uint64_t>(a.rate)).c_str(), static_cast<unsigned long long>(tune_in));
    options.title = title;
    LiveView view;
    if (!view.start(options, error)) return fail(kExitFailure, error);
    std::fprintf(stderr, "view: %s\n", view.url().c_str());
    if (view.reachable_from_other_hosts())
        std::fprintf(stderr, "ellicast: warning: --bind %s: the page can be opened from other hosts\n", a.bind.c_str());
    std::fflush(stderr);

    std::signal(SIGINT, on_view_interrupt);
    std::signal(SIGTERM, on_view_interrupt);
    struct RestoreSignals {
        ~RestoreSignals() {
            std::signal(SIGINT, SIG_DFL);
            std::signal(SIGTERM, SIG_DFL);
        }
    } restore;
    if (a.wait_for_viewer > 0) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(a.wait_for_viewer);
        if (!a.quiet) std::fprintf(stderr, "waiting for a page to open %s\n", view.url().c_str());
        while (!g_view_stop.load() && view.viewers() == 0 && std::chrono::steady_clock::now() < until)
            view.poll(std::chrono::milliseconds(50));
        if (view.viewers() == 0 && !g_view_stop.load())
            std::fprintf(stderr, "ellicast: warning: no page opened within %g s: playing anyway\n", a.wait_for_viewer);
    }

    // The channel: slot k of the trace carries carousel slot tune_in + k, sent when the bytes before
    // it have gone out at --rate; an arrival comes when the latest slot sent so far has gone out
    // (a delayed packet arrives after later ones).
    const std::vector<broadcast::Arrival> arrivals = broadcast::arrival_order(trace, slots);
    auto sent_at = [&](uint64_t slot) {
        return 8.0 * double(carousel.bytes_before(tune_in + slot + 1) - carousel.bytes_before(tune_in)) / a.rate;
    };
    std::vector<double> arrival_time(arrivals.size());
    uint64_t highest = 0;
    for (size_t i = 0; i < arrivals.size(); ++i) {
        highest = std::max(highest, arrivals[i].slot);
        arrival_time[i] = sent_at(highest);
    }
    broadcast::Reception reception;
    LiveReconstruction live(a.grid);
    const auto start = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    size_t next = 0;
    uint64_t slots_sent = 0, slots_lost = 0;
    double base_at = -1, complete_at = -1;
    double last_progress = -1;
    uint64_t region_applied = 0;
    uint64_t final_changes = 0, final_region = 0;  // what the last status after the end showed
    while (!g_view_stop.load()) {
        const double now = seconds();
        while (slots_sent < slots && sent_at(slots_sent) <= now) slots_lost += trace.lost(slots_sent++);
        for (; next < arrivals.size() && arrival_time[next] <= now; ++next) {
            const auto& arrival = arrivals[next];
            std::vector<uint8_t> bytes = broadcast::carousel_packet(carousel, packets, tune_in + arrival.slot);
            if (arrival.corrupted) bytes = broadcast::damage_packet(trace, arrival.slot, bytes);
            reception.take(bytes);
        }
        if (!live.started() && reception.base_complete()) {
            view.publish_preview(reception, now);
            if (!live.start(reception.stream(), error)) return fail(kExitFailure, "building the base mesh: " + error);
            base_at = seconds();
            if (!a.quiet)
                std::fprintf(stderr, "base whole after %s, its mesh built after %s\n", seconds_text(now).c_str(),
                             seconds_text(base_at).c_str());
        }
        if (live.started() && view.region_version() != region_applied) {
            // The page turned: points held outside the old view may now be inserted.
            region_applied = view.region_version();
            live.set_region(view.region() ? region_filter(*view.region(), reception.stream())
                                          : LiveReconstruction::InsertIf{});
        }
        if (live.started() && !live.caught_up(reception.stream())) live.work(reception.stream(), std::chrono::milliseconds(view.serving() ? 5 : 30));
        const bool caught_up = live.started() && live.caught_up(reception.stream());
        const bool ended = (reception.complete() || next >= arrivals.size()) && (caught_up || !live.started());
        if (ended && complete_at < 0) {
            complete_at = now;
            view.update(reception, live, now, {slots_sent, slots_lost}, true);
            std::fprintf(stderr, "%s after %s: %s of %s points, %s packets taken, %s lost in the channel\n",
                         reception.complete() ? "complete" : "the simulated time is over", seconds_text(now).c_str(),
                         with_commas(reception.points_received()).c_str(),
                         with_commas(reception.points_declared()).c_str(), with_commas(reception.counters().accepted).c_str(),
                         with_commas(slots_lost).c_str());
        } else if (!ended) {
            view.update(reception, live, now, {slots_sent, slots_lost});
        } else if (live.changes() != final_changes || view.region_version() != final_region) {
            // After the end the page may still turn (refining where it looks): show what changed.
            view.update(reception, live, now, {slots_sent, slots_lost}, true);
        }
        if (ended) {
            final_changes = live.changes();
            final_region = view.region_version();
        }
        if (!a.quiet && !ended && now - last_progress >= 1.0) {
            last_progress = now;
            std::fprintf(stderr, "%.1f s: %s packets taken, points %s/%s received, %s inserted, %zu page(s) open\n", now,
                         with_commas(reception.counters().accepted).c_str(),
                         with_commas(reception.points_received()).c_str(),
                         with_commas(reception.points_declared()).c_str(), with_commas(live.inserted()).c_str(),
                         view.viewers());
        }
        if (ended && a.linger >= 0 && now - complete_at >= a.linger) break;
        // Sleep in the server until the next arrival, or briefly while there is reconstruction work.
        double wait = ended ? 0.2 : (next < arrivals.size() ? arrival_time[next] - seconds() : 0.2);
        if (live.started() && !caught_up) wait = 0;
        view.poll(std::chrono::milliseconds(static_cast<int64_t>(std::clamp(wait, 0.0, 0.2) * 1000)));
    }
    if (base_at < 0) std::fprintf(stderr, "ellicast: warning: the base never became whole: nothing was shown\n");
    std::fprintf(stderr, "view: %llu model(s) published, %s building them\n",
                 static_cast<unsigned long long>(view.models_published()), seconds_text(view.publish_seconds()).c_str());
    return kExitOk;
}

const RegisterCommand kRegisterView{{64, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ViewArgs>();
    auto* cmd = app.add_subcommand(
        "view", "Play a recorded stream through a simulated channel in real time and watch it arrive in a web page");
    cmd->add_option("input", args->input, "stream file (.ellc)")->required()->check(CLI::ExistingFile);
    args->carousel.add(cmd);
    args->channel.add(cmd, true);
    cmd->add_option("--rate", args->rate, "channel rate in bits per second of packet bytes (default 1000000)")
        ->check(CLI::Range(1000.0, 1e11));
    cmd->add_option("--cycles", args->cycles, "play at most this many carousel cycles (default 20)")
        ->check(CLI::Range(0.001, 1e6));
    auto* tune = cmd->add_option("--tune-in", args->tune_in, "carousel slot at which the receiver tunes in (default 0)");
    cmd->add_flag("--tune-in-random", args->tune_in_random, "tune in at a slot of the first cycle drawn from --seed")
        ->excludes(tune);
    cmd->add_option("--grid", args->grid, "decoder grid resolution (default: the stream's hint)")
        ->check(CLI::Range(kMinGridResolution, kMaxGridResolution));
    cmd->add_option("--bind", args->bind,
                    "address the page is served on (default 127.0.0.1: this machine only; 0.0.0.0 opens it to others)");
    cmd->add_option("--port", args->port, "TCP port of the page (default 8765; 0: any free port)");
    cmd->add_option("--three", args->three, "three.js's npm package folder (default: the one scripts/setup.sh installs)");
    cmd->add_option("--reference", args->reference,
                    "the original model (any format ellicast reads): the page shows the surface error against it");
    cmd->add_option("--linger", args->linger,
                    "seconds to keep serving the page after the end (default: until Ctrl-C)")
        ->check(CLI::Range(0.0, 1e7));
    cmd->add_option("--wait-for-viewer", args->wait_for_viewer,
                    "wait up to this many seconds for a page to open before the channel starts (default 0)")
        ->check(CLI::Range(0.0, 3600.0));
    cmd->add_flag("-q,--quiet", args->quiet, "no progress on stderr");
    cmd->callback([args, &exit_code] { exit_code = run_view(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli
