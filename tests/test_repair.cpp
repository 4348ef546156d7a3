// Repair packets (format 1.2, spec 17): the code, a receiver's recovery from any k symbols of a block,
// hostile POINTS_REPAIR packets, the carousel that interleaves them, and the command line.
#include "broadcast_support.h"

#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/reception.h>

#include <algorithm>
#include <numeric>
#include <random>

using namespace ellicast;
using namespace ellicast::broadcast;
using Packets = std::vector<std::vector<uint8_t>>;

namespace {

// A synthetic one-object stream (STREAM_INFO, ELLIPSOIDS, POINTS) and, after it, the POINTS_REPAIR
// packets of `ratio` repairs per source in blocks of at most `max_sources` POINTS packets.
struct RepairStream {
    Packets base, points, repairs;
    StreamInfo info;
    std::vector<QuantizedPoint> quantized;
    std::vector<RepairBlock> blocks;
};

RepairStream repair_stream(uint32_t points, size_t max_sources, double ratio, uint16_t packet_size = 600) {
    RepairStream s;
    Packets all = test::synthetic_stream(12, points, 0x5EED, packet_size);
    ReceivedStream whole;
    for (size_t i = 0; i < all.size(); ++i) REQUIRE(whole.add_packet(all[i], i) == Error::Ok);
    REQUIRE(whole.info());
    s.info = *whole.info();
    s.info.objects = {*whole.objects()[0].info};
    for (const auto& [index, q] : whole.objects()[0].points) s.quantized.push_back(q);
    REQUIRE(s.quantized.size() == points);
    for (auto& p : all) (is_points_type(p[6]) ? s.points : s.base).push_back(p);
    const size_t batch = points_per_packet(packet_size, s.info, s.info.objects[0]);
    s.blocks = plan_repair_blocks(points, uint16_t(batch), max_sources);
    for (const RepairBlock& b : s.blocks)
        REQUIRE(packetize_repairs(s.info, 0, s.quantized, {b}, size_t(std::ceil(ratio * b.source_count())), 0x5EED,
                                  1000, s.repairs) == Error::Ok);
    return s;
}

bool same_points(const ReceivedStream& stream, const std::vector<QuantizedPoint>& expected) {
    const auto& held = stream.objects()[0].points;
    if (held.size() != expected.size()) return false;
    for (const auto& [index, q] : held) {
        const QuantizedPoint& e = expected[index];
        if (q.position != e.position || q.normal != e.normal) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("GF(2^8) arithmetic is the spec's: the examples of section 17.2 and inverses") {
    CHECK(gf256_mul(0x02, 0x80) == 0x1D);
    CHECK(gf256_mul(0x53, 0xCA) == 0x8F);
    CHECK(gf256_inv(0x02) == 0x8E);
    CHECK(gf256_inv(0x03) == 0xF4);
    for (unsigned a = 1; a < 256; ++a) CHECK(gf256_mul(uint8_t(a), gf256_inv(uint8_t(a))) == 1);
    // Multiplication distributes over XOR (a field, not a table of chance values).
    std::mt19937 rng(1);
    for (int i = 0; i < 1000; ++i) {
        const uint8_t a = uint8_t(rng()), b = uint8_t(rng()), c = uint8_t(rng());
        CHECK(gf256_mul(a, b ^ c) == (gf256_mul(a, b) ^ gf256_mul(a, c)));
    }
}

TEST_CASE("the code is MDS: any k of a block's symbols give back its sources, k - 1 never do") {
    std::mt19937 rng(7);
    for (size_t k : {size_t(1), size_t(2), size_t(9), size_t(40)}) {
        CAPTURE(k);
        std::vector<std::vector<uint8_t>> sources(k, std::vector<uint8_t>(37));
        for (auto& s : sources)
            for (auto& b : s) b = uint8_t(rng());
        std::vector<std::vector<uint8_t>> all = sources;  // rows 0..2k-1
        for (unsigned r = unsigned(k); r < 2 * k; ++r) all.push_back(repair_symbol(sources, r));
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<size_t> order(2 * k);
            std::iota(order.begin(), order.end(), 0);
            std::shuffle(order.begin(), order.end(), rng);
            order.resize(k);  // any k symbols
            std::vector<std::vector<uint8_t>> known(k);
            std::vector<uint8_t> rows;
            std::vector<std::vector<uint8_t>> symbols;
            for (size_t s : order) {
                if (s < k) known[s] = all[s];
                else rows.push_back(uint8_t(s)), symbols.push_back(all[s]);
            }
            REQUIRE(recover_source_symbols(known, rows, symbols));
            CHECK(known == sources);
            // One symbol short: not enough rows for the unknowns.
            if (!rows.empty()) {
                std::vector<std::vector<uint8_t>> fewer(k);
                for (size_t s : order)
                    if (s < k) fewer[s] = all[s];
                rows.pop_back();
                symbols.pop_back();
                CHECK_FALSE(recover_source_symbols(fewer, rows, symbols));
            }
        }
    }
}

TEST_CASE("a receiver that holds any k packets of each block recovers every point, in any order, repairs held before the stream info") {
    const RepairStream s = repair_stream(3000, 20, 1.0);
    REQUIRE(s.blocks.size() >= 2);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 10; ++trial) {
        CAPTURE(trial);
        // Keep the base, and per block a random k of its 2k symbols; shuffle everything.
        Packets kept = s.base;
        std::vector<Packets> per_block(s.blocks.size());
        auto block_of = [&](uint32_t first) {
            for (size_t b = 0; b < s.blocks.size(); ++b)
                if (first >= s.blocks[b].first_index && first < s.blocks[b].first_index + s.blocks[b].point_count) return b;
            return size_t(0);
        };
        for (const auto& p : s.points) {
            PacketView v;
            REQUIRE(parse_packet(p, v) == Error::Ok);
            per_block[block_of(uint32_t(v.payload[0]) | uint32_t(v.payload[1]) << 8)].push_back(p);
        }
        for (const auto& p : s.repairs) {
            PacketView v;
            REQUIRE(parse_packet(p, v) == Error::Ok);
            per_block[block_of(uint32_t(v.payload[0]) | uint32_t(v.payload[1]) << 8)].push_back(p);
        }
        for (size_t b = 0; b < s.blocks.size(); ++b) {
            std::shuffle(per_block[b].begin(), per_block[b].end(), rng);
            per_block[b].resize(s.blocks[b].source_count());
            kept.insert(kept.end(), per_block[b].begin(), per_block[b].end());
        }
        std::shuffle(kept.begin(), kept.end(), rng);
        ReceivedStream stream;
        for (size_t i = 0; i < kept.size(); ++i) CHECK(stream.add_packet(kept[i], i) == Error::Ok);
        CHECK(stream.counters().rejected == 0);
        CHECK(same_points(stream, s.quantized));
        for (const auto& [first, block] : stream.objects()[0].repair_blocks) CHECK(block.complete);
        CHECK(stream.objects()[0].points_recovered > 0);
        CHECK(stream.objects()[0].points_recovered < 3000);
    }
    // One packet short in a block: nothing of its missing batches is recovered, nothing wrong is made.
    Packets kept = s.base;
    kept.insert(kept.end(), s.points.begin() + 1, s.points.end());  // the first POINTS packet lost, no repair
    ReceivedStream stream;
    for (size_t i = 0; i < kept.size(); ++i) stream.add_packet(kept[i], i);
    CHECK(stream.objects()[0].points.size() < 3000);
    CHECK(stream.objects()[0].points_recovered == 0);
}

TEST_CASE("hostile POINTS_REPAIR packets are rejected with the reason the spec gives") {
    const RepairStream s = repair_stream(600, 20, 1.0);
    REQUIRE(!s.repairs.empty());
    const auto& good = s.repairs[0];
    auto edited = [&](size_t at, uint8_t value, size_t at2 = 0, uint8_t value2 = 0) {
        auto p = good;
        p[kHeaderSize + at] = value;
        if (at2) p[kHeaderSize + at2] = value2;
        return test::resealed(p);
    };
    auto outcome = [&](const std::vector<uint8_t>& repair) {
        ReceivedStream stream;
        for (size_t i = 0; i < s.base.size(); ++i) stream.add_packet(s.base[i], i);
        return stream.add_packet(repair, 99);
    };
    CHECK(outcome(good) == Error::Ok);
    CHECK(outcome(edited(4, 0)) == Error::MalformedPayload);   // batch 0 (low byte; high byte is 0)
    CHECK(outcome(edited(6, 0)) == Error::MalformedPayload);   // source_count 0
    CHECK(outcome(edited(7, 0)) == Error::MalformedPayload);   // row below source_count
    CHECK(outcome(edited(7, 255)) == Error::MalformedPayload); // row past 254
    CHECK(outcome(edited(6, 250, 7, 251)) == Error::IndexOutOfRange);  // 250 batches: past the object's points
    {
        auto p = good;
        p.resize(p.size() - 5);  // symbol too short for the batch
        PacketView v;
        REQUIRE(parse_packet_prefix(p, v) != Error::Ok);  // the length field still says more: rebuild
        PacketHeader h;
        REQUIRE(parse_packet(good, v) == Error::Ok);
        h = v.header;
        std::vector<uint8_t> payload(v.payload.begin(), v.payload.end() - 1);
        CHECK(outcome(write_packet(h, payload)) == Error::MalformedPayload);
    }
    // A block that overlaps another with other parameters: stream mismatch.
    {
        ReceivedStream stream;
        for (size_t i = 0; i < s.base.size(); ++i) stream.add_packet(s.base[i], i);
        REQUIRE(stream.add_packet(good, 50) == Error::Ok);
        auto p = good;
        p[kHeaderSize + 0] = uint8_t(p[kHeaderSize + 0] + 1);  // first_index + 1: overlaps
        CHECK(stream.add_packet(test::resealed(p), 51) == Error::StreamMismatch);
    }
    // Held before the stream info, checked when it arrives.
    {
        ReceivedStream stream;
        CHECK(stream.add_packet(edited(6, 250, 7, 251), 0) == Error::Ok);  // held: its object's entry is unknown
        CHECK(stream.counters().pending == 1);
        for (size_t i = 0; i < s.base.size(); ++i) stream.add_packet(s.base[i], 1 + i);
        CHECK(stream.counters().rejected == 1);
        REQUIRE_FALSE(stream.rejections().empty());
        CHECK(stream.rejections().back().error == Error::IndexOutOfRange);
    }
}

TEST_CASE("a recording's repair packets are checked with each block's sources built once: repeats and every row "
          "keep their verdicts, a block the receiver did not take is left to its rejection (issue 29, row 5)") {
    const RepairStream s = repair_stream(600, 20, 1.0);
    ReceivedStream stream;
    uint64_t where = 0;
    for (const auto& p : s.base) stream.add_packet(p, where++);
    for (const auto& p : s.points) stream.add_packet(p, where++);
    for (const auto& p : s.repairs) stream.add_packet(p, where++);
    RepairPacketChecker checker(stream);
    std::string why;
    PacketView v;
    // Every row, each many times: all conform (checking each once rebuilt the block every time).
    for (int repeat = 0; repeat < 50; ++repeat)
        for (const auto& p : s.repairs) {
            REQUIRE(parse_packet(p, v) == Error::Ok);
            CHECK(checker.check(v, why) == Error::Ok);
        }
    // A forged symbol of a held block is still caught, after the same row was found right.
    auto forged = test::resealed([&] {
        auto f = s.repairs[0];
        f[kHeaderSize + 8 + 3] ^= 0x10;
        return f;
    }());
    REQUIRE(parse_packet(forged, v) == Error::Ok);
    CHECK(checker.check(v, why) == Error::StreamMismatch);
    CHECK(why.find("is not the repair symbol") != std::string::npos);
    CHECK(check_repair_packet(stream, v, why) == Error::StreamMismatch);  // alone, the same verdict
}

TEST_CASE("a forged repair symbol is caught by the validator check, and a signed stream would have rejected it") {
    const RepairStream s = repair_stream(600, 20, 1.0);
    ReceivedStream stream;
    uint64_t where = 0;
    for (const auto& p : s.base) stream.add_packet(p, where++);
    for (const auto& p : s.points) stream.add_packet(p, where++);
    auto forged = s.repairs[0];
    forged[kHeaderSize + 8 + 3] ^= 0x10;  // one bit of the symbol
    forged = test::resealed(forged);
    PacketView v;
    REQUIRE(parse_packet(forged, v) == Error::Ok);
    std::string why;
    CHECK(check_repair_packet(stream, v, why) == Error::StreamMismatch);
    CHECK(why.find("is not the repair symbol") != std::string::npos);
    REQUIRE(parse_packet(s.repairs[0], v) == Error::Ok);
    CHECK(check_repair_packet(stream, v, why) == Error::Ok);
}

TEST_CASE("the carousel interleaves each block's POINTS and repair packets, every symbol once a period") {
    const RepairStream s = repair_stream(6000, 40, 1.0, 1200);
    Packets packets = s.base;
    packets.insert(packets.end(), s.points.begin(), s.points.end());
    packets.insert(packets.end(), s.repairs.begin(), s.repairs.end());
    Carousel c;
    std::string error;
    REQUIRE(build_carousel(packets, CarouselOptions{}, c, error));
    CHECK(c.period_cycles == 2);
    REQUIRE(c.blocks.size() == s.blocks.size());
    // Every symbol of every block exactly once in the period; each cycle's data slots hold as many
    // POINTS as repair packets, give or take one per block.
    std::vector<size_t> sent(packets.size(), 0);
    for (const auto& e : c.cycle) ++sent[e.packet];
    for (const auto& b : c.blocks)
        for (uint32_t p : b.symbols) CHECK(sent[p] == 1);
    const size_t half = c.cycle.size() / 2;
    size_t points_first_cycle = 0, repairs_first_cycle = 0;
    for (size_t i = 0; i < half; ++i) {
        const uint8_t type = packets[c.cycle[i].packet][6];
        points_first_cycle += is_points_type(type);
        repairs_first_cycle += type == uint8_t(PacketType::PointsRepair);
    }
    CHECK(points_first_cycle + repairs_first_cycle == s.points.size());
    CHECK(std::abs(double(points_first_cycle) - double(repairs_first_cycle)) <= double(c.blocks.size()));
    // Without loss every point is held about one cycle after tune-in, and the stats say so.
    const CarouselStats stats = carousel_stats(c);
    CHECK(double(stats.worst_full_wait_bytes) < 1.2 * c.bytes_per_cycle());
}

TEST_CASE("under 50% loss a receiver holds every point after about two cycles with repair packets, far later without") {
    const RepairStream s = repair_stream(8000, 127, 1.0, 1200);
    Packets with = s.base, without = s.base;
    with.insert(with.end(), s.points.begin(), s.points.end());
    without.insert(without.end(), s.points.begin(), s.points.end());
    with.insert(with.end(), s.repairs.begin(), s.repairs.end());
    auto median_cycles = [&](const Packets& packets) {
        Carousel c;
        std::string error;
        REQUIRE(build_carousel(packets, CarouselOptions{}, c, error));
        std::mt19937_64 rng(5);
        std::vector<double> times;
        for (int trial = 0; trial < 21; ++trial) {
            Reception reception;
            const uint64_t start = rng() % c.cycle.size();
            uint64_t slot = start;
            for (; slot < start + 40 * c.cycle.size() && !reception.complete(); ++slot)
                if (rng() % 2) reception.take(carousel_packet(c, packets, slot));
            times.push_back(double(c.bytes_before(slot) - c.bytes_before(start)) / c.bytes_per_cycle());
        }
        std::sort(times.begin(), times.end());
        return times[times.size() / 2];
    };
    const double repaired = median_cycles(with), repeated = median_cycles(without);
    MESSAGE("every point held after " << repaired << " cycles with repair packets, " << repeated << " without (median of 21)");
    CHECK(repaired < 2.6);
    CHECK(repeated > 3.5);
}

TEST_CASE("command line: encode makes repair packets by default, --repair 0 none, validate flags a forged symbol") {
    const auto dir = test::scratch_dir("repair_cli");
    const std::string exe = test::shell_quoted(test::ellicast_exe().string());
    const std::string sample = (test::source_dir() / "samples" / "trefoil.obj").string();
    int status = 0;
    auto run = [&](const std::string& args) { return test::run_command(exe + " " + args, status); };
    const std::string with = (dir / "with.ellc").string(), without = (dir / "without.ellc").string();
    std::string out = run("encode -q '" + sample + "' -o '" + with + "'");
    REQUIRE(status == 0);
    CHECK(out.find("repair 0 (0 packets)") == std::string::npos);
    out = run("encode -q --repair 0 '" + sample + "' -o '" + without + "'");
    REQUIRE(status == 0);
    CHECK(out.find("repair 0 (0 packets)") != std::string::npos);
    run("validate '" + with + "'");
    CHECK(status == 0);
    run("encode -q --repair 5 '" + sample + "' -o '" + (dir / "x.ellc").string() + "'");
    CHECK(status == 2);
    // Flip one bit of the last packet's symbol (a POINTS_REPAIR) and reseal it.
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE(read_file(with, bytes, message) == Error::Ok);
    ContainerContents contents = read_container(bytes);
    const ContainerPacket& last = contents.packets.back();
    REQUIRE(last.view.header.type == uint8_t(PacketType::PointsRepair));
    std::vector<uint8_t> packet(bytes.begin() + std::ptrdiff_t(last.offset),
                                bytes.begin() + std::ptrdiff_t(last.offset + last.view.size));
    packet[kHeaderSize + 8] ^= 1;
    packet = test::resealed(packet);
    std::copy(packet.begin(), packet.end(), bytes.begin() + std::ptrdiff_t(last.offset));
    const std::string forged = (dir / "forged.ellc").string();
    REQUIRE(write_file(forged, bytes, message) == Error::Ok);
    out = run("validate '" + forged + "'");
    CHECK(status == 1);
    CHECK(out.find("is not the repair symbol") != std::string::npos);
}
