// How soon after tuning in a receiver can show a first picture: it needs the stream info part of
// an object and one ELLIPSOIDS packet of it. Simulates the carousel of a stream file under
// independent loss, with and without the stream info repeated inside the chunks, and prints the
// share of receivers that can show something after a given time and the percentiles of the wait.
// A signed stream given its public key (--key) is also measured as a receiver with that key sees it:
// the stream info and the ellipsoids count only once a MANIFEST part that lists them has verified.
//   bench_first_picture STREAM.ellc [--loss 0.5] [--trials 20000] [--seed 1] [--key PUB]
#include <ellicast/auth.h>
#include <ellicast/broadcast/carousel.h>
#include <ellicast/format.h>

#include "stream_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace ellicast;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_first_picture STREAM.ellc [--loss P] [--trials N] [--seed S] [--key PUB]\n");
        return 2;
    }
    double loss = 0.5;
    size_t trials = 20000;
    uint32_t seed = 1;
    std::optional<auth::PublicKey> key;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--loss")) loss = std::stod(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--trials")) trials = std::stoul(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--seed")) seed = uint32_t(std::stoul(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--key")) {
            auth::PublicKey k;
            std::string error;
            if (!auth::read_public_key(argv[i + 1], k, error)) return std::fprintf(stderr, "--key: %s\n", error.c_str()), 2;
            key = k;
        }
        else return std::fprintf(stderr, "unknown option %s\n", argv[i]), 2;
    }
    std::vector<std::vector<uint8_t>> packets;
    if (!bench::read_stream_packets(argv[1], packets))
        return std::fprintf(stderr, "%s: not an ellicast stream file\n", argv[1]), 1;
    std::printf("%s: %zu packets, loss %.2f, %zu trials\n", std::filesystem::path(argv[1]).filename().c_str(), packets.size(), loss, trials);
    std::printf("%-28s %10s %10s %10s %10s %10s %10s\n", "carousel", "cycle B", "shown@.125", "shown@.25", "shown@.5",
                "p50 cyc", "p99 cyc");
    // (stream info repeat, with the key)
    std::vector<std::pair<size_t, bool>> rows = {{0, false}, {8, false}, {4, false}};
    if (key) rows.insert(rows.end(), {{0, true}, {8, true}, {4, true}});
    for (const auto& [every, with_key] : rows) {
        broadcast::CarouselOptions options;
        options.stream_info_every = every;
        broadcast::Carousel c;
        std::string error;
        if (!broadcast::build_carousel(packets, options, c, error)) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> uniform(0, 1);
        const double cycle = c.bytes_per_cycle();
        std::vector<double> waits;
        for (size_t t = 0; t < trials; ++t) {
            // Tune in at a uniformly random moment: the packet on the air is missed.
            const double at = uniform(rng) * cycle;
            uint64_t slot = uint64_t(std::upper_bound(c.cycle_offsets.begin(), c.cycle_offsets.end(), uint64_t(at)) -
                                     c.cycle_offsets.begin());
            const double start = at;
            bool info = false, ellipsoids = false;
            double wait = -1;
            // With the key: what passes the receiver's filter (held packets released by their part).
            std::optional<auth::Authenticator> authenticator;
            if (with_key) authenticator.emplace(*key);
            auto take = [&](const std::vector<uint8_t>& p) {
                const uint8_t ty = p[6];
                info |= ty == uint8_t(PacketType::StreamInfo);
                ellipsoids |= ty == uint8_t(PacketType::Ellipsoids);
            };
            for (uint64_t k = 0; k < 64 * c.cycle.size(); ++k, ++slot) {
                if (uniform(rng) < loss) continue;
                const std::vector<uint8_t>& p = packets[c.packet_at(slot)];
                if (authenticator) {
                    PacketView view;
                    parse_packet(p, view);
                    if (authenticator->take(view, p, k) == auth::Authenticator::Verdict::Pass) take(p);
                    for (const auto& released : authenticator->take_released()) take(released.bytes);
                } else {
                    take(p);
                }
                if (info && ellipsoids) {
                    wait = (double(c.bytes_before(slot + 1)) - start) / cycle;
                    break;
                }
            }
            waits.push_back(wait < 0 ? 1e9 : wait);
        }
        std::sort(waits.begin(), waits.end());
        auto shown = [&](double x) { return 100.0 * double(std::upper_bound(waits.begin(), waits.end(), x) - waits.begin()) / double(trials); };
        char name[64];
        if (every) std::snprintf(name, sizeof name, "stream info every %zu%s", every, with_key ? ", key" : "");
        else std::snprintf(name, sizeof name, "stream info with base only%s", with_key ? ", key" : "");
        std::printf("%-28s %10llu %9.1f%% %9.1f%% %9.1f%% %10.3f %10.3f\n", name, (unsigned long long)c.bytes_per_cycle(),
                    shown(0.125), shown(0.25), shown(0.5), waits[trials / 2], waits[trials * 99 / 100]);
    }
    return 0;
}
