// Format 1.0 packets and quantization (spec/format.md sections 3 to 8): the checksum, bit-flip
// detection at every bit of a packet, round trips of every payload, refusal of every inconsistent
// length, and the quantization error bounds the spec states, measured over random inputs.
#include "support.h"

#include <ellicast/format.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace ellicast;

namespace {

using Packet = std::vector<uint8_t>;

struct Rng {
    std::mt19937_64 engine;
    explicit Rng(uint64_t seed) : engine(seed) {}
    double uniform(double a = 0, double b = 1) { return std::uniform_real_distribution<double>(a, b)(engine); }
    uint32_t below(uint32_t n) { return static_cast<uint32_t>(engine() % n); }
};

std::array<float, 4> random_rotation(Rng& rng) {
    double u1 = rng.uniform(), u2 = rng.uniform(0, 2 * M_PI), u3 = rng.uniform(0, 2 * M_PI);
    double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return {float(a * std::sin(u2)), float(a * std::cos(u2)), float(b * std::sin(u3)), float(b * std::cos(u3))};
}

std::array<float, 3> random_unit(Rng& rng) {
    double z = rng.uniform(-1, 1), phi = rng.uniform(0, 2 * M_PI), r = std::sqrt(1 - z * z);
    return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
}

// Rotation matrix of a unit quaternion (w, x, y, z); column i is the direction of semi-axis i.
std::array<std::array<double, 3>, 3> rotation_matrix(const std::array<float, 4>& q) {
    double w = q[0], x = q[1], y = q[2], z = q[3];
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

std::array<double, 3> surface_point(const Ellipsoid& e, const std::array<double, 3>& u) {
    auto R = rotation_matrix(e.rotation);
    std::array<double, 3> p;
    for (int i = 0; i < 3; ++i) {
        p[i] = e.center[i];
        for (int k = 0; k < 3; ++k) p[i] += R[i][k] * e.radii[k] * u[k];
    }
    return p;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// A small stream with every packet type, at the given packet size.
struct Sample {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    StreamPackets packets;
};

Sample sample_stream(uint16_t packet_size, uint8_t attributes, int seed, uint32_t ellipsoids = 40, uint32_t points = 300) {
    Sample s;
    Rng rng(seed);
    s.info.packet_size = packet_size;
    ObjectInfo o;
    o.frame = {{-2, -1, 0.5f}, 3};
    o.ellipsoid_count = ellipsoids;
    o.point_count = points;
    o.attributes = attributes;
    s.info.objects = {o};
    ObjectContent c;
    for (uint32_t i = 0; i < ellipsoids; ++i) {
        Ellipsoid e;
        for (int k = 0; k < 3; ++k) {
            e.center[k] = float(o.frame.origin[k] + rng.uniform(0, 1) * o.frame.scale);
            e.radii[k] = float(rng.uniform(0, 0.5) * o.frame.scale);
        }
        e.rotation = random_rotation(rng);
        c.ellipsoids.push_back(quantize_ellipsoid(e, o.frame));
    }
    for (uint32_t i = 0; i < points; ++i) {
        SurfacePoint p;
        for (int k = 0; k < 3; ++k) p.position[k] = float(o.frame.origin[k] + rng.uniform(0, 1) * o.frame.scale);
        p.normal = random_unit(rng);
        p.texcoord = {float(rng.uniform()), float(rng.uniform())};
        p.color = {float(rng.uniform()), float(rng.uniform()), float(rng.uniform()), float(rng.uniform())};
        c.points.push_back(quantize_point(p, s.info, o));
    }
    s.contents = {c};
    REQUIRE(packetize_stream(s.info, s.contents, 42, s.packets) == Error::Ok);
    return s;
}

bool same(const QuantizedEllipsoid& a, const QuantizedEllipsoid& b) {
    return a.center == b.center && a.radii == b.radii && a.largest == b.largest && a.rotation == b.rotation;
}

bool same(const QuantizedPoint& a, const QuantizedPoint& b, const ObjectInfo& o) {
    if (a.position != b.position) return false;
    if (o.has(kAttrNormal) && a.normal != b.normal) return false;
    if (o.has(kAttrTexcoord) && a.texcoord != b.texcoord) return false;
    for (int i = 0; i < o.color_channels(); ++i)
        if (a.color[i] != b.color[i]) return false;
    return true;
}

}  // namespace

TEST_CASE("CRC-32C has the check value of the Castagnoli CRC and continues over split input") {
    const char* text = "123456789";
    CHECK(crc32c(reinterpret_cast<const uint8_t*>(text), 9) == 0xE3069283u);
    uint32_t part = crc32c(reinterpret_cast<const uint8_t*>(text), 4);
    CHECK(crc32c(reinterpret_cast<const uint8_t*>(text) + 4, 5, part) == 0xE3069283u);
    CHECK(crc32c(nullptr, 0) == 0);
    // Long input (the SSE 4.2 and table paths agree with a bitwise reference).
    std::vector<uint8_t> data(1000);
    for (size_t i = 0; i < data.size(); ++i) data[i] = uint8_t(i * 7 + 3);
    uint32_t c = 0xFFFFFFFFu;
    for (uint8_t b : data) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0x82F63B78u & (0u - (c & 1u)));
    }
    CHECK(crc32c(data.data(), data.size()) == (c ^ 0xFFFFFFFFu));
}

