// Format 1.1: scene graph, materials and texture fragments.
#include "support.h"

#include "ellicast/format.h"

#include <algorithm>
#include <random>

using namespace ellicast;

namespace {

SceneDescription sample_scene(size_t image_bytes) {
    SceneDescription scene;
    for (uint16_t i = 0; i < 6; ++i) {
        SceneNode n;
        n.index = i;
        n.parent = i == 0 ? kNone : static_cast<uint16_t>((i - 1) / 2);
        n.mesh = i % 2 ? 0 : kNone;
        n.name = "node " + std::to_string(i);
        n.translation = {float(i), 2.5f, -1};
        n.rotation = {0, 0.70710677f, 0, 0.70710677f};
        if (i == 5) {  // a matrix node: no TRS travels for it
            n = SceneNode{};
            n.index = i;
            n.parent = 2;
            n.has_matrix = true;
            n.matrix[12] = 7;
        }
        scene.nodes.push_back(n);
    }
    SceneMesh mesh;
    mesh.name = "truck";
    mesh.primitives = {{0, 0}, {1, kNone}};
    scene.meshes.push_back(mesh);
    Material m;
    m.name = "paint";
    m.base_color = {0.8f, 0.1f, 0.1f, 1};
    m.metallic = 0.2f;
    m.roughness = 0.7f;
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = 0.25f;
    m.double_sided = true;
    m.base_color_texture = {0, 0, 1};
    m.normal_texture = {0, 1, 0.5f};
    scene.materials.push_back(m);
    SceneDescription::Texture t;
    std::mt19937 rng(11);
    for (size_t i = 0; i < image_bytes; ++i) t.image.push_back(static_cast<uint8_t>(rng()));
    t.info.image_type = ImageType::Png;
    t.info.min_filter = 9987;
    scene.textures.push_back(t);
    return scene;
}

std::vector<std::vector<uint8_t>> all_packets(const ScenePackets& p) {
    std::vector<std::vector<uint8_t>> out;
    for (const auto* v : {&p.scene, &p.materials, &p.textures}) out.insert(out.end(), v->begin(), v->end());
    return out;
}

}  // namespace

TEST_CASE("a scene, its materials and a texture come back whole from shuffled, duplicated packets") {
    const auto scene = sample_scene(20000);
    ScenePackets packets;
    REQUIRE(packetize_scene(scene, 1200, 9, 0, packets) == Error::Ok);
    auto all = all_packets(packets);
    auto copy = all;
    all.insert(all.end(), copy.begin(), copy.end());
    std::shuffle(all.begin(), all.end(), std::mt19937(5));
    ReceivedStream rs;
    for (size_t i = 0; i < all.size(); ++i) REQUIRE(rs.add_packet(all[i], i) == Error::Ok);
    CHECK(rs.counters().rejected == 0);
    CHECK(rs.counters().duplicates == copy.size());
    REQUIRE(rs.scene_nodes().size() == scene.nodes.size());
    for (const auto& n : scene.nodes) CHECK(rs.scene_nodes().at(n.index) == n);
    CHECK(rs.scene_meshes().at(0) == SceneMesh{0, "truck", {{0, 0}, {1, kNone}}, {}});
    Material expected = scene.materials[0];
    expected.material_count = 1;
    CHECK(rs.materials().at(0) == expected);
    const auto& t = rs.textures().at(0);
    CHECK(t.complete);
    CHECK(t.image == scene.textures[0].image);
    CHECK(t.info.min_filter == 9987);
}

TEST_CASE("scene packets are marked skippable so a 1.0 decoder still decodes the geometry") {
    ScenePackets packets;
    REQUIRE(packetize_scene(sample_scene(3000), 1200, 1, 0, packets) == Error::Ok);
    for (const auto& p : all_packets(packets)) {
        PacketView v;
        REQUIRE(parse_packet(p, v) == Error::Ok);
        CHECK(v.header.skippable());
        CHECK(v.header.version_minor == 1);
    }
}

TEST_CASE("every texture fragment is useful alone: its bytes land at their offset, the rest stays missing") {
    const auto scene = sample_scene(5000);
    ScenePackets packets;
    REQUIRE(packetize_scene(scene, 600, 1, 0, packets) == Error::Ok);
    REQUIRE(packets.textures.size() > 3);
    ReceivedStream rs;
    REQUIRE(rs.add_packet(packets.textures[2], 0) == Error::Ok);
    const auto& t = rs.textures().at(0);
    CHECK_FALSE(t.complete);
    CHECK(t.image.empty());
    REQUIRE(t.pieces.size() == 1);
    const auto& [offset, bytes] = *t.pieces.begin();
    CHECK(t.received_bytes == bytes.size());
    CHECK(std::equal(bytes.begin(), bytes.end(), scene.textures[0].image.begin() + offset));
    // The remaining fragments, in reverse order, complete it.
    for (size_t i = packets.textures.size(); i-- > 0;) rs.add_packet(packets.textures[i], i);
    CHECK(rs.textures().at(0).complete);
    CHECK(rs.textures().at(0).image == scene.textures[0].image);
}

TEST_CASE("texture fragments that contradict the image they announce are rejected") {
    ScenePackets a, b;
    auto scene = sample_scene(4000);
    REQUIRE(packetize_scene(scene, 1200, 1, 0, a) == Error::Ok);
    scene.textures[0].image[10] ^= 1;  // another image of the same size: another CRC
    REQUIRE(packetize_scene(scene, 1200, 1, 0, b) == Error::Ok);
    ReceivedStream rs;
    REQUIRE(rs.add_packet(a.textures[0], 0) == Error::Ok);
    CHECK(rs.add_packet(b.textures[1], 1) == Error::StreamMismatch);
}

