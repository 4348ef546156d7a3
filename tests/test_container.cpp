// Container files (.ellc, spec/format.md section 10): truncation at every byte offset loses only the
// packets it cuts, damage anywhere loses only the packets it hits, the reader resynchronizes on the
// next intact packet, and files are written atomically.
#include "support.h"

#include <ellicast/format.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

using namespace ellicast;

namespace {

using Packet = std::vector<uint8_t>;

// A stream of small packets of every type (packet size 128): about 40 packets.
std::vector<Packet> small_stream() {
    StreamInfo info;
    info.packet_size = 128;
    ObjectInfo a, b;
    a.frame = {{0, 0, 0}, 1};
    a.ellipsoid_count = 30;
    a.point_count = 200;
    a.attributes = kAttrNormal;
    b.frame = {{5, 5, 5}, 2};
    b.point_count = 40;
    b.kind = ObjectKind::PointSet;
    b.attributes = kAttrColor;
    info.objects = {a, b};
    std::mt19937 rng(1);
    std::vector<ObjectContent> contents(2);
    for (uint32_t i = 0; i < a.ellipsoid_count; ++i) {
        QuantizedEllipsoid q;
        q.center = {uint16_t(rng() % 32768), uint16_t(rng() % 32768), uint16_t(rng() % 32768)};
        q.radii = {uint16_t(rng() % 8192), uint16_t(rng() % 8192), uint16_t(rng() % 8192)};
        contents[0].ellipsoids.push_back(q);
    }
    for (uint32_t i = 0; i < a.point_count; ++i) {
        QuantizedPoint q;
        q.position = {uint32_t(rng() % 16384), uint32_t(rng() % 16384), uint32_t(rng() % 16384)};
        q.normal = {uint32_t(rng() % 1024), uint32_t(rng() % 1024)};
        contents[0].points.push_back(q);
    }
    for (uint32_t i = 0; i < b.point_count; ++i) {
        QuantizedPoint q;
        q.position = {uint32_t(rng() % 16384), uint32_t(rng() % 16384), uint32_t(rng() % 16384)};
        q.color = {uint32_t(rng() % 256), uint32_t(rng() % 256), uint32_t(rng() % 256), 0};
        contents[1].points.push_back(q);
    }
    StreamPackets packets;
    REQUIRE(packetize_stream(info, contents, 7, packets) == Error::Ok);
    std::vector<Packet> all = packets.stream_info;
    all.insert(all.end(), packets.ellipsoids.begin(), packets.ellipsoids.end());
    all.insert(all.end(), packets.points.begin(), packets.points.end());
    return all;
}

std::vector<uint64_t> packet_offsets(const std::vector<Packet>& packets) {
    std::vector<uint64_t> offsets;
    uint64_t at = kContainerHeaderSize;
    for (const Packet& p : packets) {
        offsets.push_back(at);
        at += p.size();
    }
    return offsets;
}

std::vector<uint64_t> offsets_read(const ContainerContents& c) {
    std::vector<uint64_t> out;
    for (const auto& p : c.packets) out.push_back(p.offset);
    return out;
}

}  // namespace

TEST_CASE("a container is its 12-byte header and the packets back to back") {
    auto packets = small_stream();
    auto bytes = write_container(packets);
    const std::vector<uint8_t> header = {0x89, 0x45, 0x4C, 0x43, 0x0D, 0x0A, 0x1A, 0x0A, 1, 0, 0, 0};
    REQUIRE(bytes.size() > header.size());
    CHECK(std::equal(header.begin(), header.end(), bytes.begin()));
    ContainerContents c = read_container(bytes);
    CHECK(c.header_error == Error::Ok);
    CHECK(c.damaged.empty());
    REQUIRE(c.packets.size() == packets.size());
    CHECK(offsets_read(c) == packet_offsets(packets));
    for (size_t i = 0; i < packets.size(); ++i) CHECK(c.packets[i].view.size == packets[i].size());
    // An empty recording is valid.
    ContainerContents empty = read_container(write_container({}));
    CHECK(empty.header_error == Error::Ok);
    CHECK(empty.packets.empty());
    CHECK(empty.damaged.empty());
}

TEST_CASE("a container header that is not ellicast's is refused and nothing is read") {
    auto bytes = write_container(small_stream());
    for (size_t n = 0; n < kContainerHeaderSize; ++n) {
        ContainerContents c = read_container(std::span<const uint8_t>(bytes.data(), n));
        CAPTURE(n);
        CHECK(c.header_error == (n >= 8 ? Error::TooShort : Error::BadSignature));
        CHECK(c.packets.empty());
    }
    for (size_t i = 0; i < 8; ++i) {
        auto bad = bytes;
        bad[i] ^= 0x20;
        CHECK(read_container(bad).header_error == Error::BadSignature);
    }
    auto v2 = bytes;
    v2[8] = 2;
    CHECK(read_container(v2).header_error == Error::UnsupportedContainer);
    auto reserved = bytes;
    reserved[9] = reserved[10] = reserved[11] = 0xFF;  // reserved: ignored when reading
    CHECK(read_container(reserved).packets.size() == small_stream().size());
}

