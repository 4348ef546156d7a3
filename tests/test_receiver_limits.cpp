// What a receiver does with streams that would otherwise hold memory forever or overflow.
#include "support.h"

#include "ellicast/format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

using namespace ellicast;

namespace {

StreamInfo one_object_stream() {
    StreamInfo info;
    ObjectInfo o;
    o.frame = {{0, 0, 0}, 1};
    o.point_count = 10;
    info.objects.push_back(o);
    return info;
}

// The packets of a one-object stream of 10 points (stream id 3).
StreamPackets one_object_packets() {
    std::vector<ObjectContent> contents(1);
    contents[0].points.resize(10);
    StreamPackets packets;
    REQUIRE(packetize_stream(one_object_stream(), contents, 3, packets) == Error::Ok);
    return packets;
}

}  // namespace

TEST_CASE("packets held for an object the stream turns out not to have are rejected when its info arrives") {
    const StreamPackets packets = one_object_packets();
    // A POINTS packet of object 0 re-addressed to object 5: valid on its own, held without stream info.
    PacketView view;
    REQUIRE(parse_packet(packets.points[0], view) == Error::Ok);
    PacketHeader h = view.header;
    h.object_id = 5;
    auto stray = write_packet(h, view.payload);
    ReceivedStream rs;
    REQUIRE(rs.add_packet(stray, 0) == Error::Ok);
    CHECK(rs.counters().pending == 1);
    REQUIRE(rs.add_packet(packets.stream_info[0], 1) == Error::Ok);
    CHECK(rs.counters().pending == 0);
    REQUIRE(rs.rejections().size() == 1);
    CHECK(rs.rejections()[0].error == Error::UnknownObject);
    CHECK(rs.rejections()[0].where == 0);
}

TEST_CASE("a frame whose far corner overflows single precision is refused") {
    StreamInfo info = one_object_stream();
    info.objects[0].frame = {{3e38f, 0, 0}, 3e38f};
    CHECK(check_stream_info(info) == Error::MalformedPayload);
    info.objects[0].frame = {{-3e38f, 0, 0}, 3e38f};  // ends at 0: fine
    CHECK(check_stream_info(info) == Error::Ok);
    info.objects[0].attributes = kAttrTexcoord;
    info.objects[0].texcoord_origin = {3e38f, 0};
    info.objects[0].texcoord_scale = {3e38f, 1};
    CHECK(check_stream_info(info) == Error::MalformedPayload);
}