TEST_CASE("a packet has the header layout of the spec, little-endian, with the CRC-32C of header and payload") {
    PacketHeader h;
    h.version_minor = 0;
    h.type = 0x02;
    h.stream_id = 0x11223344;
    h.sequence = 0x55667788;
    h.object_id = 0x0102;
    std::vector<uint8_t> payload = {1, 2, 3};
    Packet p = write_packet(h, payload);
    REQUIRE(p.size() == 27);
    const std::vector<uint8_t> head = {0xE1, 0x4C, 0x43, 0x53, 1, 0, 2, 0, 0x44, 0x33, 0x22, 0x11,
                                       0x88, 0x77, 0x66, 0x55, 0x02, 0x01, 3, 0};
    CHECK(std::equal(head.begin(), head.end(), p.begin()));
    uint32_t crc = crc32c(p.data(), 23);
    CHECK(p[23] == uint8_t(crc));
    CHECK(p[26] == uint8_t(crc >> 24));
    PacketView view;
    REQUIRE(parse_packet(p, view) == Error::Ok);
    CHECK(view.header.stream_id == 0x11223344u);
    CHECK(view.header.sequence == 0x55667788u);
    CHECK(view.header.object_id == 0x0102);
    CHECK(view.payload.size() == 3);
}

TEST_CASE("a single flipped bit anywhere in a packet is detected") {
    // Full-size packets of every type at the default packet size, every bit position of each.
    Sample s = sample_stream(kDefaultPacketSize, kAttrNormal | kAttrTexcoord | kAttrColor, 1, 200, 600);
    std::vector<Packet> packets = {s.packets.stream_info[0], s.packets.ellipsoids[0], s.packets.points[0]};
    for (const Packet& original : packets) {
        PacketView view;
        REQUIRE(parse_packet(original, view) == Error::Ok);
        CAPTURE(packet_type_name(view.header.type));
        CAPTURE(original.size());
        size_t undetected = 0;
        for (size_t bit = 0; bit < original.size() * 8; ++bit) {
            Packet damaged = original;
            damaged[bit / 8] ^= uint8_t(1u << (bit % 8));
            if (parse_packet(damaged, view) == Error::Ok) ++undetected;
            ReceivedStream stream;
            if (stream.add_packet(damaged, 0) == Error::Ok) ++undetected;
        }
        CHECK(undetected == 0);
    }
}

TEST_CASE("a packet cut at any length, or followed by extra bytes, is refused") {
    Sample s = sample_stream(600, kAttrColor, 2);
    const Packet& p = s.packets.points[0];
    PacketView view;
    for (size_t n = 0; n < p.size(); ++n) {
        Error e = parse_packet(std::span<const uint8_t>(p.data(), n), view);
        CHECK((e == (n < kPacketOverhead ? Error::TooShort : Error::Truncated)));
    }
    Packet longer = p;
    longer.push_back(0);
    CHECK(parse_packet(longer, view) == Error::LengthMismatch);
    CHECK(parse_packet_prefix(longer, view) == Error::Ok);
}

