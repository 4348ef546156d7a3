// Mapped points (format 1.7, spec 23): ranks, the POINT_MAP tree, and a real model's points sent
// over a map, received in any order, with part of the map, with repair, and against hostile packets.
#include "encode_options.h"
#include "support.h"

#include "ellicast/broadcast/carousel.h"
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <algorithm>
#include <map>
#include <random>

using namespace ellicast;
using namespace ellicast::test;

namespace {

std::string sample(const std::string& relative) { return (shared_samples() / relative).string(); }

// A sample with a small base (the points are what is tested), mapped or not.
EncodeResult encode_small_base(const std::string& model, bool point_map = true) {
    LoadResult loaded = load_meshes(sample(model));
    EncodeOptions o = fast_options();
    o.max_ellipsoids = 4;
    o.candidates = 16;
    o.grid = 16;
    o.point_map = point_map;
    return encode_meshes(loaded.meshes, o);
}

EncodeResult encode_bunny(bool point_map) { return encode_small_base("meshes/bunny.ply", point_map); }

StreamPackets packets_of(const EncodeResult& encoded) {
    StreamPackets p;
    REQUIRE(packetize_stream(encoded.info, encoded.contents, 1, p) == Error::Ok);
    return p;
}

uint64_t total_bytes(const std::vector<std::vector<uint8_t>>& packets) {
    uint64_t n = 0;
    for (const auto& p : packets) n += p.size();
    return n;
}

std::vector<uint8_t> packet(PacketType type, uint16_t object, const std::vector<uint8_t>& payload, uint32_t stream_id = 1) {
    PacketHeader h;
    h.type = uint8_t(type);
    h.version_minor = kMapMinor;
    h.stream_id = stream_id;
    h.object_id = object;
    return write_packet(h, payload);
}

}  // namespace

TEST_CASE("mapped ranks deal the indices to the batches in turn, as spec 23.2's example says") {
    std::vector<uint32_t> ranks;
    for (uint32_t i = 0; i < 10; ++i) ranks.push_back(mapped_rank(i, 10, 4));
    CHECK(ranks == std::vector<uint32_t>{0, 3, 6, 8, 1, 4, 7, 9, 2, 5});
    for (uint32_t n_points : {1u, 2u, 7u, 100u, 389u, 1000u, 36212u})
        for (uint32_t batch : {1u, 3u, 389u, 1000u, 65535u}) {
            std::vector<uint8_t> seen(n_points, 0);
            for (uint32_t i = 0; i < n_points; ++i) {
                const uint32_t r = mapped_rank(i, n_points, batch);
                REQUIRE(r < n_points);
                CHECK(seen[r] == 0);
                seen[r] = 1;
                CHECK(mapped_index(r, n_points, batch) == i);
            }
        }
}

TEST_CASE("a cell's Morton code and its corner are each other's inverse at every level and bit depth (spec 23.2)") {
    std::mt19937 rng(23);
    for (unsigned P = 8; P <= 16; ++P)
        for (unsigned L = 1; L < P; ++L)
            for (int trial = 0; trial < 200; ++trial) {
                const std::array<uint32_t, 3> q{uint32_t(rng()) & ((1u << P) - 1), uint32_t(rng()) & ((1u << P) - 1),
                                                uint32_t(rng()) & ((1u << P) - 1)};
                const uint64_t code = morton_cell(q, P, L);
                // Spec 23.2 bit by bit: bit b of the cell's coordinate on axis a is bit 3b + a of the code.
                uint64_t spec_code = 0;
                for (unsigned b = 0; b < L; ++b)
                    for (unsigned a = 0; a < 3; ++a) spec_code |= uint64_t((q[a] >> (P - L + b)) & 1u) << (3 * b + a);
                REQUIRE(code == spec_code);
                // Bits above the level's 3L are not the cell's: a corner ignores them.
                const uint64_t noisy = code | (uint64_t(rng()) << (3 * L));
                for (const uint64_t c : {code, noisy}) {
                    const std::array<uint32_t, 3> corner = cell_corner(c, P, L);
                    for (int a = 0; a < 3; ++a) REQUIRE(corner[a] == (q[a] >> (P - L)) << (P - L));
                }
            }
}

