// The carousel schedule: b d1 b d2 ... b dn, its overhead and its waits.
#include "broadcast_support.h"
#include "support.h"

#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/channel.h>

#include <algorithm>
#include <set>

using namespace ellicast;
using namespace ellicast::broadcast;

namespace {

PacketHeader header_of(const std::vector<uint8_t>& bytes) {
    PacketView view;
    REQUIRE(parse_packet(bytes, view) == Error::Ok);
    return view.header;
}

}  // namespace

TEST_CASE("the carousel repeats every non-POINTS packet before each chunk of point packets") {
    auto packets = test::synthetic_stream(300, 6000);
    CarouselOptions options;
    options.chunk_packets = 5;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    size_t base_count = 0, data_count = 0;
    for (const auto& p : packets) (is_base_packet(header_of(p)) ? base_count : data_count)++;
    CHECK(c.base.size() == base_count);
    CHECK(c.data.size() == data_count);
    CHECK(base_count >= 2);  // STREAM_INFO and at least one ELLIPSOIDS
    const size_t chunks = (data_count + 4) / 5;
    CHECK(c.chunk_count == chunks);
    REQUIRE(c.cycle.size() == chunks * base_count + data_count);
    // Walk the cycle: each chunk starts with the whole base in order, then its point packets.
    size_t pos = 0, next_data = 0;
    for (size_t chunk = 0; chunk < chunks; ++chunk) {
        for (size_t b = 0; b < base_count; ++b, ++pos) {
            CHECK(c.cycle[pos].base);
            CHECK(c.cycle[pos].packet == c.base[b]);
        }
        size_t in_chunk = 0;
        while (pos < c.cycle.size() && !c.cycle[pos].base) {
            CHECK(c.cycle[pos].packet == c.data[next_data++]);
            ++pos, ++in_chunk;
        }
        CHECK(in_chunk <= 5);
        CHECK(in_chunk >= 4);
    }
    CHECK(next_data == data_count);
}

TEST_CASE("the base share option picks the chunk count whose share is closest") {
    auto packets = test::synthetic_stream(300, 20000);
    for (double share : {0.05, 0.15, 0.3}) {
        CarouselOptions options;
        options.base_share = share;
        options.min_base_repetitions = 1;
        options.stream_info_every = 0;  // the share of the base copies alone
        Carousel c;
        std::string error;
        REQUIRE(build_carousel(packets, options, c, error));
        CarouselStats s = carousel_stats(c);
        // Changing the chunk count by one must not get closer to the wanted share.
        for (int delta : {-1, 1}) {
            size_t n = c.chunk_count + delta;
            if (n == 0 || n > c.data.size()) continue;
            double other = double(n * c.base_bytes) / double(n * c.base_bytes + c.data_bytes);
            CHECK(std::abs(s.base_share - share) <= std::abs(other - share) + 1e-12);
        }
    }
}

TEST_CASE("a small stream's base is repeated at least the minimum number of times per cycle") {
    // spot-sized: 115 ellipsoids and 4,000 points, where a 15% share alone gives 2 repetitions.
    auto packets = test::synthetic_stream(115, 4000);
    CarouselOptions options;
    options.min_base_repetitions = 1;
    Carousel by_share;
    std::string error;
    REQUIRE(build_carousel(packets, options, by_share, error));
    CHECK(by_share.chunk_count < 4);
    options.min_base_repetitions = 4;
    Carousel c;
    REQUIRE(build_carousel(packets, options, c, error));
    CHECK(c.chunk_count == std::max<size_t>(by_share.chunk_count, std::min<size_t>(4, c.data.size())));
    CHECK(c.chunk_count >= 4);
    size_t repetitions = 0;
    for (const auto& e : c.cycle) repetitions += e.base && e.packet == c.base[0];
    CHECK(repetitions == c.chunk_count);
    // Never more repetitions than point packets to put between them.
    options.min_base_repetitions = 100000;
    REQUIRE(build_carousel(packets, options, c, error));
    CHECK(c.chunk_count == c.data.size());
}

TEST_CASE("overhead and worst-case base wait follow from the base and chunk sizes") {
    auto packets = test::synthetic_stream(200, 8000);
    CarouselOptions options;
    options.chunk_packets = 10;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    CarouselStats s = carousel_stats(c);
    const double once = double(c.base_bytes + c.data_bytes);
    CHECK(c.repeat_bytes > 0);  // the stream info inside the chunks of 10 (after the 8th packet)
    CHECK(s.repetition_overhead == doctest::Approx(double((c.chunk_count - 1) * c.base_bytes + c.repeat_bytes) / once));
    CHECK(s.cycle_bytes == c.chunk_count * c.base_bytes + c.data_bytes + c.repeat_bytes);
    // Tuning in just after the base's largest packet started: the rest of the base, a chunk, and
    // the base again up to that packet.
    uint32_t largest = 0;
    for (uint32_t b : c.base) largest = std::max(largest, c.sizes[b]);
    CHECK(s.worst_base_wait_bytes == c.base_bytes + c.max_chunk_bytes + largest);
    CHECK(s.worst_full_wait_bytes <= s.cycle_bytes + c.base_bytes);
    CHECK(s.worst_full_wait_bytes >= s.cycle_bytes);
    CHECK(s.mean_base_wait_bytes < double(s.worst_base_wait_bytes));
    CHECK(s.mean_base_wait_bytes > double(c.base_bytes));
}