TEST_CASE("a header's checks come in the order of the spec") {
    PacketHeader h;
    h.type = 0x03;
    Packet p = write_packet(h, std::vector<uint8_t>(10, 0));
    auto reseal = [](Packet& q) {
        uint32_t crc = crc32c(q.data(), q.size() - 4);
        std::memcpy(q.data() + q.size() - 4, &crc, 4);
    };
    PacketView view;
    Packet q = p;
    q[4] = 2;
    CHECK(parse_packet(q, view) == Error::UnsupportedMajor);  // even with a bad checksum
    q = p;
    q[18] = 0xFF, q[19] = 0xFF;
    CHECK(parse_packet(q, view) == Error::Oversized);
    q = p;
    q[6] = 0;
    CHECK(parse_packet(q, view) == Error::BadChecksum);  // a damaged type byte is damage, not type 0
    reseal(q);
    CHECK(parse_packet(q, view) == Error::InvalidType);
    q = p;
    q[6] = 0x7E;
    reseal(q);
    CHECK(parse_packet(q, view) == Error::Ok);  // unknown types are the receiver's business
    ReceivedStream stream;
    CHECK(stream.add_packet(q, 0) == Error::UnknownCriticalType);
    q[7] = kFlagSkippable;
    reseal(q);
    CHECK(stream.add_packet(q, 1) == Error::Ok);
    CHECK(stream.counters().skipped == 1);
}