TEST_CASE("a POINT_MAP fragment comes back as it was written, and a damaged tree is malformed with its reason") {
    // Cells of level 6 scattered over part of the cube, with counts from 1 to 40.
    std::mt19937 rng(3);
    std::vector<MapCell> cells;
    uint64_t code = 0;
    for (int i = 0; i < 300; ++i) {
        code += 1 + rng() % 50;
        cells.push_back({code, 1 + uint32_t(rng() % 40)});
    }
    for (unsigned root_level : {0u, 2u, 6u})
        for (unsigned rice : {0u, 3u, 15u}) {
            PointMapFragment f;
            f.first_rank = 17;
            f.root_level = uint8_t(root_level);
            f.rice = uint8_t(rice);
            for (const MapCell& c : cells) f.point_total += c.count;
            f.cells = cells;
            const std::vector<uint8_t> payload = encode_point_map_payload(f, 6);
            CHECK(payload.size() == kPointMapHeaderSize + (point_map_tree_bits(cells, 6, root_level, rice) + 7) / 8);
            PointMapFragment back;
            REQUIRE(decode_point_map_payload(payload, 14, 6, back) == Error::Ok);
            CHECK(back.cells == cells);
            CHECK(back.first_rank == 17);
            CHECK(back.point_total == f.point_total);
            std::string why;
            std::vector<uint8_t> shorter(payload.begin(), payload.end() - 1), longer = payload;
            longer.push_back(0);
            CHECK(decode_point_map_payload(shorter, 14, 6, back, &why) == Error::MalformedPayload);
            CHECK(!why.empty());
            CHECK(decode_point_map_payload(longer, 14, 6, back, &why) == Error::MalformedPayload);
            CHECK(why.find("payload_length") != std::string::npos);
            CHECK(decode_point_map_payload(payload, 14, 0, back, &why) == Error::MalformedPayload);  // not mapped
            CHECK(decode_point_map_payload(payload, 14, 5, back, &why) == Error::MalformedPayload);  // other level
            std::vector<uint8_t> total = payload;
            total[4] ^= 1;  // point_total one off
            CHECK(decode_point_map_payload(total, 14, 6, back, &why) == Error::MalformedPayload);
        }
    // A mask of 0 (F = 5: the root's code, then the mask of its one level above the cells).
    PointMapFragment f;
    f.root_level = 5;
    f.cells = {{8, 1}};
    f.point_total = 1;
    std::vector<uint8_t> payload = encode_point_map_payload(f, 6);
    PointMapFragment back;
    REQUIRE(decode_point_map_payload(payload, 14, 6, back) == Error::Ok);
    // Root code 1 (15 bits), mask 0x01 (8 bits), count 1 (Rice 0: one 0 bit): 24 bits.
    REQUIRE(payload.size() == kPointMapHeaderSize + 3);
    CHECK(payload[kPointMapHeaderSize] == 0x01);
    CHECK(payload[kPointMapHeaderSize + 1] == 0x80);
    payload[kPointMapHeaderSize + 1] = 0;  // the mask becomes 0
    std::string why;
    CHECK(decode_point_map_payload(payload, 14, 6, back, &why) == Error::MalformedPayload);
    CHECK(why.find("mask of 0") != std::string::npos);
}

