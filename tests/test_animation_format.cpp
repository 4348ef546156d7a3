// ANIMATION packets (format 1.4, spec 20): cutting animations into packets and what a receiver keeps.
#include "broadcast_support.h"

#include "ellicast/format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

using namespace ellicast;

namespace {

// Two nodes; animation 0 turns node 1 (LINEAR rotation, 300 keys) and moves node 0 (STEP
// translation, 5 keys); animation 1 scales node 1 with a cubic spline of 40 keys.
SceneDescription animated_scene() {
    SceneDescription scene;
    for (uint16_t i = 0; i < 2; ++i) {
        SceneNode n;
        n.index = i;
        n.parent = i == 0 ? kNone : 0;
        n.name = "node " + std::to_string(i);
        scene.nodes.push_back(n);
    }
    SceneAnimation spin;
    spin.name = "Spin";
    SceneAnimation::Track turn{1, AnimationPath::Rotation, Interpolation::Linear, 0, {}, {}};
    for (int k = 0; k < 300; ++k) {
        const float a = 0.01f * float(k);
        turn.times.push_back(0.04f * float(k));
        for (float v : {0.0f, std::sin(a), 0.0f, std::cos(a)}) turn.values.push_back(v);
    }
    SceneAnimation::Track hop{0, AnimationPath::Translation, Interpolation::Step, 0, {}, {}};
    for (int k = 0; k < 5; ++k) {
        hop.times.push_back(float(k));
        for (float v : {float(k), 0.5f * float(k % 2), -0.0f}) hop.values.push_back(v);
    }
    spin.tracks = {turn, hop};
    SceneAnimation grow;
    grow.name = "Grow \xc3\xbc";
    SceneAnimation::Track scale{1, AnimationPath::Scale, Interpolation::CubicSpline, 0, {}, {}};
    for (int k = 0; k < 40; ++k) {
        scale.times.push_back(0.1f * float(k) + 0.5f);
        for (int v = 0; v < 9; ++v) scale.values.push_back(v % 3 == 1 ? 1.0f + 0.01f * float(k) : 0.0f);
    }
    grow.tracks = {scale};
    scene.animations = {spin, grow};
    return scene;
}

ScenePackets packetize(const SceneDescription& scene, size_t packet_size = 400) {
    ScenePackets packets;
    REQUIRE(packetize_scene(scene, packet_size, 77, 0, packets) == Error::Ok);
    return packets;
}


void put_f32_at(uint8_t* p, float f) { std::memcpy(p, &f, 4); }

}  // namespace

TEST_CASE("animations come back whole, key for key, from shuffled and repeated ANIMATION packets") {
    const SceneDescription scene = animated_scene();
    const ScenePackets packets = packetize(scene);
    REQUIRE(packets.animations.size() > 3);  // the 300 rotation keys need several packets of 400 bytes
    for (const auto& p : packets.animations) {
        PacketView v;
        REQUIRE(parse_packet(p, v) == Error::Ok);
        CHECK(v.header.type == 0x14);
        CHECK(v.header.skippable());
        CHECK(v.header.version_minor == 4);
        CHECK(p.size() <= 400);
    }
    std::vector<std::vector<uint8_t>> all = packets.animations;
    all.insert(all.end(), packets.animations.begin(), packets.animations.begin() + 3);
    std::mt19937 rng(5);
    std::shuffle(all.begin(), all.end(), rng);
    ReceivedStream stream;
    for (size_t i = 0; i < all.size(); ++i) REQUIRE(stream.add_packet(all[i], i) == Error::Ok);
    CHECK(stream.counters().accepted == packets.animations.size());
    CHECK(stream.counters().duplicates == 3);
    REQUIRE(stream.animation_count() == 2);
    REQUIRE(stream.animations().size() == 2);
    for (uint16_t a = 0; a < 2; ++a) {
        const auto& got = stream.animations().at(a);
        CHECK(got.complete());
        CHECK(got.name == scene.animations[a].name);
        REQUIRE(got.track_count == scene.animations[a].tracks.size());
        for (uint16_t t = 0; t < got.track_count; ++t) {
            const auto& track = got.tracks.at(t);
            const auto& sent = scene.animations[a].tracks[t];
            CHECK(track.usable);
            CHECK(track.info.node == sent.node);
            CHECK(track.info.path == sent.path);
            CHECK(track.info.interpolation == sent.interpolation);
            CHECK(track.times == sent.times);
            CHECK(track.values == sent.values);
        }
    }
}