TEST_CASE("every payload type round-trips through its encoder and decoder") {
    Rng rng(3);
    SUBCASE("ellipsoids: every field value survives packing") {
        for (int i = 0; i < 2000; ++i) {
            QuantizedEllipsoid q;
            for (auto& v : q.center) v = uint16_t(rng.below(32768));
            for (auto& v : q.radii) v = uint16_t(rng.below(8192));
            q.largest = uint8_t(rng.below(4));
            for (auto& v : q.rotation) v = uint16_t(rng.below(16384));
            if (i == 0) q.center = {32767, 32767, 32767}, q.radii = {8191, 8191, 8191}, q.largest = 3, q.rotation = {16383, 16383, 16383};
            uint8_t bytes[kEllipsoidBytes];
            pack_ellipsoid(q, bytes);
            CHECK(same(unpack_ellipsoid(bytes), q));
        }
        EllipsoidBatch batch;
        batch.first_index = 123456;
        for (int i = 0; i < 50; ++i) {
            QuantizedEllipsoid q;
            q.center = {uint16_t(i), uint16_t(2 * i), uint16_t(3 * i)};
            batch.ellipsoids.push_back(q);
        }
        auto payload = encode_ellipsoids_payload(batch);
        CHECK(payload.size() == 8 + 16 * 50);
        EllipsoidBatch back;
        REQUIRE(decode_ellipsoids_payload(payload, back) == Error::Ok);
        CHECK(back.first_index == 123456);
        REQUIRE(back.ellipsoids.size() == 50);
        for (int i = 0; i < 50; ++i) CHECK(same(back.ellipsoids[i], batch.ellipsoids[i]));
    }
    SUBCASE("points: every attribute combination at every bit depth") {
        for (uint8_t attributes = 0; attributes <= kAttrKnownMask; ++attributes) {
            if ((attributes & kAttrColorAlpha) && !(attributes & kAttrColor)) continue;
            for (int bits = 2; bits <= 16; ++bits) {
                StreamInfo info;
                info.position_bits = uint8_t(std::clamp(bits, 8, 16));
                info.normal_bits = uint8_t(std::clamp(bits, 4, 16));
                info.texcoord_bits = uint8_t(std::clamp(bits, 4, 16));
                info.color_bits = uint8_t(bits);
                ObjectInfo o;
                o.attributes = attributes;
                PointBatch batch;
                batch.first_index = 7;
                for (int i = 0; i < 37; ++i) {
                    QuantizedPoint q;
                    for (auto& v : q.position) v = rng.below(1u << info.position_bits);
                    for (auto& v : q.normal) v = rng.below(1u << info.normal_bits);
                    for (auto& v : q.texcoord) v = rng.below(1u << info.texcoord_bits);
                    for (auto& v : q.color) v = rng.below(1u << info.color_bits);
                    batch.points.push_back(q);
                }
                auto payload = encode_points_payload(batch, info, o);
                CHECK(payload.size() == 8 + (37 * point_record_bits(info, o) + 7) / 8);
                PointBatch back;
                REQUIRE(decode_points_payload(payload, info, o, back) == Error::Ok);
                REQUIRE(back.points.size() == 37);
                bool all_same = true;
                for (int i = 0; i < 37; ++i) all_same &= same(back.points[i], batch.points[i], o);
                CHECK_MESSAGE(all_same, "attributes " << int(attributes) << " bits " << bits);
            }
        }
    }
    SUBCASE("stream info: every field, in parts") {
        StreamInfo info;
        info.packet_size = 777;
        info.position_bits = 11;
        info.normal_bits = 9;
        info.texcoord_bits = 13;
        info.color_bits = 5;
        info.content_id = 0xDEADBEEF;
        info.grid_hint = 96;
        info.coverage_target = 0.9f;
        info.seed = 99;
        for (int i = 0; i < 5; ++i) {
            ObjectInfo o;
            o.frame = {{float(i), -float(i), 0.25f}, 1.5f + i};
            o.ellipsoid_count = i == 3 ? 0 : 10 * i;
            o.point_count = 100000u * i;
            o.kind = i == 3 ? ObjectKind::PointSet : ObjectKind::Surface;
            o.attributes = uint8_t(i % 4 == 0 ? kAttrColor | kAttrColorAlpha : i);
            o.texcoord_origin = {-1, 2};
            o.texcoord_scale = {3, 0};
            info.objects.push_back(o);
        }
        auto payload = encode_stream_info_payload(info, 2, 3);
        CHECK(payload.size() == kStreamInfoFixedSize + 3 * kObjectEntrySize);
        StreamInfoPart part;
        REQUIRE(decode_stream_info_payload(payload, part) == Error::Ok);
        CHECK(part.object_count == 5);
        CHECK(part.first_object == 2);
        REQUIRE(part.info.objects.size() == 3);
        for (int i = 0; i < 3; ++i) CHECK(part.info.objects[i] == info.objects[2 + i]);
        CHECK(part.info.packet_size == 777);
        CHECK(part.info.position_bits == 11);
        CHECK(part.info.normal_bits == 9);
        CHECK(part.info.texcoord_bits == 13);
        CHECK(part.info.color_bits == 5);
        CHECK(part.info.content_id == 0xDEADBEEFu);
        CHECK(part.info.grid_hint == 96);
        CHECK(part.info.coverage_target == 0.9f);
        CHECK(part.info.seed == 99u);
    }
    SUBCASE("a whole stream: packetized and received in any order, the same integers come back") {
        Sample s = sample_stream(300, kAttrNormal | kAttrColor | kAttrColorAlpha, 4);
        std::vector<Packet> all = s.packets.points;
        all.insert(all.end(), s.packets.ellipsoids.begin(), s.packets.ellipsoids.end());
        all.insert(all.end(), s.packets.stream_info.begin(), s.packets.stream_info.end());
        for (const Packet& p : all) CHECK(p.size() <= 300);
        ReceivedStream stream;
        for (size_t i = 0; i < all.size(); ++i) CHECK(stream.add_packet(all[i], i) == Error::Ok);
        REQUIRE(stream.objects().size() == 1);
        const ReceivedObject& o = stream.objects()[0];
        REQUIRE(o.ellipsoids.size() == s.contents[0].ellipsoids.size());
        REQUIRE(o.points.size() == s.contents[0].points.size());
        for (const auto& [i, q] : o.ellipsoids) CHECK(same(*q, s.contents[0].ellipsoids[i]));
        bool all_same = true;
        for (const auto& [i, q] : o.points) all_same &= same(q, s.contents[0].points[i], s.info.objects[0]);
        CHECK(all_same);
        CHECK(stream.counters().pending == 0);
    }
}

