// Skins (format 1.5, spec 21): SKIN and JOINT_WEIGHTS packets, the node record's skin, and what a
// receiver keeps of them.
#include "broadcast_support.h"

#include "ellicast/format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

using namespace ellicast;

namespace {

// Five nodes: a root with a mesh (skinned by skin 0) and a chain of four joints; skin 0 has 4
// joints, skin 1 (a long one, 300 joints over the same nodes) exercises several packets.
SceneDescription skinned_scene() {
    SceneDescription scene;
    for (uint16_t i = 0; i < 5; ++i) {
        SceneNode n;
        n.index = i;
        n.parent = i <= 1 ? kNone : uint16_t(i - 1);
        n.name = "node " + std::to_string(i);
        scene.nodes.push_back(n);
    }
    scene.nodes[0].mesh = 0;
    scene.nodes[0].skin = 0;
    scene.meshes.push_back({0, "body", {{0, kNone}}, {}});
    SceneSkin arm;
    arm.name = "Arm \xc3\xa4";
    arm.skeleton = 1;
    for (uint16_t j = 0; j < 4; ++j) {
        SkinJoint joint;
        joint.node = uint16_t(1 + j);
        joint.inverse_bind[13] = -float(j);  // a translation down the chain
        joint.inverse_bind[0] = j == 2 ? -0.0f : 1.0f;
        arm.joints.push_back(joint);
    }
    SceneSkin many;
    many.name = "many";
    for (uint16_t j = 0; j < 300; ++j) {
        SkinJoint joint;
        joint.node = uint16_t(1 + j % 4);
        joint.inverse_bind[12] = 0.001f * float(j);
        many.joints.push_back(joint);
    }
    scene.skins = {arm, many};
    return scene;
}

ScenePackets packetize(const SceneDescription& scene, size_t packet_size = 1200) {
    ScenePackets packets;
    REQUIRE(packetize_scene(scene, packet_size, 77, 0, packets) == Error::Ok);
    return packets;
}


// A one-object stream of `points` points (no attributes), its info and its packets.
struct SmallStream {
    StreamInfo info;
    std::vector<std::vector<uint8_t>> packets;  // STREAM_INFO, ELLIPSOIDS, POINTS
};
SmallStream small_stream(uint32_t points, uint16_t packet_size = 1200) {
    SmallStream s;
    s.info.packet_size = packet_size;
    ObjectInfo object;
    object.frame.origin = {0, 0, 0};
    object.frame.scale = 1;
    object.ellipsoid_count = 1;
    object.point_count = points;
    s.info.objects.push_back(object);
    ObjectContent content;
    Ellipsoid e;
    e.center = {0.5f, 0.5f, 0.5f};
    e.radii = {0.2f, 0.2f, 0.2f};
    content.ellipsoids.push_back(quantize_ellipsoid(e, object.frame));
    for (uint32_t i = 0; i < points; ++i) {
        SurfacePoint p;
        p.position = {float(i % 97) / 97.0f, float(i % 89) / 89.0f, float(i % 83) / 83.0f};
        content.points.push_back(quantize_point(p, s.info, object));
    }
    StreamPackets sp;
    REQUIRE(packetize_stream(s.info, {content}, 77, sp) == Error::Ok);
    for (auto* part : {&sp.stream_info, &sp.ellipsoids, &sp.maps, &sp.points, &sp.normals})
        for (auto& p : *part) s.packets.push_back(p);
    return s;
}

// Records for `n` points: point i follows joints i % 7 and (i + 1) % 7 (wide: + 300) unevenly, every
// fifth point a single joint.
std::vector<Influences> records_for(size_t n, bool wide) {
    std::vector<Influences> out;
    for (size_t i = 0; i < n; ++i) {
        const uint16_t base = wide ? 300 : 0;
        const std::array<uint16_t, 2> joints = {uint16_t(base + i % 7), uint16_t(base + (i + 1) % 7)};
        const std::array<float, 2> weights = {1.0f + float(i % 3), i % 5 == 0 ? 0.0f : 1.0f};
        out.push_back(quantize_influences(joints, weights));
        REQUIRE(valid_influences(out.back()));
    }
    return out;
}

}  // namespace