TEST_CASE("an animation with a missing packet is not complete, while its other tracks are") {
    const ScenePackets packets = packetize(animated_scene());
    ReceivedStream stream;
    for (size_t i = 1; i < packets.animations.size(); ++i) REQUIRE(stream.add_packet(packets.animations[i], i) == Error::Ok);
    const auto& spin = stream.animations().at(0);
    CHECK_FALSE(spin.complete());
    CHECK_FALSE(spin.tracks.at(0).complete);
    CHECK(spin.tracks.at(0).keys_held < 300);
    CHECK(spin.tracks.at(1).complete);
    CHECK(stream.animations().at(1).complete());
}

TEST_CASE("ANIMATION packets that are malformed or contradict earlier ones are rejected with their reason") {
    const ScenePackets packets = packetize(animated_scene());
    const auto& first = packets.animations.front();  // animation 0, track 0, keys 0..
    struct Case {
        const char* what;
        std::function<void(uint8_t*)> edit;
        Error expected;
    };
    const std::vector<Case> cases = {
        {"path 3", [](uint8_t* p) { p[10] = 3; }, Error::MalformedPayload},
        {"interpolation 3", [](uint8_t* p) { p[11] = 3; }, Error::MalformedPayload},
        {"animation past the table", [](uint8_t* p) { p[0] = 2; }, Error::MalformedPayload},
        {"track past the animation", [](uint8_t* p) { p[4] = 2; }, Error::MalformedPayload},
        {"no key", [](uint8_t* p) { p[20] = 0, p[21] = 0; }, Error::MalformedPayload},
        {"keys past key_count", [](uint8_t* p) { p[12] = 3, p[13] = 0, p[14] = 0, p[15] = 0; }, Error::MalformedPayload},
        {"a negative time", [](uint8_t* p) { put_f32_at(p + 24 + 4, -1.0f); }, Error::MalformedPayload},
        {"times that do not increase", [](uint8_t* p) { put_f32_at(p + 24 + 4 + 20, 0.0f); }, Error::MalformedPayload},
        {"a value that is not finite", [](uint8_t* p) { put_f32_at(p + 24 + 4 + 4, INFINITY); }, Error::MalformedPayload},
        {"another table size", [](uint8_t* p) { p[2] = 3; }, Error::StreamMismatch},
        {"another node", [](uint8_t* p) { p[8] = 0; }, Error::StreamMismatch},
        {"another key value", [](uint8_t* p) { put_f32_at(p + 24 + 4 + 4, 0.5f); }, Error::StreamMismatch},
    };
    for (const auto& c : cases) {
        CAPTURE(c.what);
        ReceivedStream stream;
        REQUIRE(stream.add_packet(first, 0) == Error::Ok);
        CHECK(stream.add_packet(test::edited(first, c.edit), 1) == c.expected);
        CHECK(stream.counters().accepted == 1);
        // What was accepted stays.
        CHECK(stream.animations().at(0).tracks.at(0).keys_held > 0);
    }
    // -0 and +0 agree.
    ReceivedStream stream;
    const auto& step = *std::find_if(packets.animations.begin(), packets.animations.end(), [](const auto& p) {
        return p[kHeaderSize + 4] == 1 && p[kHeaderSize] == 0;  // animation 0, track 1: values end in -0
    });
    REQUIRE(stream.add_packet(step, 0) == Error::Ok);
    const auto plus_zero = test::edited(step, [](uint8_t* p) { put_f32_at(p + 24 + 4 + 4 + 8, 0.0f); });
    CHECK(stream.add_packet(plus_zero, 1) == Error::Ok);
    CHECK(stream.counters().duplicates == 1);
}