TEST_CASE("payload decoders refuse every inconsistent length without reading outside the payload") {
    Sample s = sample_stream(600, kAttrNormal | kAttrTexcoord | kAttrColor, 5);
    auto payload_of = [](const Packet& p) { return std::vector<uint8_t>(p.begin() + kHeaderSize, p.end() - kChecksumSize); };
    // Every shorter and a longer payload; the decoders get exactly that many bytes (ASan catches overreads).
    auto check_lengths = [](const std::vector<uint8_t>& payload, auto decode) {
        for (size_t n = 0; n <= payload.size() + 1; ++n) {
            std::vector<uint8_t> cut(payload.begin(), payload.begin() + std::min(n, payload.size()));
            if (n > payload.size()) cut.push_back(0);
            Error e = decode(std::span<const uint8_t>(cut));
            CHECK((e == (n == payload.size() ? Error::Ok : Error::MalformedPayload)));
        }
    };
    check_lengths(payload_of(s.packets.stream_info[0]), [](std::span<const uint8_t> b) {
        StreamInfoPart part;
        return decode_stream_info_payload(b, part);
    });
    check_lengths(payload_of(s.packets.ellipsoids[0]), [](std::span<const uint8_t> b) {
        EllipsoidBatch batch;
        return decode_ellipsoids_payload(b, batch);
    });
    check_lengths(payload_of(s.packets.points[0]), [&](std::span<const uint8_t> b) {
        PointBatch batch;
        return decode_points_payload(b, s.info, s.info.objects[0], batch);
    });
}

TEST_CASE("stream info out of range is refused: bit depths, packet size, frames, kinds, attributes") {
    StreamInfo good;
    ObjectInfo o;
    good.objects = {o};
    REQUIRE(check_stream_info(good) == Error::Ok);
    auto bad = [&](auto edit) {
        StreamInfo s = good;
        edit(s);
        return check_stream_info(s) == Error::MalformedPayload;
    };
    CHECK(bad([](StreamInfo& s) { s.position_bits = 7; }));
    CHECK(bad([](StreamInfo& s) { s.position_bits = 17; }));
    CHECK(bad([](StreamInfo& s) { s.normal_bits = 3; }));
    CHECK(bad([](StreamInfo& s) { s.texcoord_bits = 17; }));
    CHECK(bad([](StreamInfo& s) { s.color_bits = 1; }));
    CHECK(bad([](StreamInfo& s) { s.packet_size = 127; }));
    CHECK(bad([](StreamInfo& s) { s.packet_size = 65001; }));
    CHECK(bad([](StreamInfo& s) { s.ellipsoid_encoding = 1; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].frame.scale = 0; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].frame.scale = NAN; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].frame.origin[1] = INFINITY; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].kind = ObjectKind(2); }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].attributes = 0x10; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].attributes = kAttrColorAlpha; }));
    CHECK(bad([](StreamInfo& s) { s.objects[0].texcoord_scale[0] = -1; }));
    CHECK(bad([](StreamInfo& s) {
        s.objects[0].kind = ObjectKind::PointSet;
        s.objects[0].ellipsoid_count = 1;
    }));
    CHECK_FALSE(bad([](StreamInfo& s) { s.packet_size = 128; }));
    CHECK_FALSE(bad([](StreamInfo& s) { s.packet_size = 65000; }));
}