TEST_CASE("every packet held before the stream info counts toward the hold, empty ones too, and the hold is released in one pass") {
    const StreamPackets packets = one_object_packets();
    PacketView view;
    REQUIRE(parse_packet(packets.points[0], view) == Error::Ok);
    PacketHeader empty_header = view.header;
    empty_header.payload_length = 0;
    const auto empty = write_packet(empty_header, {});  // a POINTS packet with a 0-byte payload

    // 10 packets' worth of bookkeeping: the 11th empty packet does not fit.
    ReceivedStream::Limits small;
    small.max_pending_bytes = 10 * kHeldPacketCost;
    ReceivedStream few(small);
    for (int i = 0; i < 10; ++i) REQUIRE(few.add_packet(empty, uint64_t(i)) == Error::Ok);
    CHECK(few.add_packet(empty, 10) == Error::NoStreamInfo);
    CHECK(few.counters().pending == 10);

    // A flood of 200,000 held packets: at most the packet cap is held, the rest rejected; when the
    // stream info comes, every held packet is decoded (the empty ones rejected as malformed) at once.
    ReceivedStream flood;
    const size_t cap = ReceivedStream::Limits{}.max_pending_packets;
    size_t refused = 0;
    for (uint64_t i = 0; i < 200'000; ++i) {
        const bool real = i % 1000 == 0;
        refused += flood.add_packet(real ? packets.points[0] : empty, i) == Error::NoStreamInfo;
    }
    CHECK(flood.counters().pending == cap);
    CHECK(refused == 200'000 - cap);
    REQUIRE(flood.add_packet(packets.stream_info[0], 200'000) == Error::Ok);
    CHECK(flood.counters().pending == 0);
    REQUIRE(flood.objects().size() == 1);
    CHECK(flood.objects()[0].points.size() == 10);  // the real packets among the held ones
}

TEST_CASE("a receiver holds NORMALS entries in memory near their bytes: a bit for an entry left to the surface") {
    // Issue 29, row 3: 1 MB of NORMALS entries at one bit a point held a map node (64 bytes) a point,
    // 509 MB. Two million points, every entry left to the surface, then every other one sent.
    const uint32_t n = 2'000'000;
    for (const bool some_sent : {false, true}) {
        CAPTURE(some_sent);
        StreamInfo info;
        ObjectInfo o;
        o.frame = {{0, 0, 0}, 1};
        o.point_count = n;
        o.exact_layer = true;
        o.surface_normals = true;
        info.objects.push_back(o);
        std::vector<ObjectContent> contents(1);
        contents[0].points.resize(n);
        contents[0].normals.resize(n);
        if (some_sent)
            for (uint32_t i = 0; i < n; i += 2) contents[0].normals[i] = {true, {i % 1024, (i / 1024) % 1024}};
        StreamPackets packets;
        REQUIRE(packetize_stream(info, contents, 3, packets) == Error::Ok);
        ReceivedStream rx;
        uint64_t taken = 0;
        for (const auto& p : packets.stream_info) REQUIRE(rx.add_packet(p, 0) == Error::Ok);
        for (const auto& p : packets.normals) {
            REQUIRE(rx.add_packet(p, 1) == Error::Ok);
            taken += p.size();
        }
        const ReceivedObject& got = rx.objects()[0];
        REQUIRE(got.normals_complete());
        const uint64_t held = got.normal_entries.memory();
        MESSAGE(packets.normals.size() << " NORMALS packets, " << taken << " bytes taken, entries held in " << held
                                       << " bytes (" << double(held) / double(taken) << "x)");
        CHECK(held <= 4 * taken);
        // What is held reads back: every entry, in index order.
        uint32_t expected = 0;
        bool same = true;
        for (const auto& [index, entry] : got.normal_entries) {
            same = same && index == expected && entry == contents[0].normals[index];
            ++expected;
        }
        CHECK(same);
        CHECK(expected == n);
        // The same packets again change nothing; an entry that contradicts one held is refused.
        REQUIRE(rx.add_packet(packets.normals[3], 2) == Error::Ok);
        CHECK(rx.counters().duplicates == 1);
        CHECK(got.normal_entries.memory() == held);
    }
}

TEST_CASE("paged records keep one record per index in index order, whatever order they arrive in") {
    PagedRecords<uint16_t> records(3);
    const std::vector<uint32_t> order = {70000, 5, 511, 512, 0, 1023, 4'000'000'000u, 6, 513};
    for (uint32_t i : order) {
        const std::array<uint16_t, 3> r = {uint16_t(i), uint16_t(i >> 16), 7};
        CHECK(records.insert(i, r.data()));
    }
    const std::array<uint16_t, 3> other = {1, 2, 3};
    CHECK(!records.insert(511, other.data()));  // the first copy is kept
    CHECK(records.size() == order.size());
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<uint32_t> seen;
    for (const auto& [index, r] : records) {
        seen.push_back(index);
        CHECK(r[0] == uint16_t(index));
        CHECK(r[1] == uint16_t(index >> 16));
    }
    CHECK(seen == sorted);
    CHECK((*records.lower_bound(7)).first == 511);
    CHECK((*records.lower_bound(512)).first == 512);
    CHECK((*records.lower_bound(514)).first == 1023);
    CHECK(records.lower_bound(4'000'000'001u) == records.end());
    CHECK(records.find(4) == nullptr);
    // Counts over ranges, against the indices themselves: within a page, across pages, past the last
    // index a uint32 holds, empty and reversed ranges.
    const std::vector<std::pair<uint64_t, uint64_t>> ranges = {
        {0, 1}, {0, 7}, {5, 512}, {6, 513}, {511, 1024}, {0, 70001}, {1024, 70000}, {0, uint64_t(1) << 33},
        {4'000'000'000u, 4'000'000'001u}, {7, 7}, {9, 3}};
    for (const auto& [from, to] : ranges) {
        const size_t expected = size_t(std::count_if(order.begin(), order.end(), [&](uint32_t i) { return i >= from && i < to; }));
        CHECK(records.count(from, to) == expected);
    }
    REQUIRE(records.find(513) != nullptr);
    CHECK(records.find(513)[0] == 513);
    const uint64_t memory = records.memory();
    CHECK(memory > 0);
    CHECK(records.erase(512));
    CHECK(!records.erase(512));
    CHECK(records.find(513)[0] == 513);
    for (uint32_t i : order) records.erase(i);
    CHECK(records.empty());
    CHECK(records.memory() == 0);
    CHECK(records.begin() == records.end());

    // Quantized points keep the components their object carries, and read back whole.
    ObjectInfo o;
    o.attributes = kAttrTexcoord | kAttrColor;
    PointRecords points;
    points.set_layout(o);
    QuantizedPoint q;
    q.position = {65535, 1, 2};
    q.texcoord = {4095, 17};
    q.color = {255, 0, 128, 0};
    CHECK(points.insert(9, q));
    REQUIRE(points.find(9));
    CHECK(points.find(9)->position == q.position);
    CHECK(points.find(9)->texcoord == q.texcoord);
    CHECK(points.find(9)->color == q.color);
    CHECK(points.find(9)->normal == std::array<uint32_t, 2>{0, 0});
    CHECK(!points.find(10));
    CHECK_THROWS_AS(points.at(10), std::out_of_range);
}

TEST_CASE("a receiver holds points in memory near their bytes, and refuses a packet once over its byte budget") {
    // Issue 29, row 3: 4 MB of mapped records held unplaced took 1.64 GB (a std::map node each).
    // Two million mapped records whose map never arrives, all held unplaced.
    const uint32_t n = 2'000'000;
    StreamInfo info;
    ObjectInfo o;
    o.frame = {{0, 0, 0}, 1};
    o.point_count = n;
    o.map_level = 7;
    o.map_batch = 4096;
    info.objects.push_back(o);
    std::vector<ObjectContent> contents(1);
    contents[0].points.resize(n);
    for (uint32_t i = 0; i < n; ++i) contents[0].points[i].position = {i % 128, (i / 128) % 128, 5};
    StreamPackets packets;
    REQUIRE(packetize_stream(info, contents, 3, packets) == Error::Ok);
    ReceivedStream rx;
    uint64_t taken = 0;
    for (const auto& p : packets.stream_info) REQUIRE(rx.add_packet(p, 0) == Error::Ok);
    for (const auto& p : packets.points) {
        REQUIRE(rx.add_packet(p, 1) == Error::Ok);
        taken += p.size();
    }
    const ReceivedObject& got = rx.objects()[0];
    REQUIRE(got.unplaced.size() == n);
    const uint64_t held = got.unplaced.memory();
    MESSAGE(packets.points.size() << " MAPPED_POINTS packets, " << taken << " bytes taken, records held in " << held
                                  << " bytes (" << double(held) / double(taken) << "x)");
    CHECK(held <= 3 * taken);
    CHECK(rx.held_memory() == got.memory());
    CHECK(rx.held_memory() < rx.memory_budget());
    uint32_t expected = 0;
    bool same = true;
    for (const auto& [index, q] : got.unplaced) same = same && index == expected++ && q.position == contents[0].points[index].position;
    CHECK(same);

    // A receiver with a small budget refuses packets once its objects hold more than it, with a
    // message that says so, and takes them again when more bytes have arrived... never past one
    // packet's worth over.
    ReceivedStream::Limits small;
    small.memory_base = 256 << 10;
    small.memory_per_byte = 1;
    ReceivedStream tight(small);
    for (const auto& p : packets.stream_info) REQUIRE(tight.add_packet(p, 0) == Error::Ok);
    size_t refused = 0;
    for (const auto& p : packets.points) {
        if (tight.add_packet(p, 1) != Error::Ok) ++refused;
        CHECK(tight.held_memory() <= tight.memory_budget() + 64 * 1024);
    }
    REQUIRE(refused > 0);
    CHECK(tight.rejections().back().detail.find("over this receiver's budget") != std::string::npos);
    MESSAGE("budget " << tight.memory_budget() << " bytes: " << refused << " of " << packets.points.size()
                      << " packets refused, " << tight.held_memory() << " bytes held");
}
