// Channel simulation: loss models, reproducible traces, trace files, and the CRC turning bit
// errors into losses.
#include "broadcast_support.h"
#include "support.h"

#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/channel.h>
#include <ellicast/broadcast/reception.h>

#include <cmath>
#include <fstream>
#include <map>

using namespace ellicast;
using namespace ellicast::broadcast;

namespace {

LossTrace draw(const ChannelModel& m, uint64_t slots, size_t bytes = 1200) {
    LossTrace t;
    std::string error;
    REQUIRE(generate_trace(m, slots, bytes, t, error));
    return t;
}

bool same_trace(const LossTrace& a, const LossTrace& b) {
    if (a.slots() != b.slots()) return false;
    for (uint64_t k = 0; k < a.slots(); ++k) {
        SlotFate x = a.fate(k), y = b.fate(k);
        if (x.lost != y.lost || x.duplicated != y.duplicated || x.delay != y.delay || x.flipped_bits != y.flipped_bits)
            return false;
    }
    return true;
}

}  // namespace

TEST_CASE("independent loss drops about the given share of packets") {
    ChannelModel m;
    m.loss = 0.2;
    m.seed = 11;
    LossTrace t = draw(m, 100000);
    double rate = double(t.lost_count()) / 100000.0;
    CHECK(rate == doctest::Approx(0.2).epsilon(0.05));
    CHECK(t.corrupted_count() == 0);
    CHECK(t.duplicated_count() == 0);
}

TEST_CASE("the same seed gives the same trace, another seed another") {
    ChannelModel m;
    m.loss = 0.1;
    m.reorder = 0.05;
    m.reorder_window = 4;
    m.duplicate = 0.02;
    m.bit_error_rate = 1e-5;
    m.seed = 42;
    CHECK(same_trace(draw(m, 20000), draw(m, 20000)));
    ChannelModel other = m;
    other.seed = 43;
    CHECK_FALSE(same_trace(draw(m, 20000), draw(other, 20000)));
}

TEST_CASE("turning on duplication does not change which packets are lost") {
    ChannelModel m;
    m.loss = 0.3;
    m.seed = 5;
    LossTrace a = draw(m, 5000);
    m.duplicate = 0.2;
    LossTrace b = draw(m, 5000);
    for (uint64_t k = 0; k < 5000; ++k) CHECK(a.lost(k) == b.lost(k));
    CHECK(b.duplicated_count() > 0);
}

TEST_CASE("Gilbert-Elliott loss comes in bursts of the given mean length at the given mean rate") {
    ChannelModel m = ChannelModel::gilbert(0.1, 8, 3);
    CHECK(m.mean_loss() == doctest::Approx(0.1));
    LossTrace t = draw(m, 400000);
    double rate = double(t.lost_count()) / 400000.0;
    CHECK(rate == doctest::Approx(0.1).epsilon(0.15));
    uint64_t bursts = 0, in_burst = 0;
    for (uint64_t k = 0; k < t.slots(); ++k) {
        if (t.lost(k)) {
            ++in_burst;
            if (k == 0 || !t.lost(k - 1)) ++bursts;
        }
    }
    double mean_burst = double(in_burst) / double(bursts);
    CHECK(mean_burst == doctest::Approx(8).epsilon(0.15));
    // Independent loss at the same rate has bursts of about 1 / (1 - p).
    ChannelModel independent;
    independent.loss = 0.1;
    LossTrace u = draw(independent, 400000);
    uint64_t ubursts = 0;
    for (uint64_t k = 0; k < u.slots(); ++k)
        if (u.lost(k) && (k == 0 || !u.lost(k - 1))) ++ubursts;
    CHECK(double(u.lost_count()) / double(ubursts) < 1.3);
}

TEST_CASE("reordering keeps packets within the window and duplication delivers twice") {
    ChannelModel m;
    m.reorder = 0.3;
    m.reorder_window = 5;
    m.duplicate = 0.1;
    m.seed = 9;
    LossTrace t = draw(m, 3000);
    auto order = arrival_order(t, 3000);
    CHECK(order.size() == 3000 + t.duplicated_count());
    std::map<uint64_t, int> copies;
    bool any_out_of_order = false;
    for (size_t i = 0; i < order.size(); ++i) {
        copies[order[i].slot]++;
        // A packet arrives no earlier than... its position differs from its slot by at most
        // the window plus the duplicates before it.
        if (i > 0 && order[i].slot < order[i - 1].slot) any_out_of_order = true;
    }
    CHECK(any_out_of_order);
    for (uint64_t k = 0; k < 3000; ++k) CHECK(copies[k] == (t.fate(k).duplicated ? 2 : 1));
    // Every packet arrives before the packets sent more than `window` slots after it.
    std::map<uint64_t, size_t> first_position;
    for (size_t i = 0; i < order.size(); ++i) first_position.emplace(order[i].slot, i);
    for (uint64_t k = 0; k + 6 < 3000; ++k) CHECK(first_position[k] < first_position[k + 6]);
}