TEST_CASE("ellipsoid quantization error stays within the bounds of spec section 8.1") {
    Rng rng(6);
    const double e = std::sqrt(2.0) / 32766;
    const double theta_max = 2 * std::asin(std::sqrt(12.0) * e);
    double worst_center = 0, worst_radius = 0, worst_angle = 0, worst_surface_ratio = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const double scale = std::exp(rng.uniform(std::log(0.01), std::log(1000.0)));
        Frame f{{float(rng.uniform(-1, 1) * scale), float(rng.uniform(-1, 1) * scale), float(rng.uniform(-1, 1) * scale)},
                float(scale)};
        const double s = f.scale;
        // Rounding of the f32 outputs: two ulps of the largest coordinate involved (|origin| + s <= 2 s).
        const double slack = 2 * 1.2e-7 * 2 * s;
        Ellipsoid in;
        for (int k = 0; k < 3; ++k) {
            in.center[k] = float(f.origin[k] + rng.uniform(0, 1) * s);
            in.radii[k] = float(rng.uniform(0, 1) * s * (trial % 3 == 0 ? 0.05 : 1.0));
        }
        in.rotation = random_rotation(rng);
        if (trial % 97 == 0) in.rotation = {0.5f, -0.5f, 0.5f, -0.5f};  // the smallest possible largest component
        Ellipsoid out = dequantize_ellipsoid(quantize_ellipsoid(in, f), f);
        double r_max = 0;
        for (int k = 0; k < 3; ++k) {
            double dc = std::fabs(double(out.center[k]) - in.center[k]);
            double dr = std::fabs(double(out.radii[k]) - in.radii[k]);
            CHECK(dc <= s / 65534 + slack);
            CHECK(dr <= s / 16382 + slack);
            worst_center = std::max(worst_center, dc / s);
            worst_radius = std::max(worst_radius, dr / s);
            r_max = std::max(r_max, double(in.radii[k]));
        }
        // Rotation angle between the two: for unit quaternions at chord distance d (sign aligned), 4 asin(d / 2).
        double qi[4], n = 0, dot = 0, chord = 0;
        for (int k = 0; k < 4; ++k) n += double(in.rotation[k]) * in.rotation[k];
        for (int k = 0; k < 4; ++k) qi[k] = in.rotation[k] / std::sqrt(n), dot += qi[k] * out.rotation[k];
        for (int k = 0; k < 4; ++k) chord += std::pow(qi[k] - (dot < 0 ? -1 : 1) * double(out.rotation[k]), 2);
        double angle = 4 * std::asin(std::sqrt(chord) / 2);
        CHECK(angle <= theta_max + 1e-6);  // f32 quaternion components: about 1e-7 each
        worst_angle = std::max(worst_angle, angle);
        // Surface: the image of a surface point moves at most E(r_max).
        const double bound = std::sqrt(3.0) * s / 65534 + s / 16382 + 2 * std::sin(theta_max / 2) * r_max;
        CHECK(bound <= ellipsoid_error_bound(f, r_max) + 1e-12 * s);
        double worst_here = 0;
        for (int d = 0; d < 26; ++d) {
            std::array<double, 3> u = {double(d % 3) - 1, double(d / 3 % 3) - 1, double(d / 9 % 3) - 1};
            if (d == 13) u = {1, 0, 0};
            double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            for (auto& x : u) x /= n;
            worst_here = std::max(worst_here, distance(surface_point(in, u), surface_point(out, u)));
        }
        CHECK(worst_here <= bound + 2 * slack);
        worst_surface_ratio = std::max(worst_surface_ratio, worst_here / (bound + 2 * slack));
    }
    MESSAGE("ellipsoids: worst centre error " << worst_center << " s (bound " << 1.0 / 65534 << "), radius "
                                              << worst_radius << " s (bound " << 1.0 / 16382 << "), rotation "
                                              << worst_angle << " rad (bound " << theta_max << "), surface "
                                              << worst_surface_ratio << " of its bound");
}