TEST_CASE("truncation at every byte offset of a container file loses only the packets it cuts") {
    auto packets = small_stream();
    auto bytes = write_container(packets);
    auto offsets = packet_offsets(packets);
    REQUIRE(packets.size() >= 20);
    for (size_t n = kContainerHeaderSize; n <= bytes.size(); ++n) {
        ContainerContents c = read_container(std::span<const uint8_t>(bytes.data(), n));
        // The packets that end at or before the cut are all there, intact, at their offsets.
        std::vector<uint64_t> expected;
        uint64_t cut_start = n;
        for (size_t i = 0; i < packets.size(); ++i) {
            if (offsets[i] + packets[i].size() <= n) expected.push_back(offsets[i]);
            else if (offsets[i] < n) cut_start = offsets[i];
        }
        CAPTURE(n);
        REQUIRE(c.header_error == Error::Ok);
        CHECK(offsets_read(c) == expected);
        if (cut_start < n) {
            // The cut packet's bytes are one damaged region up to the end.
            REQUIRE(c.damaged.size() == 1);
            CHECK(c.damaged[0].offset == cut_start);
            CHECK(c.damaged[0].length == n - cut_start);
            CHECK((c.damaged[0].first_error == (n - cut_start < kPacketOverhead ? Error::TooShort : Error::Truncated)));
        } else {
            CHECK(c.damaged.empty());
        }
    }
}

TEST_CASE("damage anywhere in a container loses only the packets it hits, and every packet after it is kept") {
    auto packets = small_stream();
    auto bytes = write_container(packets);
    auto offsets = packet_offsets(packets);
    // One corrupted byte at every offset of the packet area: exactly the packet holding it is lost.
    for (size_t at = kContainerHeaderSize; at < bytes.size(); ++at) {
        auto damaged = bytes;
        damaged[at] ^= 0x5A;
        ContainerContents c = read_container(damaged);
        size_t hit = 0;
        while (!(offsets[hit] <= at && at < offsets[hit] + packets[hit].size())) ++hit;
        std::vector<uint64_t> expected;
        for (size_t i = 0; i < packets.size(); ++i)
            if (i != hit) expected.push_back(offsets[i]);
        CAPTURE(at);
        CHECK(offsets_read(c) == expected);
        REQUIRE(c.damaged.size() == 1);
        CHECK(c.damaged[0].offset == offsets[hit]);
        CHECK(c.damaged[0].length == packets[hit].size());
    }
}

TEST_CASE("the reader resynchronizes after inserted garbage, false packet starts and cut-off packets") {
    auto packets = small_stream();
    std::mt19937 rng(5);
    std::vector<uint8_t> bytes = write_container({});
    std::vector<uint64_t> expected;
    size_t garbage_regions = 0;
    for (size_t i = 0; i < packets.size(); ++i) {
        if (i % 5 == 2) {
            // Noise with stray magic bytes and a packet header that lies about its length.
            std::vector<uint8_t> noise(17 + rng() % 50);
            for (auto& b : noise) b = uint8_t(rng());
            noise[3] = 0xE1;
            Packet fake = packets[i];
            fake.resize(fake.size() / 2);  // a packet cut short: its header promises more
            bytes.insert(bytes.end(), noise.begin(), noise.end());
            bytes.insert(bytes.end(), fake.begin(), fake.end());
            ++garbage_regions;
        }
        expected.push_back(bytes.size());
        bytes.insert(bytes.end(), packets[i].begin(), packets[i].end());
    }
    ContainerContents c = read_container(bytes);
    CHECK(offsets_read(c) == expected);
    CHECK(c.damaged.size() == garbage_regions);
    uint64_t damaged_bytes = 0;
    for (const auto& d : c.damaged) damaged_bytes += d.length;
    uint64_t packet_bytes = 0;
    for (const auto& p : packets) packet_bytes += p.size();
    CHECK(damaged_bytes + packet_bytes + kContainerHeaderSize == bytes.size());
}

TEST_CASE("a duplicated and reordered recording decodes to the same stream as the original") {
    auto packets = small_stream();
    ReceivedStream in_order;
    for (size_t i = 0; i < packets.size(); ++i) REQUIRE(in_order.add_packet(packets[i], i) == Error::Ok);
    std::vector<Packet> shuffled = packets;
    shuffled.insert(shuffled.end(), packets.begin(), packets.begin() + 10);
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
    const auto recording = write_container(shuffled);  // the views of read_container point into it
    ContainerContents c = read_container(recording);
    ReceivedStream stream;
    for (const auto& p : c.packets) CHECK(stream.add_parsed(p.view, p.offset) == Error::Ok);
    CHECK(stream.counters().duplicates == 10);
    CHECK(stream.counters().pending == 0);
    REQUIRE(stream.objects().size() == in_order.objects().size());
    for (size_t o = 0; o < stream.objects().size(); ++o) {
        CHECK(stream.objects()[o].ellipsoids.size() == in_order.objects()[o].ellipsoids.size());
        CHECK(stream.objects()[o].points.size() == in_order.objects()[o].points.size());
        auto a = stream.points(o), b = in_order.points(o);
        REQUIRE(a.size() == b.size());
        for (size_t i = 0; i < a.size(); ++i) CHECK(a[i].position == b[i].position);
    }
}

TEST_CASE("container files are written through a temporary name and read back, I/O errors name the file") {
    auto dir = test::scratch_dir("container_io");
    auto bytes = write_container(small_stream());
    std::string message;
    const std::string path = (dir / "stream.ellc").string();
    REQUIRE(write_file(path, bytes, message) == Error::Ok);
    CHECK_FALSE(std::filesystem::exists(path + ".partial"));
    std::vector<uint8_t> back;
    REQUIRE(read_file(path, back, message) == Error::Ok);
    CHECK(back == bytes);
    CHECK(read_file((dir / "missing.ellc").string(), back, message) == Error::IoError);
    CHECK(message.find("missing.ellc") != std::string::npos);
    CHECK(read_file(dir.string(), back, message) == Error::IoError);
    CHECK(message.find("directory") != std::string::npos);
    CHECK(write_file((dir / "no" / "such" / "dir.ellc").string(), bytes, message) == Error::IoError);
    CHECK(message.find("dir.ellc") != std::string::npos);
}