TEST_CASE("the bunny's points travel mapped: fewer bytes, the same points, placed whatever the order they come in") {
    if (!have_sample("meshes/bunny.ply")) return;
    const EncodeResult plain = encode_bunny(false), mapped = encode_bunny(true);
    const ObjectInfo& object = mapped.info.objects[0];
    REQUIRE(object.mapped());
    CHECK(!plain.info.objects[0].mapped());
    CHECK(object.map_level >= 4);
    CHECK(object.map_level <= 8);
    // The same points, in another order.
    auto sorted = [](std::vector<QuantizedPoint> v) {
        auto key = [](const QuantizedPoint& q) { return std::tie(q.position, q.normal, q.texcoord, q.color); };
        std::sort(v.begin(), v.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
        return v;
    };
    const auto& points = mapped.contents[0].points;
    REQUIRE(points.size() == plain.contents[0].points.size());
    auto a = sorted(points), b = sorted(plain.contents[0].points);
    CHECK(std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) { return x.position == y.position; }));

    const StreamPackets p = packets_of(mapped), q = packets_of(plain);
    REQUIRE(!p.maps.empty());
    CHECK(q.maps.empty());
    for (const auto* group : {&p.maps, &p.points})
        for (const auto& packet : *group) CHECK(packet.size() <= mapped.info.packet_size);
    const double mapped_bytes = double(total_bytes(p.maps) + total_bytes(p.points));
    const double plain_bytes = double(total_bytes(q.points));
    MESSAGE("bunny, 14 bits: " << mapped_bytes / double(points.size()) << " bytes a point mapped (" << p.maps.size()
                               << " POINT_MAP packets, level " << int(object.map_level) << "), "
                               << plain_bytes / double(points.size()) << " as POINTS");
    CHECK(mapped_bytes < 0.8 * plain_bytes);

    // Points first, then the map: every record is held unplaced, then placed exactly.
    ReceivedStream rx;
    uint64_t where = 0;
    for (const auto& packet : p.stream_info) REQUIRE(rx.add_packet(packet, where++) == Error::Ok);
    for (const auto& packet : p.points) REQUIRE(rx.add_packet(packet, where++) == Error::Ok);
    CHECK(rx.objects()[0].points.empty());
    CHECK(rx.objects()[0].unplaced.size() == points.size());
    for (const auto& packet : p.maps) REQUIRE(rx.add_packet(packet, where++) == Error::Ok);
    CHECK(rx.objects()[0].map_complete());
    CHECK(rx.objects()[0].unplaced.empty());
    REQUIRE(rx.objects()[0].points.size() == points.size());
    for (const auto& [index, point] : rx.objects()[0].points) CHECK(point.position == points[index].position);
    // Held in memory near their bytes (spec 11.2): a 2-byte component and page bookkeeping a point.
    // A map cell is 8 bytes held (a 4-byte code and the rank it starts at) against about half a byte
    // on the wire (its octree): the map is held in about 11 times its bytes (91 KB for 8.5 KB).
    const uint64_t held_points = rx.objects()[0].points.memory(), held_map = rx.objects()[0].map_memory;
    const double point_bytes = double(total_bytes(p.points)), map_bytes = double(total_bytes(p.maps));
    MESSAGE("bunny: points held in " << held_points << " bytes for " << point_bytes << " bytes of MAPPED_POINTS ("
                                     << double(held_points) / point_bytes << "x), the map in " << held_map << " for "
                                     << map_bytes << " (" << double(held_map) / map_bytes << "x)");
    CHECK(double(held_points) <= 2.5 * point_bytes);
    CHECK(double(held_points + held_map) <= 5 * mapped_bytes);
    CHECK(double(held_map) <= 16 * map_bytes);
    CHECK(rx.held_memory() == rx.objects()[0].memory());
    // Repeats are duplicates and change nothing.
    const auto accepted = rx.counters().accepted;
    for (const auto& packet : p.maps) REQUIRE(rx.add_packet(packet, where++) == Error::Ok);
    CHECK(rx.counters().accepted == accepted);

    // Half the map: the points of its ranks are placed, the others wait; the object is not complete.
    if (p.maps.size() >= 2) {
        ReceivedStream half;
        for (const auto& packet : p.stream_info) half.add_packet(packet, 0);
        for (size_t i = 0; i < p.maps.size(); i += 2) half.add_packet(p.maps[i], 1);
        for (const auto& packet : p.points) half.add_packet(packet, 2);
        const auto& o = half.objects()[0];
        CHECK(!o.map_complete());
        CHECK(o.points.size() + o.unplaced.size() == points.size());
        CHECK(o.points.size() > points.size() / 4);
        CHECK(o.unplaced.size() > points.size() / 4);
        for (const auto& [index, point] : o.points) CHECK(point.position == points[index].position);
    }
}

TEST_CASE("repair symbols over mapped records bring back a lost MAPPED_POINTS packet, placed once its map arrives") {
    if (!have_sample("meshes/bunny.ply")) return;
    const EncodeResult mapped = encode_bunny(true);
    const ObjectInfo& object = mapped.info.objects[0];
    const StreamPackets p = packets_of(mapped);
    REQUIRE(p.points.size() >= 3);
    const auto blocks = plan_repair_blocks(object.point_count, uint16_t(point_batch_size(mapped.info, object)), 127);
    std::vector<std::vector<uint8_t>> repairs;
    REQUIRE(packetize_repairs(mapped.info, 0, mapped.contents[0].points, blocks, 1, 1, 0, repairs) == Error::Ok);
    // Every POINTS packet but the first, then one repair per block, then the map.
    ReceivedStream rx;
    for (const auto& packet : p.stream_info) rx.add_packet(packet, 0);
    for (size_t i = 1; i < p.points.size(); ++i) REQUIRE(rx.add_packet(p.points[i], i) == Error::Ok);
    for (const auto& r : repairs) REQUIRE(rx.add_packet(r, 1000) == Error::Ok);
    CHECK(rx.objects()[0].points_recovered > 0);
    CHECK(rx.objects()[0].points.empty());  // nothing placed without the map
    for (const auto& packet : p.maps) rx.add_packet(packet, 2000);
    REQUIRE(rx.objects()[0].points.size() == object.point_count);
    for (const auto& [index, point] : rx.objects()[0].points)
        CHECK(point.position == mapped.contents[0].points[index].position);
}