TEST_CASE("a receiver tuning in at any slot holds the base within one chunk plus one base") {
    auto packets = test::synthetic_stream(150, 5000);
    CarouselOptions options;
    options.chunk_packets = 7;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    const size_t bound = c.base.size() + c.chunk_packets;  // in slots
    std::vector<bool> all(3 * c.cycle.size(), true);
    size_t worst = 0;
    for (uint64_t start = 0; start < 2 * c.cycle.size(); ++start) {
        int64_t done = completion_slot(c, WaitFor::Base, start, all);
        REQUIRE(done >= 0);
        worst = std::max(worst, size_t(done) + 1);
        int64_t full = completion_slot(c, WaitFor::Everything, start, all);
        REQUIRE(full >= 0);
        CHECK(size_t(full) + 1 <= c.cycle.size());
    }
    CHECK(worst <= bound);
    CHECK(worst >= bound - 1);  // the bound is reached (tuning in just after a base started)
}

TEST_CASE("the expected wait without loss equals the mean wait, and grows with the loss rate") {
    auto packets = test::synthetic_stream(120, 3000);
    CarouselOptions options;
    options.chunk_packets = 4;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    CarouselStats s = carousel_stats(c);
    CHECK(expected_wait_bytes(c, WaitFor::Base, 0) == doctest::Approx(s.mean_base_wait_bytes));
    CHECK(expected_wait_bytes(c, WaitFor::Everything, 0) == doctest::Approx(s.mean_full_wait_bytes));
    double previous = 0;
    for (double loss : {0.0, 0.1, 0.3, 0.5}) {
        double w = expected_wait_bytes(c, WaitFor::Base, loss, 64);
        CHECK(w > previous);
        previous = w;
    }
}

TEST_CASE("slots carry their slot number as sequence number, with a valid checksum") {
    auto packets = test::synthetic_stream(50, 1000);
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, CarouselOptions{}, c, error));
    std::set<uint32_t> seen;
    for (uint64_t k = 0; k < 3 * c.cycle.size(); ++k) {
        auto bytes = carousel_packet(c, packets, k);
        PacketView view;
        REQUIRE(parse_packet(bytes, view) == Error::Ok);
        CHECK(view.header.sequence == uint32_t(k));
        // Same content as the scheduled packet: only the sequence number differs.
        PacketView original;
        REQUIRE(parse_packet(packets[c.packet_at(k)], original) == Error::Ok);
        CHECK(std::equal(view.payload.begin(), view.payload.end(), original.payload.begin(), original.payload.end()));
        CHECK(view.header.type == original.header.type);
    }
}

TEST_CASE("a carousel refuses an empty stream, a damaged packet and an absurd share") {
    Carousel c;
    std::string error;
    CHECK_FALSE(build_carousel({}, CarouselOptions{}, c, error));
    CHECK(error.find("no packet") != std::string::npos);
    auto packets = test::synthetic_stream(20, 100);
    packets[1][30] ^= 0x10;
    CHECK_FALSE(build_carousel(packets, CarouselOptions{}, c, error));
    CHECK(error.find("packet 1") != std::string::npos);
    CHECK(error.find(error_name(Error::BadChecksum)) != std::string::npos);
    packets = test::synthetic_stream(20, 100);
    CarouselOptions bad;
    bad.base_share = 1.5;
    CHECK_FALSE(build_carousel(packets, bad, c, error));
    CHECK(error.find("share") != std::string::npos);
}