TEST_CASE("texture bytes beyond the receiver's limit are rejected, and an announced size costs nothing") {
    ReceivedStream::Limits limits;
    limits.max_texture_bytes = 1000;
    ReceivedStream rs(limits);
    ScenePackets packets;
    REQUIRE(packetize_scene(sample_scene(5000), 1200, 1, 0, packets) == Error::Ok);
    // The first fragment (1,148 bytes) is over the 1,000-byte limit; its announced 5,000 bytes
    // were never reserved.
    CHECK(rs.add_packet(packets.textures[0], 0) == Error::MalformedPayload);
    CHECK(rs.textures().at(0).pieces.empty());
    CHECK(rs.textures().at(0).received_bytes == 0);
}

TEST_CASE("one-byte texture fragments count their bookkeeping toward the texture memory cap") {
    // 1-byte fragments of a 5,000-byte image, every other byte (so that none merge): each costs 1 +
    // 64 bytes; a 65,000-byte cap holds 1,000 of them, not 65,000.
    auto scene = sample_scene(5000);
    ScenePackets whole;
    REQUIRE(packetize_scene(scene, 1200, 1, 0, whole) == Error::Ok);
    PacketView view;
    REQUIRE(parse_packet(whole.textures[0], view) == Error::Ok);
    TextureFragment first;
    REQUIRE(decode_texture_fragment_payload(view.payload, first) == Error::Ok);
    ReceivedStream::Limits limits;
    limits.max_texture_bytes = 1000 * (1 + kHeldPacketCost);
    ReceivedStream rs(limits);
    size_t accepted = 0, refused = 0;
    for (uint32_t offset = 0; offset < 4000; offset += 2) {
        TextureFragment f = first;
        f.offset = offset;
        f.data = {scene.textures[0].image[offset]};
        PacketHeader h = view.header;
        const auto payload = encode_texture_fragment_payload(f);
        h.payload_length = uint16_t(payload.size());
        const Error e = rs.add_packet(write_packet(h, payload), offset);
        (e == Error::Ok ? accepted : refused) += 1;
        if (e != Error::Ok) CHECK(e == Error::MalformedPayload);
    }
    CHECK(accepted == 1000);
    CHECK(refused == 1000);
    CHECK(rs.textures().at(0).pieces.size() == 1000);
}

TEST_CASE("overlapping fragments of a texture keep only the bytes that are new") {
    auto scene = sample_scene(3000);
    ScenePackets a, b;
    REQUIRE(packetize_scene(scene, 1200, 1, 0, a) == Error::Ok);  // fragments at 0, 1148, 2296
    REQUIRE(packetize_scene(scene, 700, 1, 0, b) == Error::Ok);   // fragments at 0, 648, 1296, ...
    ReceivedStream rs;
    REQUIRE(rs.add_packet(a.textures[1], 0) == Error::Ok);
    REQUIRE(rs.add_packet(b.textures[1], 1) == Error::Ok);  // same image, other cut: compatible
    const auto& t = rs.textures().at(0);
    uint64_t held = 0;
    uint32_t last_end = 0;
    for (const auto& [offset, bytes] : t.pieces) {
        CHECK(offset >= last_end);  // disjoint
        last_end = offset + uint32_t(bytes.size());
        held += bytes.size();
        CHECK(std::equal(bytes.begin(), bytes.end(), scene.textures[0].image.begin() + offset));
    }
    CHECK(held == t.received_bytes);
    for (const auto* set : {&a.textures, &b.textures})
        for (const auto& p : *set) rs.add_packet(p, 2);
    CHECK(rs.textures().at(0).complete);
    CHECK(rs.textures().at(0).image == scene.textures[0].image);
    CHECK(rs.textures().at(0).pieces.empty());
}

TEST_CASE("scene records referring outside their tables are refused at both ends") {
    auto scene = sample_scene(100);
    scene.nodes[3].parent = 40;
    ScenePackets packets;
    CHECK(packetize_scene(scene, 1200, 1, 0, packets) == Error::MalformedPayload);

    SceneBatch batch;
    batch.node_count = 2;
    SceneNode n;
    n.index = 1;
    n.parent = 7;  // beyond node_count
    batch.nodes.push_back(n);
    auto payload = encode_scene_payload(batch);
    SceneBatch decoded;
    CHECK(decode_scene_payload(payload, decoded) == Error::MalformedPayload);
    payload.pop_back();  // and a record cut short
    CHECK(decode_scene_payload(payload, decoded) == Error::MalformedPayload);
}

TEST_CASE("names too long for the smallest packets are shortened at a UTF-8 boundary") {
    auto scene = sample_scene(100);
    std::string name;
    for (int i = 0; i < 100; ++i) name += "\xC3\xA9";  // 'é', two bytes each
    scene.nodes[0].name = name;
    scene.materials[0].name = name;
    ScenePackets packets;
    REQUIRE(packetize_scene(scene, kMinPacketSize, 1, 0, packets) == Error::Ok);
    ReceivedStream rs;
    for (const auto& p : all_packets(packets)) REQUIRE(rs.add_packet(p, 0) == Error::Ok);
    const std::string& got = rs.scene_nodes().at(0).name;
    CHECK(got.size() < name.size());
    CHECK(got.size() % 2 == 0);
    CHECK(name.compare(0, got.size(), got) == 0);
    CHECK(rs.materials().at(0).name.size() % 2 == 0);
    for (const auto& p : all_packets(packets)) CHECK(p.size() <= kMinPacketSize);
}