TEST_CASE("every packet the channel corrupts with bit errors is rejected by the CRC") {
    auto packets = test::synthetic_stream(100, 4000);
    ChannelModel m;
    m.bit_error_rate = 2e-5;
    m.seed = 77;
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, CarouselOptions{}, c, error));
    const uint64_t slots = 4 * c.cycle.size();
    std::vector<std::vector<uint8_t>> sent;
    for (uint64_t k = 0; k < slots; ++k) sent.push_back(carousel_packet(c, packets, k));
    LossTrace t = draw(m, slots, 1200);
    REQUIRE(t.corrupted_count() > 10);
    Reception reception;
    for (const Arrival& a : arrival_order(t, slots)) {
        auto bytes = a.corrupted ? damage_packet(t, a.slot, sent[a.slot]) : sent[a.slot];
        Error e = reception.take(bytes);
        if (a.corrupted)
            CHECK(e != Error::Ok);
        else
            CHECK(e == Error::Ok);
    }
    CHECK(reception.counters().damaged + reception.counters().not_ellicast + reception.counters().invalid ==
          t.corrupted_count());
    CHECK(reception.complete());  // four cycles at this error rate: everything got through
}

TEST_CASE("a trace written to a file reads back identical and applies to another stream") {
    ChannelModel m;
    m.loss = 0.15;
    m.reorder = 0.05;
    m.reorder_window = 3;
    m.duplicate = 0.05;
    m.bit_error_rate = 1e-5;
    m.seed = 1234;
    LossTrace t = draw(m, 5000);
    auto dir = test::scratch_dir("channel-trace");
    std::string error;
    REQUIRE(write_trace((dir / "t.trace").string(), t, error));
    LossTrace back;
    REQUIRE(read_trace((dir / "t.trace").string(), back, error));
    CHECK(same_trace(t, back));
    CHECK(back.packet_bytes() == 1200);
    CHECK(back.description() == t.description());
    CHECK(back.description().find("seed=1234") != std::string::npos);
    // Applied to two different packet sequences of the same length, the same slots go missing.
    std::vector<std::vector<uint8_t>> a, b;
    for (uint32_t k = 0; k < 5000; ++k) {
        a.push_back(std::vector<uint8_t>(1200, uint8_t(k)));
        b.push_back(std::vector<uint8_t>(1200, uint8_t(k * 7 + 1)));
    }
    auto ra = apply_trace(back, a), rb = apply_trace(back, b);
    CHECK(ra.size() == rb.size());
    CHECK(ra.size() == 5000 - t.lost_count() + t.duplicated_count());
}

TEST_CASE("a damaged trace file is refused with the line that is wrong") {
    auto dir = test::scratch_dir("channel-bad-trace");
    auto write = [&](const std::string& text) {
        std::ofstream((dir / "bad.trace").string()) << text;
        LossTrace t;
        std::string error;
        bool ok = read_trace((dir / "bad.trace").string(), t, error);
        return std::make_pair(ok, error);
    };
    auto [ok1, e1] = write("not a trace\n");
    CHECK_FALSE(ok1);
    CHECK(e1.find(":1:") != std::string::npos);
    auto [ok2, e2] = write("ellicast-loss-trace 1\nslots 10\npacket_bytes 1200\n12 lost\n");
    CHECK_FALSE(ok2);
    CHECK(e2.find(":4:") != std::string::npos);
    CHECK(e2.find("beyond") != std::string::npos);
    auto [ok3, e3] = write("ellicast-loss-trace 1\nslots 10\npacket_bytes 1200\n3 vanish\n");
    CHECK_FALSE(ok3);
    CHECK(e3.find("unknown fate") != std::string::npos);
    auto [ok4, e4] = write("ellicast-loss-trace 1\nslots 99999999999\npacket_bytes 1200\n");
    CHECK_FALSE(ok4);
    CHECK(e4.find("cap") != std::string::npos);
}

TEST_CASE("an impossible channel model is refused with what is wrong") {
    LossTrace t;
    std::string error;
    ChannelModel m;
    m.loss = 1.5;
    CHECK_FALSE(generate_trace(m, 10, 1200, t, error));
    CHECK(error.find("loss") != std::string::npos);
    m = ChannelModel{};
    m.reorder = 0.1;
    CHECK_FALSE(generate_trace(m, 10, 1200, t, error));
    CHECK(error.find("window") != std::string::npos);
    m = ChannelModel{};
    CHECK_FALSE(generate_trace(m, kMaxTraceSlots + 1, 1200, t, error));
}