TEST_CASE("a track whose times go back across packets is complete but not usable") {
    SceneDescription scene = animated_scene();
    ScenePackets packets = packetize(scene);
    // Animation 0 track 0's second packet, its times moved below those of the first.
    auto second = std::find_if(packets.animations.begin(), packets.animations.end(), [](const auto& p) {
        return p[kHeaderSize] == 0 && p[kHeaderSize + 4] == 0 && p[kHeaderSize + 16] != 0;
    });
    REQUIRE(second != packets.animations.end());
    *second = test::edited(*second, [](uint8_t* p) {
        const uint16_t count = uint16_t(p[20] | p[21] << 8);
        for (uint16_t k = 0; k < count; ++k) put_f32_at(p + 24 + 4 + size_t(k) * 20, 0.001f * float(k));  // after the name "Spin"
    });
    ReceivedStream stream;
    for (size_t i = 0; i < packets.animations.size(); ++i) REQUIRE(stream.add_packet(packets.animations[i], i) == Error::Ok);
    const auto& track = stream.animations().at(0).tracks.at(0);
    CHECK(track.complete);
    CHECK_FALSE(track.usable);
}

TEST_CASE("animation keys count toward the receiver's memory cap, and keys announced cost nothing") {
    const ScenePackets packets = packetize(animated_scene());
    ReceivedStream::Limits limits;
    limits.max_texture_bytes = 1000;
    ReceivedStream stream(limits);
    size_t rejected = 0;
    for (size_t i = 0; i < packets.animations.size(); ++i)
        if (stream.add_packet(packets.animations[i], i) == Error::MalformedPayload) ++rejected;
    CHECK(rejected > 0);
    CHECK(stream.counters().accepted > 0);
    // A single key announcing a track of 4 billion keys is taken without reserving them.
    AnimationPiece piece;
    piece.animation_count = 1;
    piece.track_count = 1;
    piece.info = {0, AnimationPath::Scale, Interpolation::Linear, 0xFFFFFFFFu};
    piece.first_key = 0xFFFFFFFEu;
    piece.times = {1};
    piece.values = {1, 1, 1};
    PacketHeader h;
    h.version_minor = 4;
    h.type = 0x14;
    h.flags = kFlagSkippable;
    h.object_id = kStreamObjectId;
    ReceivedStream big;
    CHECK(big.add_packet(write_packet(h, encode_animation_payload(piece)), 0) == Error::Ok);
    CHECK(big.animations().at(0).tracks.at(0).keys_held == 1);
}

TEST_CASE("animations a sender cannot send are refused when packetizing") {
    auto refused = [](const std::function<void(SceneDescription&)>& edit) {
        SceneDescription scene = animated_scene();
        edit(scene);
        ScenePackets packets;
        return packetize_scene(scene, 400, 1, 0, packets) == Error::MalformedPayload;
    };
    CHECK(refused([](SceneDescription& s) { s.animations[0].tracks[0].node = 2; }));
    CHECK(refused([](SceneDescription& s) { s.animations[0].tracks[0].times[3] = 0; }));
    CHECK(refused([](SceneDescription& s) { s.animations[0].tracks[0].values.pop_back(); }));
    CHECK(refused([](SceneDescription& s) { s.animations[0].tracks.clear(); }));
    CHECK(refused([](SceneDescription& s) { s.animations[1].tracks[0].times.resize(1), s.animations[1].tracks[0].values.resize(9); }));
    CHECK(refused([](SceneDescription& s) { s.animations[0].tracks[1].values[0] = NAN; }));
}