TEST_CASE("skins come back whole, joint for joint, from shuffled and repeated SKIN packets") {
    const SceneDescription scene = skinned_scene();
    const ScenePackets packets = packetize(scene);
    REQUIRE(packets.skins.size() > 2);  // 300 joints of 66 bytes need several 1200-byte packets
    for (const auto& p : packets.skins) {
        PacketView v;
        REQUIRE(parse_packet(p, v) == Error::Ok);
        CHECK(v.header.type == 0x15);
        CHECK(v.header.skippable());
        CHECK(v.header.version_minor == 5);
        CHECK(v.header.object_id == kStreamObjectId);
        CHECK(p.size() <= 1200);
    }
    std::vector<std::vector<uint8_t>> all = packets.skins;
    all.insert(all.end(), packets.skins.begin(), packets.skins.begin() + 2);
    all.insert(all.end(), packets.scene.begin(), packets.scene.end());
    std::mt19937 rng(3);
    std::shuffle(all.begin(), all.end(), rng);
    ReceivedStream stream;
    for (size_t i = 0; i < all.size(); ++i) REQUIRE(stream.add_packet(all[i], i) == Error::Ok);
    CHECK(stream.counters().duplicates == 2);
    REQUIRE(stream.skin_count() == 2);
    REQUIRE(stream.skins().size() == 2);
    for (uint16_t s = 0; s < 2; ++s) {
        const auto& got = stream.skins().at(s);
        CHECK(got.complete());
        CHECK(got.name == scene.skins[s].name);
        CHECK(got.skeleton == scene.skins[s].skeleton);
        REQUIRE(got.joint_count == scene.skins[s].joints.size());
        for (uint16_t j = 0; j < got.joint_count; ++j) CHECK(got.joints.at(j) == scene.skins[s].joints[j]);
    }
    // The node record carries its skin; nodes without one have none.
    CHECK(stream.scene_nodes().at(0).skin == 0);
    CHECK(stream.scene_nodes().at(1).skin == kNone);
    CHECK(stream.newest_minor() == 5);
}

TEST_CASE("a scene without skins is packed as before format 1.5, and says 1.1") {
    SceneDescription scene = skinned_scene();
    scene.skins.clear();
    scene.nodes[0].skin = kNone;
    const ScenePackets packets = packetize(scene);
    CHECK(packets.skins.empty());
    for (const auto& p : packets.scene) {
        PacketView v;
        REQUIRE(parse_packet(p, v) == Error::Ok);
        CHECK(v.header.version_minor == 1);
    }
    // A node record with one stray byte after its transform has no skin (spec 21: two bytes needed).
    SceneBatch batch{1, 0, {}, {}};
    SceneNode n;
    batch.nodes.push_back(n);
    std::vector<uint8_t> payload = encode_scene_payload(batch);
    payload.push_back(0x07);
    payload[8 + 1] += 1;  // the record's length (u16 after the kind byte)
    SceneBatch back;
    REQUIRE(decode_scene_payload(payload, back) == Error::Ok);
    CHECK(back.nodes.at(0).skin == kNone);
    // A node that names a skin it has no mesh for, or one past the table, is refused by the sender.
    SceneDescription bad = skinned_scene();
    bad.nodes[1].skin = 0;
    ScenePackets out;
    CHECK(packetize_scene(bad, 1200, 77, 0, out) == Error::MalformedPayload);
    bad = skinned_scene();
    bad.nodes[0].skin = 2;
    CHECK(packetize_scene(bad, 1200, 77, 0, out) == Error::MalformedPayload);
}

TEST_CASE("a skin with a lost SKIN packet is not complete") {
    const ScenePackets packets = packetize(skinned_scene());
    ReceivedStream stream;
    for (size_t i = 0; i + 1 < packets.skins.size(); ++i) REQUIRE(stream.add_packet(packets.skins[i], i) == Error::Ok);
    CHECK(stream.skins().at(0).complete());
    CHECK_FALSE(stream.skins().at(1).complete());
    CHECK(stream.skins().at(1).joints.size() < 300);
}