TEST_CASE("point quantization error stays within the bounds of spec sections 8.2 and 8.3 at every bit depth") {
    Rng rng(7);
    ObjectInfo o;
    o.frame = {{-3.5f, 10, 0.125f}, 7.25f};
    o.attributes = kAttrNormal | kAttrTexcoord | kAttrColor | kAttrColorAlpha;
    o.texcoord_origin = {-0.5f, 0};
    o.texcoord_scale = {2, 1};
    const double slack = 2 * 1.2e-7 * 20;  // two ulps of the largest coordinate (|origin| + scale < 20)
    for (int bits = 2; bits <= 16; ++bits) {
        StreamInfo info;
        info.position_bits = uint8_t(std::clamp(bits, 8, 16));
        info.normal_bits = uint8_t(std::clamp(bits, 4, 16));
        info.texcoord_bits = uint8_t(std::clamp(bits, 4, 16));
        info.color_bits = uint8_t(bits);
        const double pos_bound = o.frame.scale / (2.0 * ((1 << info.position_bits) - 1));
        const double tex_step = 1.0 / (2.0 * ((1 << info.texcoord_bits) - 1));  // times texcoord_scale
        const double col_bound = 1.0 / (2.0 * ((1 << info.color_bits) - 1));
        const double normal_bound = 3 * std::sqrt(2.0) / ((1 << info.normal_bits) - 1);
        double worst_pos = 0, worst_tex = 0, worst_col = 0, worst_normal = 0;
        for (int i = 0; i < 3000; ++i) {
            SurfacePoint p;
            for (int k = 0; k < 3; ++k) p.position[k] = float(o.frame.origin[k] + rng.uniform(0, 1) * o.frame.scale);
            p.normal = random_unit(rng);
            if (i < 6) p.normal = {0, 0, 0}, p.normal[i / 2] = i % 2 ? -1.f : 1.f;  // the poles and the equator
            p.texcoord = {float(rng.uniform(-0.5, 1.5)), float(rng.uniform(0, 1))};
            for (auto& c : p.color) c = float(rng.uniform());
            SurfacePoint q = dequantize_point(quantize_point(p, info, o), info, o);
            for (int k = 0; k < 3; ++k) worst_pos = std::max(worst_pos, std::fabs(double(q.position[k]) - p.position[k]));
            for (int k = 0; k < 2; ++k)
                worst_tex = std::max(worst_tex, std::fabs(double(q.texcoord[k]) - p.texcoord[k]) / o.texcoord_scale[k]);
            for (int k = 0; k < 4; ++k) worst_col = std::max(worst_col, std::fabs(double(q.color[k]) - p.color[k]));
            // The angle as atan2(|a x b|, a . b): well conditioned for small angles, unlike acos.
            const auto& a = p.normal;
            const auto& b = q.normal;
            double cx = double(a[1]) * b[2] - double(a[2]) * b[1], cy = double(a[2]) * b[0] - double(a[0]) * b[2],
                   cz = double(a[0]) * b[1] - double(a[1]) * b[0];
            double dot = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
            worst_normal = std::max(worst_normal, std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot));
        }
        CAPTURE(bits);
        CHECK(worst_pos <= pos_bound + slack);
        CHECK(worst_tex <= tex_step + 1e-6);
        CHECK(worst_col <= col_bound + 1e-7);
        CHECK(worst_normal <= normal_bound + 1e-6);
        MESSAGE("bits " << bits << ": position " << worst_pos / pos_bound << ", texcoord " << worst_tex / tex_step
                        << ", colour " << worst_col / col_bound << ", normal " << worst_normal / normal_bound
                        << " of their bounds (normal " << worst_normal * 180 / M_PI << " degrees at "
                        << int(info.normal_bits) << " bits)");
    }
}

TEST_CASE("packets are at most the chosen packet size, from 128 to 65000 bytes") {
    for (uint16_t size : {uint16_t(128), uint16_t(129), uint16_t(500), uint16_t(1200), uint16_t(65000)}) {
        Sample s = sample_stream(size, kAttrNormal | kAttrTexcoord | kAttrColor | kAttrColorAlpha, 8, 300, 3000);
        size_t largest = 0;
        for (const auto* list : {&s.packets.stream_info, &s.packets.ellipsoids, &s.packets.points})
            for (const Packet& p : *list) largest = std::max(largest, p.size());
        CAPTURE(size);
        CHECK(largest <= size);
        CHECK(s.packets.ellipsoids[0].size() == 24 + 8 + 16 * std::min<size_t>(300, ellipsoids_per_packet(size)));
    }
}