TEST_CASE("ellicast simulate gives the same losses for the same seed and for the trace it wrote") {
    auto dir = test::scratch_dir("simulate-cli");
    auto packets = test::synthetic_stream(200, 8000);
    test::write_stream_file(dir / "in.ellc", packets);
    auto simulate = [&](const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> args = {"simulate", (dir / "in.ellc").string(), "-o", (dir / out).string(),
                                         "--cycles", "1.5", "--tune-in", "17"};
        args.insert(args.end(), extra.begin(), extra.end());
        return test::run_ellicast(args, dir / (out + ".log"));
    };
    REQUIRE(simulate("a.ellc", {"--loss", "0.2", "--burst", "4", "--duplicate", "0.05", "--reorder", "0.1",
                                "--bit-errors", "1e-5", "--seed", "99", "--trace-out", (dir / "t.trace").string()}) == 0);
    REQUIRE(simulate("b.ellc", {"--loss", "0.2", "--burst", "4", "--duplicate", "0.05", "--reorder", "0.1",
                                "--bit-errors", "1e-5", "--seed", "99"}) == 0);
    REQUIRE(simulate("c.ellc", {"--trace-in", (dir / "t.trace").string()}) == 0);
    REQUIRE(simulate("d.ellc", {"--loss", "0.2", "--burst", "4", "--seed", "100"}) == 0);
    auto a = test::read_stream_file(dir / "a.ellc");  // also checks: no damaged packet was written
    CHECK(a == test::read_stream_file(dir / "b.ellc"));
    CHECK(a == test::read_stream_file(dir / "c.ellc"));
    CHECK(a != test::read_stream_file(dir / "d.ellc"));
    std::string log = test::read_text(dir / "a.ellc.log");
    CHECK(log.find("base complete") != std::string::npos);
    CHECK(log.find("estimated loss") != std::string::npos);
    // The expected base wait is at the channel's rate, not at what this short run happened to lose;
    // from a recorded trace, at what the trace lost.
    CHECK(log.find("expected at the channel's 20.0% loss") != std::string::npos);
    CHECK(test::read_text(dir / "c.ellc.log").find("expected at the trace's ") != std::string::npos);
    // Without loss, one cycle from slot 0 is exactly the schedule.
    REQUIRE(simulate("clean.ellc", {"--tune-in", "0", "--cycles", "1"}) != 0);  // --tune-in given twice
    REQUIRE(test::run_ellicast({"simulate", (dir / "in.ellc").string(), "-o", (dir / "clean.ellc").string()},
                               dir / "clean.log") == 0);
    REQUIRE(test::run_ellicast({"schedule", (dir / "in.ellc").string(), "-o", (dir / "cycle.ellc").string()},
                               dir / "cycle.log") == 0);
    CHECK(test::read_stream_file(dir / "clean.ellc") == test::read_stream_file(dir / "cycle.ellc"));
    // Absurd options are refused.
    CHECK(test::run_ellicast({"simulate", (dir / "in.ellc").string(), "-o", (dir / "x.ellc").string(), "--loss", "2"},
                             dir / "x.log") == 2);
    CHECK(test::run_ellicast({"simulate", (dir / "in.ellc").string(), "-o", (dir / "x.ellc").string(), "--cycles",
                              "900000"},
                             dir / "y.log") == 2);
}

TEST_CASE("mutated and random datagrams never crash a receiver, are all counted, and the stream still completes") {
    auto packets = test::synthetic_stream(60, 1500, 0x9999);
    std::mt19937_64 rng(17);
    Reception reception;
    uint64_t sent = 0;
    // First the stream info, so the receiver locks on this stream; then hostile traffic.
    REQUIRE(reception.take(packets[0]) == Error::Ok);
    ++sent;
    for (int i = 0; i < 20000; ++i) {
        std::vector<uint8_t> bytes;
        switch (i % 4) {
            case 0: {  // a valid packet with a few flipped bits
                bytes = packets[rng() % packets.size()];
                for (int k = 0, n = 1 + int(rng() % 4); k < n; ++k) bytes[rng() % bytes.size()] ^= uint8_t(1u << (rng() % 8));
                break;
            }
            case 1: {  // a valid packet cut short or extended
                bytes = packets[rng() % packets.size()];
                bytes.resize(rng() % (bytes.size() + 40));
                break;
            }
            case 2: {  // random bytes behind a valid magic
                bytes.resize(rng() % 1400);
                for (auto& b : bytes) b = uint8_t(rng());
                if (bytes.size() >= 4) std::copy(kPacketMagic.begin(), kPacketMagic.end(), bytes.begin());
                break;
            }
            default: {  // random bytes
                bytes.resize(rng() % 2000);
                for (auto& b : bytes) b = uint8_t(rng());
                break;
            }
        }
        reception.take(bytes);
        ++sent;
    }
    for (const auto& p : packets) reception.take(p), ++sent;
    const auto& c = reception.counters();
    CHECK(c.datagrams == sent);
    CHECK(c.accepted + c.duplicates + c.rejected() == sent);
    CHECK(c.rejected() > 15000);
    CHECK(reception.complete());
    CHECK(reception.points_received() == 1500);
}