TEST_CASE("SKIN packets that are malformed or contradict earlier ones are rejected with their reason") {
    const ScenePackets packets = packetize(skinned_scene());
    const auto& first = packets.skins.front();  // skin 0, all 4 joints
    const size_t joints_at = kSkinHeaderSize + std::string("Arm \xc3\xa4").size();
    struct Case {
        const char* what;
        std::function<void(uint8_t*)> edit;
        Error expected;
    };
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Case> cases = {
        {"skin index at the table size", [](uint8_t* p) { p[0] = 2; }, Error::MalformedPayload},
        {"no joint", [](uint8_t* p) { p[4] = 0, p[5] = 0; }, Error::MalformedPayload},
        {"joints past the count", [](uint8_t* p) { p[6] = 1; }, Error::MalformedPayload},
        {"count 0", [](uint8_t* p) { p[8] = 0; }, Error::MalformedPayload},
        {"count larger than the payload", [](uint8_t* p) { p[8] = 5; }, Error::MalformedPayload},
        {"a matrix entry not finite", [&](uint8_t* p) { std::memcpy(p + joints_at + 2 + 4 * 5, &inf, 4); },
         Error::MalformedPayload},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        ReceivedStream stream;
        CHECK(stream.add_packet(test::edited(first, c.edit), 0) == c.expected);
        CHECK(stream.skins().empty());
    }
    // Comparisons against what was accepted: each rejects the packet and keeps the first.
    const std::vector<Case> mismatches = {
        {"another skin count", [](uint8_t* p) { p[2] = 3; }, Error::StreamMismatch},
        {"another skeleton", [](uint8_t* p) { p[10] = 2; }, Error::StreamMismatch},
        {"another name", [](uint8_t* p) { p[14] = 'a'; }, Error::StreamMismatch},
        {"another joint node", [&](uint8_t* p) { p[joints_at] = 3; }, Error::StreamMismatch},
        {"another matrix entry", [&](uint8_t* p) { p[joints_at + 2 + 4 * 13 + 3] ^= 0x01; }, Error::StreamMismatch},
    };
    for (const Case& c : mismatches) {
        INFO(c.what);
        ReceivedStream stream;
        REQUIRE(stream.add_packet(first, 0) == Error::Ok);
        CHECK(stream.add_packet(test::edited(first, c.edit), 1) == c.expected);
        CHECK(stream.skins().at(0).joints.at(0) == skinned_scene().skins[0].joints[0]);
        CHECK(stream.counters().rejected == 1);
    }
    // -0 and +0 are the same matrix entry: a repeat with +0 where the sender wrote -0 is a duplicate.
    ReceivedStream stream;
    REQUIRE(stream.add_packet(first, 0) == Error::Ok);
    const size_t negative_zero = joints_at + 2 * 66 + 2;  // joint 2's matrix entry 0
    REQUIRE(first[kHeaderSize + negative_zero + 3] == 0x80);
    CHECK(stream.add_packet(test::edited(first, [&](uint8_t* p) { p[negative_zero + 3] = 0; }), 1) == Error::Ok);
    CHECK(stream.counters().duplicates == 1);
}

TEST_CASE("a receiver's memory cap counts the joints it keeps") {
    const ScenePackets packets = packetize(skinned_scene());
    ReceivedStream::Limits limits;
    limits.max_texture_bytes = 128 * 100;  // room for 100 joints
    ReceivedStream stream(limits);
    size_t rejected = 0;
    for (size_t i = 0; i < packets.skins.size(); ++i)
        if (stream.add_packet(packets.skins[i], i) == Error::MalformedPayload) ++rejected;
    CHECK(rejected > 0);
    size_t kept = 0;
    for (const auto& [s, skin] : stream.skins()) kept += skin.joints.size();
    CHECK(kept <= 100);
}

