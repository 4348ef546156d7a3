// How soon after tuning in a receiver holds every point, and how many it holds on the way, for the
// carousel of a stream file under independent loss: with repair packets (format 1.2) the carousel
// interleaves them with the POINTS packets; without, it repeats the POINTS packets every cycle.
// Prints, per loss rate, the median and 90th percentile of the cycles until every point is held and
// until the stream is complete (format 1.3: with each object's exact layer, so the receiver shows
// the original mesh), and the median share of points held after 0.25, 0.5 and 1 cycle.
//   bench_full_quality STREAM.ellc [--loss 0.1,0.5] [--trials 20] [--seed 1]
#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/reception.h>
#include <ellicast/format.h>

#include "stream_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace ellicast;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_full_quality STREAM.ellc [--loss P,P,...] [--trials N] [--seed S]\n");
        return 2;
    }
    std::vector<double> losses = {0.1, 0.5};
    size_t trials = 20;
    uint64_t seed = 1;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--loss")) {
            losses.clear();
            std::stringstream list(argv[i + 1]);
            for (std::string item; std::getline(list, item, ',');) losses.push_back(std::stod(item));
        } else if (!std::strcmp(argv[i], "--trials")) {
            trials = std::stoul(argv[i + 1]);
        } else if (!std::strcmp(argv[i], "--seed")) {
            seed = std::stoull(argv[i + 1]);
        } else {
            return std::fprintf(stderr, "unknown option %s\n", argv[i]), 2;
        }
    }
    std::vector<std::vector<uint8_t>> packets;
    if (!bench::read_stream_packets(argv[1], packets))
        return std::fprintf(stderr, "%s: not an ellicast stream file\n", argv[1]), 1;
    broadcast::Carousel c;
    std::string error;
    if (!broadcast::build_carousel(packets, broadcast::CarouselOptions{}, c, error))
        return std::fprintf(stderr, "%s\n", error.c_str()), 1;
    const double cycle = c.bytes_per_cycle();
    std::printf("%s: %zu packets, %zu repair blocks, cycle %.0f bytes, %zu trials\n",
                std::filesystem::path(argv[1]).filename().c_str(), packets.size(), c.blocks.size(), cycle, trials);
    std::printf("%6s %12s %12s %12s %12s %10s %10s %10s\n", "loss", "points p50", "points p90", "exact p50", "exact p90",
                "held@.25", "held@.5", "held@1");
    for (double loss : losses) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> uniform(0, 1);
        std::vector<double> done, points, at_quarter, at_half, at_one;
        for (size_t t = 0; t < trials; ++t) {
            std::fprintf(stderr, "\rloss %.2f: trial %zu/%zu", loss, t + 1, trials);
            broadcast::Reception reception;
            const uint64_t start = rng() % c.cycle.size();
            double quarter = -1, half = -1, one = -1, finished = -1, all_points = -1;
            for (uint64_t slot = start; slot < start + 200 * c.cycle.size(); ++slot) {
                const double elapsed = double(c.bytes_before(slot) - c.bytes_before(start)) / cycle;
                const double share =
                    reception.points_declared() ? double(reception.points_received()) / double(reception.points_declared()) : 0;
                if (quarter < 0 && elapsed >= 0.25) quarter = share;
                if (half < 0 && elapsed >= 0.5) half = share;
                if (one < 0 && elapsed >= 1.0) one = share;
                if (uniform(rng) >= loss) reception.take(broadcast::carousel_packet(c, packets, slot));
                if (all_points < 0 && reception.points_declared() &&
                    reception.points_received() == reception.points_declared())
                    all_points = double(c.bytes_before(slot + 1) - c.bytes_before(start)) / cycle;
                if (reception.complete()) {
                    finished = double(c.bytes_before(slot + 1) - c.bytes_before(start)) / cycle;
                    break;
                }
            }
            done.push_back(finished < 0 ? 1e9 : finished);
            points.push_back(all_points < 0 ? 1e9 : all_points);
            at_quarter.push_back(quarter < 0 ? 1 : quarter);
            at_half.push_back(half < 0 ? 1 : half);
            at_one.push_back(one < 0 ? 1 : one);
        }
        std::fprintf(stderr, "\n");
        for (auto* v : {&done, &points, &at_quarter, &at_half, &at_one}) std::sort(v->begin(), v->end());
        auto median = [](const std::vector<double>& v) { return v[v.size() / 2]; };
        std::printf("%5.0f%% %12.2f %12.2f %12.2f %12.2f %9.1f%% %9.1f%% %9.1f%%\n", loss * 100, median(points),
                    points[points.size() * 9 / 10], median(done), done[done.size() * 9 / 10], 100 * median(at_quarter),
                    100 * median(at_half), 100 * median(at_one));
    }
    return 0;
}