TEST_CASE("hostile mapped packets are rejected with their reason and change nothing") {
    if (!have_sample("meshes/bunny.ply")) return;
    const EncodeResult mapped = encode_bunny(true);
    const ObjectInfo& object = mapped.info.objects[0];
    const StreamPackets p = packets_of(mapped);
    REQUIRE(p.maps.size() >= 2);
    ReceivedStream rx;
    for (const auto& packet : p.stream_info) REQUIRE(rx.add_packet(packet, 0) == Error::Ok);
    PacketView first;
    REQUIRE(parse_packet(p.maps[0], first) == Error::Ok);
    REQUIRE(rx.add_packet(p.maps[0], 1) == Error::Ok);
    PointMapFragment f;
    REQUIRE(decode_point_map_payload(first.payload, mapped.info.position_bits, object.map_level, f) == Error::Ok);
    // The same cells one rank later: they overlap the fragment received.
    PointMapFragment shifted = f;
    shifted.first_rank += 1;
    CHECK(rx.add_packet(packet(PacketType::PointMap, 0, encode_point_map_payload(shifted, object.map_level)), 2) ==
          Error::StreamMismatch);
    // Ranks past the object's points.
    shifted.first_rank = object.point_count - 1;
    CHECK(rx.add_packet(packet(PacketType::PointMap, 0, encode_point_map_payload(shifted, object.map_level)), 3) ==
          Error::IndexOutOfRange);
    // The fixed fields (step 11): a root count of 0.
    std::vector<uint8_t> no_roots(first.payload.begin(), first.payload.end());
    no_roots[10] = no_roots[11] = 0;
    CHECK(rx.add_packet(packet(PacketType::PointMap, 0, no_roots), 4) == Error::MalformedPayload);
    // A POINTS packet for the mapped object, and the object's own MAPPED_POINTS payload as POINTS.
    PacketView points;
    REQUIRE(parse_packet(p.points[0], points) == Error::Ok);
    CHECK(rx.add_packet(packet(PacketType::Points, 0, {points.payload.begin(), points.payload.end()}), 5) ==
          Error::MalformedPayload);
    CHECK(rx.rejections().back().detail.find("MAPPED_POINTS") != std::string::npos);
    CHECK(rx.objects()[0].map_fragments.size() == 1);
    CHECK(rx.objects()[0].points.empty());
    // A stream info whose entry says level 14 of 14 bits is malformed.
    StreamInfo bad = mapped.info;
    bad.objects[0].map_level = bad.position_bits;
    CHECK(check_stream_info(bad) == Error::MalformedPayload);
    bad.objects[0].map_level = 3;
    bad.objects[0].map_batch = 0;
    CHECK(check_stream_info(bad) == Error::MalformedPayload);
}

TEST_CASE("a 1.6 STREAM_INFO with 48-byte entries is read without the map fields") {
    StreamInfo info;
    ObjectInfo o;
    o.point_count = 10;
    o.map_level = 3;
    o.map_batch = 4;
    info.objects.push_back(o);
    const std::vector<uint8_t> payload = encode_stream_info_payload(info, 0, 1);
    REQUIRE(payload.size() == kStreamInfoFixedSize + kMappedEntrySize);
    StreamInfoPart part;
    REQUIRE(decode_stream_info_payload(payload, part, kMapMinor) == Error::Ok);
    CHECK(part.info.objects[0].map_level == 3);
    CHECK(part.info.objects[0].map_batch == 4);
    REQUIRE(decode_stream_info_payload(payload, part, kMorphMinor) == Error::Ok);
    CHECK(part.info.objects[0].map_level == 0);
    CHECK(part.info.objects[0].map_batch == 0);
}