TEST_CASE("ellicast schedule writes the carousel cycles in the order the sender sends them") {
    auto dir = test::scratch_dir("schedule-cli");
    auto packets = test::synthetic_stream(120, 4000);
    test::write_stream_file(dir / "in.ellc", packets);
    REQUIRE(test::run_ellicast({"schedule", (dir / "in.ellc").string(), "-o", (dir / "cycle.ellc").string(), "--chunk",
                                "6", "--cycles", "2", "--rate", "1000000"},
                               dir / "log.txt") == 0);
    std::string log = test::read_text(dir / "log.txt");
    CHECK(log.find("repetition overhead") != std::string::npos);
    CHECK(log.find("worst-case wait for a complete base") != std::string::npos);
    auto written = test::read_stream_file(dir / "cycle.ellc");
    CarouselOptions options;
    options.chunk_packets = 6;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    REQUIRE(written.size() == 2 * c.cycle.size());
    for (size_t k = 0; k < written.size(); ++k) CHECK(written[k] == carousel_packet(c, packets, k));
    // Refuses to overwrite its input, and a file that is not a stream.
    CHECK(test::run_ellicast({"schedule", (dir / "in.ellc").string(), "-o", (dir / "in.ellc").string()},
                             dir / "log2.txt") == 2);
    CHECK(test::run_ellicast({"schedule", (dir / "log.txt").string(), "-o", (dir / "x.ellc").string()},
                             dir / "log3.txt") == 3);
    CHECK(test::read_text(dir / "log3.txt").find("not an ellicast") != std::string::npos);
}

TEST_CASE("the expected wait under loss matches the mean over simulated loss traces") {
    auto packets = test::synthetic_stream(100, 2000);
    CarouselOptions options;
    options.chunk_packets = 3;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    const size_t n = c.cycle.size();
    for (double loss : {0.2, 0.5}) {
        double sum_base = 0, sum_full = 0;
        const int trials = 1500;
        for (int t = 0; t < trials; ++t) {
            ChannelModel m;
            m.loss = loss;
            m.seed = 1000 + t;
            LossTrace trace;
            REQUIRE(generate_trace(m, 40 * n, 1200, trace, error));
            std::vector<bool> delivered(trace.slots());
            for (uint64_t k = 0; k < trace.slots(); ++k) delivered[k] = !trace.lost(k);
            const uint64_t start = uint64_t(t) % n;  // every slot start equally often
            int64_t base = completion_slot(c, WaitFor::Base, start, delivered);
            int64_t full = completion_slot(c, WaitFor::Everything, start, delivered);
            REQUIRE(base >= 0);
            REQUIRE(full >= 0);
            sum_base += double(c.bytes_before(start + base + 1) - c.bytes_before(start));
            sum_full += double(c.bytes_before(start + full + 1) - c.bytes_before(start));
        }
        CHECK(sum_base / trials == doctest::Approx(expected_wait_bytes(c, WaitFor::Base, loss, 0, true)).epsilon(0.05));
        CHECK(sum_full / trials ==
              doctest::Approx(expected_wait_bytes(c, WaitFor::Everything, loss, 0, true)).epsilon(0.03));
    }
}

TEST_CASE("inside each chunk the stream info comes again after every k point packets, so a receiver rarely waits for it") {
    auto packets = test::synthetic_stream(400, 30000);
    CarouselOptions options;
    options.chunk_packets = 20;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, options, c, error));
    REQUIRE(c.stream_info.size() == 1);
    const uint32_t info = c.stream_info[0];
    // Walk each chunk: after the base, point packets with the stream info after the 8th and 16th
    // (not after the 20th: the base follows).
    size_t pos = 0, repeats = 0;
    for (size_t chunk = 0; chunk < c.chunk_count; ++chunk) {
        for (size_t b = 0; b < c.base.size(); ++b, ++pos) CHECK_FALSE(c.cycle[pos].stream_info_repeat);
        size_t points = 0;
        while (pos < c.cycle.size() && !(c.cycle[pos].base && !c.cycle[pos].stream_info_repeat)) {
            if (c.cycle[pos].stream_info_repeat) {
                CHECK(c.cycle[pos].packet == info);
                CHECK(c.cycle[pos].base);
                CHECK(points % 8 == 0);
                ++repeats;
            } else {
                ++points;
            }
            ++pos;
        }
        CHECK(points <= 20);
    }
    CHECK(repeats == c.repeat_bytes / c.sizes[info]);
    CHECK(repeats >= 2 * (c.chunk_count - 1));
    // Between two copies of the stream info there are at most 8 point packets or one base.
    int64_t last = -1;
    size_t longest_gap = 0;
    for (size_t k = 0; k < 2 * c.cycle.size(); ++k) {
        if (c.packet_at(k) != info) continue;
        if (last >= 0) longest_gap = std::max(longest_gap, k - size_t(last));
        last = int64_t(k);
    }
    CHECK(longest_gap <= std::max<size_t>(9, c.base.size() + 8));

    options.stream_info_every = 0;
    Carousel without;
    REQUIRE(build_carousel(packets, options, without, error));
    CHECK(without.repeat_bytes == 0);
    CHECK(without.cycle.size() == without.chunk_count * without.base.size() + without.data.size());
    // The price: a little over one stream info per 8 point packets.
    CHECK(c.cycle_bytes - without.cycle_bytes == c.repeat_bytes);
    CHECK(double(c.repeat_bytes) < 0.02 * double(c.cycle_bytes));
}
