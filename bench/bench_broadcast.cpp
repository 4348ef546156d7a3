// Broadcast on loopback: time from tune-in to the first displayed base and to full quality, as a
// function of the loss rate, measured with real UDP datagrams at a fixed rate, against the
// carousel's theoretical values (exact expectations for the schedule under independent loss).
//
//   build/bench/bench_broadcast [MODEL_OR_STREAM] [--rate BPS] [--loss 0,0.1,...] [--trials N]
//                               [--base-share F | --chunk N] [--seed S] [--out DIR]
//
// MODEL_OR_STREAM: a stream file (.ellc) or a model that is encoded first (default: the bunny
// from ../shared/samples). Each trial: a receiver listens on 127.0.0.1; a sender thread starts the
// carousel at a random slot (a uniformly random tune-in) with sender-side independent loss drawn
// from its own seed; the receiver records when the base is complete, when its base mesh is built
// (rasterize + marching cubes: "displayed"), and when every packet has arrived. Writes
// DIR/broadcast.csv (every trial), DIR/broadcast_summary.csv, DIR/broadcast.gp and, when gnuplot
// is installed, DIR/broadcast.svg and DIR/broadcast.png.
#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/channel.h>
#include <ellicast/broadcast/reception.h>
#include <ellicast/broadcast/udp.h>

#include "ellicast/codec/decoder.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace ellicast;
using namespace ellicast::broadcast;
using Clock = std::chrono::steady_clock;

namespace {

struct Trial {
    double loss = 0;
    int trial = 0;
    uint64_t first_slot = 0;
    double base = -1;       // seconds from the first slot's send time to a complete base
    double shown = -1;      // ... to a built base mesh
    double full = -1;       // ... to every packet
    double measured_loss = 0;
    double rate_ratio = 0;  // achieved sending rate / asked rate (below 1: the sender fell behind)
};

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

bool load_stream(const std::string& path, std::vector<std::vector<uint8_t>>& packets, std::string& error) {
    if (std::filesystem::path(path).extension() == ".ellc") {
        std::vector<uint8_t> bytes;
        if (read_file(path, bytes, error) != Error::Ok) return false;
        ContainerContents contents = read_container(bytes);
        if (contents.header_error != Error::Ok) {
            error = path + ": not a stream file";
            return false;
        }
        for (const auto& p : contents.packets)
            packets.emplace_back(bytes.begin() + p.offset, bytes.begin() + p.offset + p.view.size);
        return !packets.empty();
    }
    std::fprintf(stderr, "encoding %s ...\n", path.c_str());
    LoadResult model = load_meshes(path);
    EncodeResult encoded = encode_meshes(model.meshes, EncodeOptions{});
    StreamPackets sp;
    if (packetize_stream(encoded.info, encoded.contents, 1, sp) != Error::Ok) {
        error = "packetizing failed";
        return false;
    }
    for (auto* part : {&sp.stream_info, &sp.ellipsoids, &sp.maps, &sp.points, &sp.normals})
        for (auto& p : *part) packets.push_back(p);
    return true;
}

// Builds the base meshes of a received stream, as a receiver does before showing anything.
void build_base(const ReceivedStream& stream) {
    for (size_t i = 0; i < stream.objects().size(); ++i) {
        const auto& object = stream.objects()[i];
        if (!object.info || object.info->kind != ObjectKind::Surface) continue;
        EllipsoidGrid grid;
        std::string error;
        int resolution = stream.info()->grid_hint > 0 ? stream.info()->grid_hint : kDefaultGridResolution;
        if (!rasterize_ellipsoids(stream.ellipsoids(i), object.info->frame, resolution, grid, error)) continue;
        if (!grid.empty()) marching_cubes(grid);
    }
}

Trial run_trial(const Carousel& carousel, const std::vector<std::vector<uint8_t>>& packets, double rate, double loss,
                uint64_t seed, int index) {
    Trial t;
    t.loss = loss;
    t.trial = index;
    UdpReceiver receiver;
    std::string error;
    Endpoint any;
    parse_endpoint("127.0.0.1:0", any, error);
    if (!receiver.open(any, ReceiverOptions{}, error)) {
        std::fprintf(stderr, "receiver: %s\n", error.c_str());
        return t;
    }
    Endpoint to;
    parse_endpoint("127.0.0.1:" + std::to_string(receiver.local_port()), to, error);
    UdpSender sender;
    if (!sender.open(to, SenderOptions{}, error)) {
        std::fprintf(stderr, "sender: %s\n", error.c_str());
        return t;
    }
    ChannelModel model;
    model.loss = loss;
    model.seed = seed;
    const double max_cycles = 60;
    LossTrace trace;
    generate_trace(model, static_cast<uint64_t>(max_cycles * carousel.cycle.size()), 1200, trace, error);
    ServeOptions serve;
    serve.bits_per_second = rate;
    serve.cycles = max_cycles;
    serve.trace = &trace;
    t.first_slot = (seed * 0x9E3779B97F4A7C15ull >> 20) % carousel.cycle.size();
    serve.first_slot = t.first_slot;
    std::atomic<bool> stop{false};
    ServeCounters counters;
    Clock::time_point start;
    std::atomic<bool> started{false};
    Clock::time_point end;
    std::thread sending([&] {
        start = Clock::now();
        started = true;
        serve_carousel(carousel, packets, sender, serve, counters, error, {}, &stop);
        end = Clock::now();
    });
    Reception reception;
    std::vector<uint8_t> buffer(kMaxPacketSize + 1);
    const auto deadline = Clock::now() + std::chrono::duration<double>(max_cycles * carousel.cycle_bytes * 8 / rate + 5);
    while (Clock::now() < deadline) {
        Datagram d;
        if (receiver.receive(buffer, std::chrono::milliseconds(20), d, error) != 1) continue;
        reception.take(std::span<const uint8_t>(buffer.data(), d.size), d.truncated);
        auto now = Clock::now();
        if (t.base < 0 && reception.base_complete()) {
            t.base = seconds(start, now);
            build_base(reception.stream());
            t.shown = seconds(start, Clock::now());
        }
        if (reception.complete()) {
            t.full = seconds(start, Clock::now());
            break;
        }
    }
    stop = true;
    sending.join();
    t.measured_loss = reception.loss().loss();
    const double sent_bits =
        8.0 * double(carousel.bytes_before(t.first_slot + counters.slots) - carousel.bytes_before(t.first_slot));
    t.rate_ratio = sent_bits / std::max(1e-9, seconds(start, end)) / rate;
    return t;
}

std::vector<double> parse_list(const std::string& text) {
    std::vector<double> out;
    std::stringstream items(text);
    std::string item;
    while (std::getline(items, item, ',')) out.push_back(std::stod(item));
    return out;
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / double(v.size());
}

}  // namespace