TEST_CASE("influence records: the four largest weights in 255ths that sum to 255") {
    {
        const std::array<uint16_t, 6> joints = {1, 2, 3, 4, 5, 2};
        const std::array<float, 6> weights = {0.1f, 0.2f, 0.3f, 0.05f, 0.15f, 0.2f};  // joint 2 twice: 0.4
        const Influences r = quantize_influences(joints, weights);
        REQUIRE(r.count == 4);
        CHECK(valid_influences(r));
        CHECK(r.joints[0] == 2);
        CHECK(r.joints[1] == 3);
        CHECK(r.joints[2] == 5);
        CHECK(r.joints[3] == 1);
        CHECK(r.weights[0] + r.weights[1] + r.weights[2] + r.weights[3] == 255);
    }
    {
        // A weight that rounds to nothing is left out.
        const std::array<uint16_t, 2> joints = {7, 9};
        const std::array<float, 2> weights = {1.0f, 0.0001f};
        const Influences r = quantize_influences(joints, weights);
        CHECK(r.count == 1);
        CHECK(r.joints[0] == 7);
        CHECK(r.weights[0] == 255);
    }
    {
        const std::array<uint16_t, 3> joints = {0, 1, 2};
        const std::array<float, 3> weights = {1, 1, 1};  // 85 each
        const Influences r = quantize_influences(joints, weights);
        CHECK(r.count == 3);
        CHECK(r.weights[0] == 85);
        CHECK(r.weights[2] == 85);
    }
    const std::array<uint16_t, 1> none = {4};
    const std::array<float, 1> zero = {0};
    CHECK(quantize_influences(none, zero).count == 0);
    Influences bad;
    bad.count = 2;
    bad.joints = {3, 3, 0, 0};
    bad.weights = {100, 155, 0, 0};
    CHECK_FALSE(valid_influences(bad));
}

TEST_CASE("JOINT_WEIGHTS packets carry a record for every point, with one- and two-byte joints") {
    for (bool wide : {false, true}) {
        INFO(wide);
        const SmallStream s = small_stream(1000);
        const std::vector<Influences> records = records_for(1000, wide);
        std::vector<std::vector<uint8_t>> weights;
        REQUIRE(packetize_joint_weights(s.info, 0, records, 77, 0, weights) == Error::Ok);
        REQUIRE(weights.size() > 1);
        for (const auto& p : weights) {
            PacketView v;
            REQUIRE(parse_packet(p, v) == Error::Ok);
            CHECK(v.header.type == 0x07);
            CHECK(v.header.skippable());
            CHECK(v.header.version_minor == 5);
            CHECK(v.header.object_id == 0);
            CHECK(p.size() <= 1200);
            CHECK(v.payload[6] == (wide ? 2 : 1));
        }
        // Weights before the stream info are held and taken when it arrives.
        std::vector<std::vector<uint8_t>> all = weights;
        all.insert(all.end(), s.packets.begin(), s.packets.end());
        all.push_back(weights.front());
        ReceivedStream stream;
        for (size_t i = 0; i < all.size(); ++i) REQUIRE(stream.add_packet(all[i], i) == Error::Ok);
        const ReceivedObject& object = stream.objects().at(0);
        REQUIRE(object.weights.size() == 1000);
        for (uint32_t i = 0; i < 1000; ++i) CHECK(*object.weights.find(i) == records[i]);
        CHECK(stream.counters().duplicates == 1);
    }
    // A record list that does not match the object, or an invalid record, is refused by the sender.
    const SmallStream s = small_stream(10);
    std::vector<std::vector<uint8_t>> out;
    CHECK(packetize_joint_weights(s.info, 0, records_for(9, false), 77, 0, out) == Error::MalformedPayload);
    std::vector<Influences> bad = records_for(10, false);
    bad[3].weights[0] += 1;
    CHECK(packetize_joint_weights(s.info, 0, bad, 77, 0, out) == Error::MalformedPayload);
}