TEST_CASE("the carousel sends a small object's one map fragment with every stream info, and each fragment of a large map four times a cycle or more") {
    if (!have_sample("meshes/spot.obj") || !have_sample("meshes/bunny.ply")) return;
    for (const char* model : {"meshes/spot.obj", "meshes/bunny.ply"}) {
        const StreamPackets p = packets_of(encode_small_base(model));
        std::vector<std::vector<uint8_t>> all;
        for (auto* group : {&p.stream_info, &p.ellipsoids, &p.maps, &p.points}) all.insert(all.end(), group->begin(), group->end());
        broadcast::Carousel carousel;
        std::string error;
        REQUIRE(broadcast::build_carousel(all, broadcast::CarouselOptions{}, carousel, error));
        REQUIRE(!carousel.maps.empty());
        std::map<uint32_t, size_t> sent;
        size_t infos = 0;
        for (const auto& entry : carousel.cycle) {
            sent[entry.packet]++;
            infos += all[entry.packet][6] == uint8_t(PacketType::StreamInfo);
        }
        const double cycles = double(carousel.period_cycles);
        for (uint32_t m : carousel.maps) CHECK(double(sent[m]) / cycles >= 4);
        if (carousel.maps.size() == 1) CHECK(sent[carousel.maps[0]] == infos);
        MESSAGE(std::string(model) << ": " << carousel.maps.size() << " map fragments, sent " << double(sent[carousel.maps[0]]) / cycles
                      << " times a cycle (the first), " << carousel.chunk_count << " chunks");
    }
}

TEST_CASE("ellicast decode of a mapped stream whose map did not arrive shows the base and says how many points wait for it") {
    if (!have_sample("meshes/spot.obj")) return;
    auto dir = scratch_dir("point_map_cli");
    int status = 0;
    std::string out = run_command(shell_quoted(ellicast_exe().string()) + " encode -q -e 40 '" + sample("meshes/spot.obj") + "' -o '" +
                                      (dir / "spot.ellc").string() + "'",
                                  status);
    REQUIRE_MESSAGE(status == 0, out);
    CHECK(out.find("points mapped at level") != std::string::npos);
    // The same recording without its POINT_MAP packets.
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE(read_file((dir / "spot.ellc").string(), bytes, message) == Error::Ok);
    ContainerContents contents = read_container(bytes);
    std::vector<std::vector<uint8_t>> kept;
    size_t maps = 0;
    for (const auto& p : contents.packets) {
        if (p.view.header.type == uint8_t(PacketType::PointMap)) {
            ++maps;
            continue;
        }
        kept.emplace_back(p.view.payload.data() - kHeaderSize, p.view.payload.data() + p.view.payload.size() + kChecksumSize);
    }
    REQUIRE(maps > 0);
    REQUIRE(write_file((dir / "nomap.ellc").string(), write_container(kept), message) == Error::Ok);
    out = run_command(shell_quoted(ellicast_exe().string()) + " decode '" + (dir / "nomap.ellc").string() + "' -o '" +
                          (dir / "nomap.glb").string() + "'",
                      status);
    CHECK_MESSAGE(status == 0, out);
    CHECK_MESSAGE(out.find("points arrived but are not shown: the POINT_MAP fragments that place them did not arrive") !=
                      std::string::npos,
                  out);
    CHECK(std::filesystem::exists(dir / "nomap.glb"));
    out = run_command(shell_quoted(ellicast_exe().string()) + " validate '" + (dir / "nomap.ellc").string() + "'", status);
    CHECK(status != 0);
    CHECK_MESSAGE(out.find("its point map holds 0 of") != std::string::npos, out);
}

TEST_CASE("a received map fragment holds its cells compactly, with codes past 32 bits at deep levels") {
    // Level 10: 30-bit codes, 4 bytes each; level 14: 42-bit codes, 8 bytes each.
    for (const unsigned level : {10u, 14u}) {
        const uint64_t top = (uint64_t(1) << (3 * level)) - 1;
        const std::vector<MapCell> cells = {{0, 3}, {5, 1}, {top / 2 + 7, 250}, {top - 1, 2}, {top, 1}};
        const ReceivedMapFragment f(257, cells, level);
        CHECK(f.size() == cells.size());
        CHECK(f.point_total() == 257);
        CHECK(f.cells() == cells);
        CHECK(f.same_cells(cells));
        std::vector<MapCell> other = cells;
        other[2].count = 249;
        other[3].count = 3;  // same total, another split
        CHECK(!f.same_cells(other));
        other = cells;
        other[4].code = top - 2 + (uint64_t(1) << 32) * (level > 10);
        CHECK(!f.same_cells(other));
        // Ranks 0..2 are cell 0, 3 cell 1, 4..253 cell 2, 254..255 cell 3, 256 cell 4.
        CHECK(f.cell_of(0) == 0);
        CHECK(f.cell_of(2) == 0);
        CHECK(f.cell_of(3) == 1);
        CHECK(f.cell_of(4) == 2);
        CHECK(f.cell_of(253) == 2);
        CHECK(f.cell_of(254) == 3);
        CHECK(f.cell_of(256) == 4);
        CHECK(f.code(4) == top);
        CHECK(f.memory() <= cells.size() * (level > 10 ? 12 : 8));
    }
}