int main(int argc, char** argv) {
    // ../shared/samples next to the checkout (this file is <checkout>/bench/bench_broadcast.cpp).
    std::string input = (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "shared" /
                         "samples" / "meshes" / "bunny.ply")
                            .string();
    double rate = 2e6;
    std::vector<double> losses = {0, 0.05, 0.1, 0.2, 0.3, 0.5};
    int trials = 8;
    uint64_t seed = 1;
    CarouselOptions options;
    std::string out_dir = "broadcast-bench";
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--rate") rate = std::stod(next());
        else if (a == "--loss") losses = parse_list(next());
        else if (a == "--trials") trials = std::stoi(next());
        else if (a == "--seed") seed = std::stoull(next());
        else if (a == "--base-share") options.base_share = std::stod(next());
        else if (a == "--chunk") options.chunk_packets = std::stoul(next());
        else if (a == "--out") out_dir = next();
        else if (!a.empty() && a[0] != '-') input = a;
        else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            return 2;
        }
    }
    std::vector<std::vector<uint8_t>> packets;
    std::string error;
    if (!load_stream(input, packets, error)) {
        std::fprintf(stderr, "cannot load %s: %s\n", input.c_str(), error.c_str());
        return 1;
    }
    Carousel carousel;
    if (!build_carousel(packets, options, carousel, error)) {
        std::fprintf(stderr, "carousel: %s\n", error.c_str());
        return 1;
    }
    CarouselStats stats = carousel_stats(carousel);
    const double bytes_to_s = 8.0 / rate;
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\ninput: %s (%zu packets)\n", input.c_str(), packets.size());
    std::printf("rate: %.0f bit/s; cycle %zu packets, %llu bytes = %.3f s; %zu chunks\n", rate, carousel.cycle.size(),
                (unsigned long long)stats.cycle_bytes, stats.cycle_bytes * bytes_to_s, carousel.chunk_count);
    std::printf("base %llu bytes, points %llu bytes; base share %.1f%%, repetition overhead %.1f%%\n",
                (unsigned long long)stats.base_bytes, (unsigned long long)stats.data_bytes, 100 * stats.base_share,
                100 * stats.repetition_overhead);
    std::printf("worst-case base wait without loss %.3f s, mean %.3f s; worst full %.3f s\n",
                stats.worst_base_wait_bytes * bytes_to_s, stats.mean_base_wait_bytes * bytes_to_s,
                stats.worst_full_wait_bytes * bytes_to_s);

    std::filesystem::create_directories(out_dir);
    std::ofstream csv(out_dir + "/broadcast.csv");
    csv << "loss,trial,first_slot,measured_loss,base_s,shown_s,full_s,rate_ratio\n";
    std::ofstream summary(out_dir + "/broadcast_summary.csv");
    summary << "loss,trials,base_mean_s,base_max_s,shown_mean_s,full_mean_s,full_max_s,theory_base_s,theory_full_s,"
               "base_min_s,full_min_s,rate_ratio_min\n";
    std::printf("\n%6s %7s | %9s %9s %9s | %9s %9s | %9s %9s | %s\n", "loss", "trials", "base", "theory", "shown", "full",
                "theory", "base max", "full max", "rate (min)");
    int trial_index = 0;
    for (double loss : losses) {
        std::vector<double> base, shown, full;
        double rate_min = 1e9;
        for (int k = 0; k < trials; ++k) {
            Trial t = run_trial(carousel, packets, rate, loss, seed * 1000003 + trial_index++, k);
            csv << loss << "," << k << "," << t.first_slot << "," << t.measured_loss << "," << t.base << "," << t.shown
                << "," << t.full << "," << t.rate_ratio << "\n";
            rate_min = std::min(rate_min, t.rate_ratio);
            if (t.base >= 0) base.push_back(t.base);
            if (t.shown >= 0) shown.push_back(t.shown);
            if (t.full >= 0) full.push_back(t.full);
        }
        double theory_base = expected_wait_bytes(carousel, WaitFor::Base, loss, 0, true) * bytes_to_s;
        double theory_full = expected_wait_bytes(carousel, WaitFor::Everything, loss, 0, true) * bytes_to_s;
        auto maxof = [](const std::vector<double>& v) { return v.empty() ? -1 : *std::max_element(v.begin(), v.end()); };
        auto minof = [](const std::vector<double>& v) { return v.empty() ? -1 : *std::min_element(v.begin(), v.end()); };
        std::printf("%6.2f %7d | %8.3fs %8.3fs %8.3fs | %8.3fs %8.3fs | %8.3fs %8.3fs | %.1f%%\n", loss, trials,
                    mean(base), theory_base, mean(shown), mean(full), theory_full, maxof(base), maxof(full),
                    100 * rate_min);
        std::fflush(stdout);
        summary << loss << "," << trials << "," << mean(base) << "," << maxof(base) << "," << mean(shown) << ","
                << mean(full) << "," << maxof(full) << "," << theory_base << "," << theory_full << "," << minof(base)
                << "," << minof(full) << "\n";
    }
    summary.close();
    csv.close();
    std::ofstream gp(out_dir + "/broadcast.gp");
    gp << "# gnuplot script written by bench_broadcast\n"
          "set datafile separator ','\n"
          "set key top left\n"
          "set grid\n"
          "set xlabel 'packet loss rate'\n"
          "set ylabel 'seconds after tune-in'\n"
          "set title 'ellicast on loopback at "
       << rate / 1e6 << " Mbit/s: " << std::filesystem::path(input).filename().string()
       << "'\n"
          "set logscale y\n"
          "plot 'broadcast_summary.csv' every ::1 using 1:3:10:4 with yerrorbars lc rgb '#1f77b4' pt 7 title 'base "
          "complete (measured: mean, min..max)',\\\n"
          "     '' every ::1 using 1:8 with lines lc rgb '#1f77b4' dt 2 title 'base (schedule, expected)',\\\n"
          "     '' every ::1 using 1:5 with points lc rgb '#2ca02c' pt 5 title 'base mesh displayed (measured mean)',\\\n"
          "     '' every ::1 using 1:6:11:7 with yerrorbars lc rgb '#d62728' pt 7 title 'full quality (measured: mean, "
          "min..max)',\\\n"
          "     '' every ::1 using 1:9 with lines lc rgb '#d62728' dt 2 title 'full quality (schedule, expected)'\n";
    gp.close();
    std::string cmd = "cd '" + out_dir +
                      "' && gnuplot -e \"set terminal svg size 900,600 dynamic; set output 'broadcast.svg'\" broadcast.gp && "
                      "gnuplot -e \"set terminal pngcairo size 900,600; set output 'broadcast.png'\" broadcast.gp";
    if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
        if (std::system(cmd.c_str()) == 0)
            std::printf("\nplots: %s/broadcast.svg, %s/broadcast.png\n", out_dir.c_str(), out_dir.c_str());
    } else {
        std::printf("\ngnuplot is not installed: run it on %s/broadcast.gp\n", out_dir.c_str());
    }
    return 0;
}