TEST_CASE("JOINT_WEIGHTS packets that are malformed, out of range or contradict earlier ones are rejected") {
    const SmallStream s = small_stream(10);
    std::vector<Influences> records(10);
    for (uint32_t i = 0; i < 10; ++i) {
        records[i].count = 2;
        records[i].joints = {uint16_t(i), uint16_t(i + 1), 0, 0};
        records[i].weights = {200, 55, 0, 0};
    }
    std::vector<std::vector<uint8_t>> weights;
    REQUIRE(packetize_joint_weights(s.info, 0, records, 77, 0, weights) == Error::Ok);
    REQUIRE(weights.size() == 1);
    const auto& packet = weights.front();
    // The payload: first_index, count, joint size 1, reserved, then 10 records of 5 bytes.
    struct Case {
        const char* what;
        std::function<void(std::vector<uint8_t>&)> edit;
        Error expected;
    };
    auto at = [](std::vector<uint8_t>& p, size_t offset) -> uint8_t& { return p[kHeaderSize + offset]; };
    const std::vector<Case> cases = {
        {"count 0", [&](std::vector<uint8_t>& p) { at(p, 4) = 0; }, Error::MalformedPayload},
        {"joint size 3", [&](std::vector<uint8_t>& p) { at(p, 6) = 3; }, Error::MalformedPayload},
        {"no influence", [&](std::vector<uint8_t>& p) { at(p, 8) = 0; }, Error::MalformedPayload},
        {"five influences", [&](std::vector<uint8_t>& p) { at(p, 8) = 5; }, Error::MalformedPayload},
        {"a zero weight", [&](std::vector<uint8_t>& p) { at(p, 11) = 0, at(p, 12) = 255; }, Error::MalformedPayload},
        {"weights summing to 254", [&](std::vector<uint8_t>& p) { at(p, 11) = 199; }, Error::MalformedPayload},
        {"a joint named twice", [&](std::vector<uint8_t>& p) { at(p, 10) = at(p, 9); }, Error::MalformedPayload},
        {"a point fewer than the records", [&](std::vector<uint8_t>& p) { at(p, 4) = 9; }, Error::MalformedPayload},
        {"a point more than the records", [&](std::vector<uint8_t>& p) { at(p, 4) = 11; }, Error::MalformedPayload},
        {"first_index + count past 2^32 - 1",
         [&](std::vector<uint8_t>& p) { at(p, 0) = 0xFF, at(p, 1) = 0xFF, at(p, 2) = 0xFF, at(p, 3) = 0xFF; },
         Error::MalformedPayload},
        {"points past the object's count", [&](std::vector<uint8_t>& p) { at(p, 0) = 1; }, Error::IndexOutOfRange},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        std::vector<uint8_t> p = packet;
        c.edit(p);
        ReceivedStream stream;
        for (size_t i = 0; i < s.packets.size(); ++i) REQUIRE(stream.add_packet(s.packets[i], i) == Error::Ok);
        CHECK(stream.add_packet(test::resealed(p), 100) == c.expected);
        CHECK(stream.objects().at(0).weights.empty());
    }
    {
        // Trailing bytes after the last record.
        std::vector<uint8_t> p(packet.begin() + long(kHeaderSize), packet.end() - long(kChecksumSize));
        p.push_back(0);
        JointWeightsRun run;
        CHECK(decode_joint_weights_payload(p, run) == Error::MalformedPayload);
    }
    // Another record for a point held: rejected, the first kept.
    ReceivedStream stream;
    for (size_t i = 0; i < s.packets.size(); ++i) REQUIRE(stream.add_packet(s.packets[i], i) == Error::Ok);
    REQUIRE(stream.add_packet(packet, 100) == Error::Ok);
    std::vector<uint8_t> other = packet;
    at(other, 8 + 5 * 9 + 3) = 201;  // the last point's weights 201 + 54
    at(other, 8 + 5 * 9 + 4) = 54;
    CHECK(stream.add_packet(test::resealed(other), 101) == Error::StreamMismatch);
    CHECK(*stream.objects().at(0).weights.find(9) == records[9]);
    // The same records with two-byte joints are the same records: a duplicate.
    const JointWeightsRun run{0, records};
    std::vector<uint8_t> payload = encode_joint_weights_payload(run);
    REQUIRE(payload[6] == 1);
    std::vector<uint8_t> wide = {payload.begin(), payload.begin() + 8};
    wide[6] = 2;
    for (const Influences& r : records) {
        wide.push_back(r.count);
        for (size_t k = 0; k < r.count; ++k) wide.push_back(uint8_t(r.joints[k])), wide.push_back(0);
        for (size_t k = 0; k < r.count; ++k) wide.push_back(r.weights[k]);
    }
    std::vector<uint8_t> wide_packet(packet.begin(), packet.begin() + long(kHeaderSize));
    wide_packet.insert(wide_packet.end(), wide.begin(), wide.end());
    wide_packet.resize(wide_packet.size() + kChecksumSize);
    const uint16_t length = uint16_t(wide.size());
    std::memcpy(wide_packet.data() + kHeaderSize - 2, &length, 2);  // payload_length, the header's last field
    CHECK(stream.add_packet(test::resealed(wide_packet), 102) == Error::Ok);
    CHECK(stream.counters().duplicates == 1);
}
