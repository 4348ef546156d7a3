// Writes the conformance vectors of spec/vectors/: valid/, unusual/ and faulty/ container files, each
// with its expected decode (NAME.json) beside it. Deterministic: the same program writes the same bytes.
//
//   ellicast_make_vectors spec/vectors        (from the repository root)
//
// Streams are made with the reference library (quantize, packetize_stream, write_container); the
// unusual and faulty ones are then edited byte by byte the way a channel, a newer encoder or a broken
// encoder would, and resealed (checksum recomputed) where the defect must not be a checksum error.
#include "expected_decode.h"

#include <ellicast/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using namespace ellicast;
namespace fs = std::filesystem;

namespace {

using Packet = std::vector<uint8_t>;
using Packets = std::vector<Packet>;

// splitmix64: a portable generator (std distributions differ between standard libraries).
struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed) {}
    uint64_t next() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return (next() >> 11) * (1.0 / 9007199254740992.0); }
    double range(double a, double b) { return a + (b - a) * uniform(); }
    size_t below(size_t n) { return static_cast<size_t>(next() % n); }
};

std::array<float, 4> random_rotation(Rng& rng) {
    // Shoemake's uniform random unit quaternion.
    double u1 = rng.uniform(), u2 = rng.uniform() * 2 * M_PI, u3 = rng.uniform() * 2 * M_PI;
    double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return {float(a * std::sin(u2)), float(a * std::cos(u2)), float(b * std::sin(u3)), float(b * std::cos(u3))};
}

ObjectInfo make_object(std::array<float, 3> origin, float scale, uint32_t ellipsoids, uint32_t points,
                       uint8_t attributes, ObjectKind kind = ObjectKind::Surface) {
    ObjectInfo o;
    o.frame.origin = origin;
    o.frame.scale = scale;
    o.ellipsoid_count = ellipsoids;
    o.point_count = points;
    o.kind = kind;
    o.attributes = attributes;
    if (attributes & kAttrTexcoord) {
        o.texcoord_origin = {0, 0};
        o.texcoord_scale = {1, 1};
    }
    return o;
}

// Ellipsoids inside the frame and points on a sphere in its middle, quantized by the library.
ObjectContent make_content(const StreamInfo& info, const ObjectInfo& o, Rng& rng) {
    ObjectContent c;
    const double s = o.frame.scale;
    std::array<double, 3> mid;
    for (int i = 0; i < 3; ++i) mid[i] = o.frame.origin[i] + 0.5 * s;
    for (uint32_t i = 0; i < o.ellipsoid_count; ++i) {
        Ellipsoid e;
        for (int k = 0; k < 3; ++k) {
            e.center[k] = float(mid[k] + rng.range(-0.3, 0.3) * s);
            e.radii[k] = float(rng.range(0.02, 0.2) * s);
        }
        e.rotation = random_rotation(rng);
        c.ellipsoids.push_back(quantize_ellipsoid(e, o.frame));
    }
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (uint32_t i = 0; i < o.point_count; ++i) {
        double z = o.point_count > 1 ? 1 - 2 * (i + 0.5) / o.point_count : 0;
        double r = std::sqrt(std::max(0.0, 1 - z * z));
        double phi = golden * i;
        std::array<double, 3> dir = {r * std::cos(phi), r * std::sin(phi), z};
        SurfacePoint p;
        for (int k = 0; k < 3; ++k) {
            p.position[k] = float(mid[k] + 0.4 * s * dir[k]);
            p.normal[k] = float(dir[k]);
        }
        p.texcoord = {float(std::atan2(dir[1], dir[0]) / (2 * M_PI) + 0.5), float(std::acos(dir[2]) / M_PI)};
        p.color = {float(rng.uniform()), float(rng.uniform()), float(rng.uniform()), float(rng.uniform())};
        c.points.push_back(quantize_point(p, info, o));
    }
    return c;
}

struct Stream {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    StreamPackets packets;

    Packets all() const {
        Packets out = packets.stream_info;
        out.insert(out.end(), packets.ellipsoids.begin(), packets.ellipsoids.end());
        out.insert(out.end(), packets.points.begin(), packets.points.end());
        return out;
    }
};

// The library writes its own (newest) minor version; these vectors are format 1.0 streams, whose
// packets say 1.0 (spec 9: an encoder writes the lowest minor version its packets need).
void mark_version_1_0(Packets& packets) {
    for (Packet& p : packets) {
        p[5] = 0;
        const size_t body = p.size() - kChecksumSize;
        const uint32_t crc = crc32c(p.data(), body);
        for (int i = 0; i < 4; ++i) p[body + i] = uint8_t(crc >> (8 * i));
    }
}
void mark_version_1_0(StreamPackets& s) {
    mark_version_1_0(s.stream_info);
    mark_version_1_0(s.ellipsoids);
    mark_version_1_0(s.points);
}

Stream make_stream(StreamInfo info, uint32_t stream_id, uint64_t seed) {
    Stream s;
    Rng rng(seed);
    for (const ObjectInfo& o : info.objects) s.contents.push_back(make_content(info, o, rng));
    s.info = info;
    Error e = packetize_stream(info, s.contents, stream_id, s.packets);
    if (e != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed: " << error_name(e) << "\n";
        std::exit(1);
    }
    mark_version_1_0(s.packets);
    return s;
}

StreamInfo default_info(std::vector<ObjectInfo> objects, uint16_t packet_size = 1200) {
    StreamInfo info;
    info.packet_size = packet_size;
    info.coverage_target = 0.95f;
    info.seed = 7;
    info.grid_hint = 64;
    info.objects = std::move(objects);
    return info;
}

// Byte edits on a serialized packet.
void put16(Packet& p, size_t at, uint16_t v) {
    p[at] = uint8_t(v);
    p[at + 1] = uint8_t(v >> 8);
}
void put32(Packet& p, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) p[at + i] = uint8_t(v >> (8 * i));
}
uint16_t get16(const Packet& p, size_t at) { return uint16_t(p[at] | (p[at + 1] << 8)); }
uint32_t get32(const Packet& p, size_t at) {
    return uint32_t(p[at]) | uint32_t(p[at + 1]) << 8 | uint32_t(p[at + 2]) << 16 | uint32_t(p[at + 3]) << 24;
}
// Recomputes the checksum after an edit, so that the defect is the edit and not a checksum error.
void reseal(Packet& p) {
    const size_t body = p.size() - kChecksumSize;
    put32(p, body, crc32c(p.data(), body));
}
// Rebuilds a packet around a new payload (payload_length and checksum follow).
Packet with_payload(const Packet& p, const std::vector<uint8_t>& payload) {
    Packet copy = p;
    reseal(copy);
    PacketView view;
    if (parse_packet(copy, view) != Error::Ok) {
        std::cerr << "make_vectors: with_payload needs a valid packet\n";
        std::exit(1);
    }
    return write_packet(view.header, payload);
}
std::vector<uint8_t> payload_of(const Packet& p) {
    return {p.begin() + kHeaderSize, p.end() - kChecksumSize};
}

struct Writer {
    fs::path root;
    std::vector<std::string> written;
    size_t total_bytes = 0;

    void write(const std::string& set, const std::string& name, const std::string& description,
               const std::vector<uint8_t>& bytes) {
        fs::create_directories(root / set);
        const fs::path base = root / set / name;
        {
            std::ofstream f(base.string() + ".ellc", std::ios::binary | std::ios::trunc);
            f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            if (!f) fail(base.string() + ".ellc");
        }
        nlohmann::json j;
        j["vector"] = set + "/" + name;
        j["description"] = description;
        const nlohmann::json decoded = conformance::expected_decode(bytes);
        for (auto it = decoded.begin(); it != decoded.end(); ++it) j[it.key()] = it.value();
        std::string text;
        conformance::write_readable(j, text);
        text += "\n";
        {
            std::ofstream f(base.string() + ".json", std::ios::binary | std::ios::trunc);
            f << text;
            if (!f) fail(base.string() + ".json");
        }
        total_bytes += bytes.size() + text.size();
        written.push_back(set + "/" + name);
        std::printf("%-40s %7zu bytes  %s\n", (set + "/" + name + ".ellc").c_str(), bytes.size(), description.c_str());
    }
    void write(const std::string& set, const std::string& name, const std::string& description, const Packets& packets) {
        write(set, name, description, write_container(packets));
    }
    [[noreturn]] static void fail(const std::string& path) {
        std::cerr << "make_vectors: cannot write " << path << "\n";
        std::exit(1);
    }
};

constexpr uint32_t kStreamId = 0x0E11CA57;

// ------------------------------------------------------------------------------------------------

void valid_vectors(Writer& w) {
    {
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 1, 2, 0)});
        Stream s = make_stream(info, kStreamId, 1);
        w.write("valid", "minimal", "one surface object: 1 ellipsoid, 2 points without attributes (the worked example of spec appendix A)",
                s.all());
    }
    {
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 16, 100, kAttrNormal | kAttrTexcoord | kAttrColor)}, 600);
        Stream s = make_stream(info, kStreamId, 2);
        w.write("valid", "sphere",
                "one surface object: 16 ellipsoids, 100 points with normal, texture coordinates and RGB colour, packet size 600",
                s.all());
    }
    {
        StreamInfo info = default_info({make_object({0, 0, 0}, 10, 10, 60, kAttrNormal | kAttrTexcoord),
                                        make_object({-5, 2, 0.5f}, 3, 6, 40, kAttrColor | kAttrColorAlpha)},
                                       512);
        Stream s = make_stream(info, kStreamId, 3);
        w.write("valid", "two_objects",
                "two objects (normals + texture coordinates; RGBA colour) with their own frames, packet size 512, point packets of both objects interleaved",
                s.all());
    }
    {
        // A UV seam: points 2k and 2k+1 share their position and differ in texture coordinates.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 4, 24, kAttrNormal | kAttrTexcoord)});
        Stream s;
        Rng rng(4);
        s.info = info;
        s.contents.push_back(make_content(info, info.objects[0], rng));
        for (size_t i = 1; i < s.contents[0].points.size(); i += 2) {
            s.contents[0].points[i].position = s.contents[0].points[i - 1].position;
            s.contents[0].points[i].normal = s.contents[0].points[i - 1].normal;
            s.contents[0].points[i].texcoord[0] = (s.contents[0].points[i - 1].texcoord[0] + 2048) % 4096;  // 12 bits
        }
        packetize_stream(info, s.contents, kStreamId, s.packets);
        mark_version_1_0(s.packets);
        w.write("valid", "seam",
                "a UV seam: points 2k and 2k+1 have identical quantized positions and normals and different texture coordinates; a decoder makes one surface vertex of each pair (spec 7.2)",
                s.all());
    }
    {
        // A carousel as a broadcast sends it: the base (stream info and ellipsoids) before every chunk
        // of point packets; every transmission gets its own sequence number.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 12, 120, kAttrNormal)}, 200);
        Stream s = make_stream(info, kStreamId, 5);
        Packets sent;
        const auto& pts = s.packets.points;
        const size_t chunk = (pts.size() + 2) / 3;
        for (size_t first = 0; first < pts.size(); first += chunk) {
            for (const auto& p : s.packets.stream_info) sent.push_back(p);
            for (const auto& p : s.packets.ellipsoids) sent.push_back(p);
            for (size_t i = first; i < std::min(pts.size(), first + chunk); ++i) sent.push_back(pts[i]);
        }
        for (uint32_t i = 0; i < sent.size(); ++i) restamp_packet(sent[i], i);
        mark_version_1_0(sent);
        w.write("valid", "carousel",
                "a carousel b d1 b d2 b d3: the base (STREAM_INFO + ELLIPSOIDS) repeated before each third of the points, sequence numbers counting transmissions; repeats are duplicates",
                sent);
    }
}

void unusual_vectors(Writer& w) {
    {
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 20, 60, 0), make_object({2, 2, 2}, 1, 3, 10, kAttrNormal)},
                                       kMinPacketSize);
        Stream s = make_stream(info, kStreamId, 10);
        w.write("unusual", "packet_size_128",
                "the smallest packet size, 128 bytes: one object entry per STREAM_INFO part (2 parts), 6 ellipsoids or 18 points per packet",
                s.all());
    }
    {
        // 16-bit positions without attributes: 6 bytes a point, 10828 points fill a payload of exactly
        // 8 + 64968 = 64976 bytes, a packet of exactly 65000 bytes.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 4060, 10828, 0)}, uint16_t(kMaxPacketSize));
        info.position_bits = 16;
        Stream s = make_stream(info, kStreamId, 11);
        w.write("unusual", "packet_size_65000",
                "the largest packet size: one POINTS packet of exactly 65000 bytes (10828 points at 16 bits) and one ELLIPSOIDS packet of 64992 bytes (4060 ellipsoids); elements given by digest",
                s.all());
    }
    for (int bits = 2; bits <= 16; ++bits) {
        StreamInfo info = default_info({make_object({-3, -2, -1}, 6, 2, 12, kAttrNormal | kAttrTexcoord | kAttrColor | kAttrColorAlpha),
                                        make_object({0, 0, 0}, 0.5f, 1, 8, kAttrColor)},
                                       256);
        info.position_bits = uint8_t(std::clamp(bits, 8, 16));
        info.normal_bits = uint8_t(std::clamp(bits, 4, 16));
        info.texcoord_bits = uint8_t(std::clamp(bits, 4, 16));
        info.color_bits = uint8_t(bits);
        Stream s = make_stream(info, kStreamId, 100 + bits);
        char name[16];
        std::snprintf(name, sizeof name, "bits_%02d", bits);
        char desc[200];
        std::snprintf(desc, sizeof desc,
                      "bit depths: positions %d, normals %d, texture coordinates %d, colours %d (RGBA and RGB objects), packet size 256",
                      info.position_bits, info.normal_bits, info.texcoord_bits, info.color_bits);
        w.write("unusual", name, desc, s.all());
    }
    {
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 3, 10, 0), make_object({0, 0, 0}, 1, 0, 0, kAttrNormal),
                                        make_object({1, 1, 1}, 1, 2, 5, 0)});
        Stream s = make_stream(info, kStreamId, 12);
        w.write("unusual", "empty_object", "three objects, the middle one empty (0 ellipsoids, 0 points): it is complete as soon as its entry arrives",
                s.all());
    }
    {
        StreamInfo info = default_info({});
        Stream s = make_stream(info, kStreamId, 13);
        w.write("unusual", "no_objects", "a stream with an empty object table: one STREAM_INFO packet with object_count 0 and no entries",
                s.all());
    }
    {
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 0, 50, kAttrColor, ObjectKind::PointSet)});
        Stream s = make_stream(info, kStreamId, 14);
        w.write("unusual", "point_set", "a point-set object (kind 1): 50 points with RGB colour, no ellipsoids", s.all());
    }
    {
        std::vector<ObjectInfo> objects;
        for (int i = 0; i < 60; ++i) objects.push_back(make_object({float(i), 0, 0}, 1, 1, 1, 0));
        StreamInfo info = default_info(objects);
        Stream s = make_stream(info, kStreamId, 15);
        w.write("unusual", "split_stream_info",
                "60 objects: the object table is split over 3 STREAM_INFO parts (26 + 26 + 8 entries), each repeating the stream-level fields",
                s.all());
    }
    {
        // Reordered and duplicated, with the stream info last: every object packet is held first.
        StreamInfo info = default_info({make_object({0, 0, 0}, 10, 10, 60, kAttrNormal | kAttrTexcoord),
                                        make_object({-5, 2, 0.5f}, 3, 6, 40, kAttrColor | kAttrColorAlpha)},
                                       512);
        Stream s = make_stream(info, kStreamId, 3);
        Packets body;
        for (const auto& p : s.packets.ellipsoids) body.push_back(p);
        for (const auto& p : s.packets.points) body.push_back(p);
        Rng rng(16);
        for (size_t i = body.size(); i > 1; --i) std::swap(body[i - 1], body[rng.below(i)]);
        Packets sent;
        for (size_t i = 0; i < body.size(); ++i) {
            sent.push_back(body[i]);
            if (i % 3 == 0) sent.push_back(body[i]);  // byte-identical duplicate
            if (i % 4 == 1) {                         // a retransmission with its own sequence number
                Packet again = body[i];
                restamp_packet(again, 1000 + uint32_t(i));
                sent.push_back(again);
            }
        }
        sent.push_back(s.packets.stream_info[0]);
        sent.push_back(s.packets.stream_info[0]);
        w.write("unusual", "duplicated_reordered",
                "the stream of valid/two_objects shuffled, with byte-identical and restamped duplicates, STREAM_INFO last (twice): every object packet is held, then decoded; the result equals valid/two_objects",
                sent);
    }
    {
        // What a 1.1 encoder might send: grown STREAM_INFO (info_size 40, entry_size 52) and a new
        // skippable packet type. A 1.0 decoder reads what it knows and skips the rest.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 8, 30, kAttrNormal)});
        Stream s = make_stream(info, kStreamId, 17);
        Packets sent;
        for (Packet p : s.all()) {
            p[5] = 1;  // minor version 1
            if (p[6] == uint8_t(PacketType::StreamInfo)) {
                auto payload = payload_of(p);
                const size_t entries = get16(p, kHeaderSize + 20);
                std::vector<uint8_t> grown(payload.begin(), payload.begin() + 32);
                grown[0] = 40;  // info_size
                grown[2] = 52;  // entry_size
                for (int k = 0; k < 8; ++k) grown.push_back(uint8_t(0xA0 + k));  // new stream-level fields
                for (size_t e = 0; e < entries; ++e) {
                    grown.insert(grown.end(), payload.begin() + 32 + e * 44, payload.begin() + 32 + (e + 1) * 44);
                    for (int k = 0; k < 8; ++k) grown.push_back(uint8_t(0xB0 + k));  // new entry fields
                }
                p = with_payload(p, grown);
            } else {
                reseal(p);
            }
            sent.push_back(p);
            if (sent.size() == 2) {
                PacketHeader h;
                h.version_minor = 1;
                h.type = 0xF0;
                h.flags = kFlagSkippable;
                h.stream_id = kStreamId;
                h.sequence = 500;
                h.object_id = 0;
                std::vector<uint8_t> payload(37, 0x5A);
                sent.push_back(write_packet(h, payload));
            }
        }
        w.write("unusual", "minor_1_1",
                "version 1.1 packets: STREAM_INFO grown to info_size 40 / entry_size 52 with unknown trailing fields, and an unknown skippable type 0xF0; a 1.0 decoder decodes everything else and skips 0xF0",
                sent);
    }
    {
        // Reserved bits and fields set: decoders ignore them.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 8, 30, kAttrColor)});
        Stream s = make_stream(info, kStreamId, 18);
        Packets sent;
        for (Packet p : s.all()) {
            p[7] |= 0xFE;  // flags bits 1..7
            if (p[6] == uint8_t(PacketType::StreamInfo)) {
                p[kHeaderSize + 11] = 0x77;                              // reserved u8
                put16(p, kHeaderSize + 32 + 26, 0xBEEF);                 // reserved u16 of entry 0
            } else {
                put16(p, kHeaderSize + 6, 0xCAFE);                       // reserved u16 of the batch header
            }
            reseal(p);
            sent.push_back(p);
        }
        w.write("unusual", "reserved_bits_set",
                "every reserved header flag bit and reserved field set to non-zero values; decoders ignore them and decode as usual",
                sent);
    }
}

void faulty_vectors(Writer& w) {
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 12, 40, kAttrNormal)}, 200);
    const Stream s = make_stream(info, kStreamId, 20);
    const Packets base = s.all();  // 1 STREAM_INFO, 2 ELLIPSOIDS, 4 POINTS packets
    auto first_of = [&](PacketType t) {
        for (size_t i = 0; i < base.size(); ++i)
            if (base[i][6] == uint8_t(t)) return i;
        return size_t(0);
    };
    const size_t ell = first_of(PacketType::Ellipsoids);
    const size_t pts = first_of(PacketType::Points);

    {
        Packets p = base;
        p[pts][0] = 0xE2;
        w.write("faulty", "bad_magic", "the first byte of the first POINTS packet is E2 instead of E1: a damaged region (bad magic); the packets after it are kept", p);
    }
    {
        Packets p = base;
        p[pts][kHeaderSize + 20] ^= 0x08;
        w.write("faulty", "bad_crc", "one bit flipped in the payload of the first POINTS packet: a damaged region (bad checksum); the points of that packet are missing", p);
    }
    {
        auto bytes = write_container(base);
        bytes.resize(bytes.size() - base.back().size() / 2);
        w.write("faulty", "truncated_packet", "the file ends in the middle of its last packet: a damaged region (truncated) at the end", bytes);
    }
    {
        auto bytes = write_container(base);
        bytes.resize(10);
        w.write("faulty", "truncated_container", "a 10-byte file: the signature and 2 bytes of the container header (too short); nothing is read", bytes);
    }
    {
        auto bytes = write_container(base);
        bytes.erase(bytes.begin() + 4);  // CR LF -> LF, as a text-mode transfer does
        w.write("faulty", "bad_signature", "the container signature with its CR LF turned into LF (a text-mode transfer): bad container signature; nothing is read", bytes);
    }
    {
        auto bytes = write_container(base);
        bytes[8] = 2;
        w.write("faulty", "container_version_2", "container version 2: unsupported container version; nothing is read", bytes);
    }
    {
        Packets p = base;
        p[pts][4] = 2;
        reseal(p[pts]);
        w.write("faulty", "wrong_major", "the first POINTS packet says format 2.0 (checksum valid): a damaged region (unsupported major version) for a 1.0 reader", p);
    }
    {
        Packets p = base;
        p[pts][6] = 0xF1;
        p[pts][7] = 0;
        reseal(p[pts]);
        w.write("faulty", "unknown_critical_type", "a packet of the unknown type 0xF1 not marked skippable (checksum valid): rejected (unknown critical type); the rest decodes", p);
    }
    {
        Packets p = base;
        p[pts][6] = 0;
        reseal(p[pts]);
        w.write("faulty", "type_zero", "a packet of type 0 (checksum valid): a damaged region (invalid type)", p);
    }
    {
        Packets p = base;
        put16(p[pts], 18, 0xFFFF);
        w.write("faulty", "oversized_length", "a header declaring payload_length 65535 (a 65559-byte packet): a damaged region (oversized); the reader resynchronizes on the next packet", p);
    }
    {
        Packets p = base;
        put16(p[ell], kHeaderSize + 4, uint16_t(get16(p[ell], kHeaderSize + 4) + 1));
        reseal(p[ell]);
        w.write("faulty", "payload_length_inconsistent", "the first ELLIPSOIDS packet's count is one more than its payload holds (checksum valid): rejected (malformed payload)", p);
    }
    {
        Packets p = base;
        put32(p[pts], kHeaderSize, 35);  // 35 + count > 40 points
        reseal(p[pts]);
        w.write("faulty", "index_out_of_range", "the first POINTS packet starts at index 35 of 40 points and runs past the end (checksum valid): rejected (index out of range)", p);
    }
    {
        Packets p = base;
        p[0][kHeaderSize + 6] = 17;
        reseal(p[0]);
        w.write("faulty", "stream_info_bad_bits", "STREAM_INFO with position_bits 17 (checksum valid): rejected (malformed payload); with no stream info every object packet stays held", p);
    }
    {
        Packets p = base;
        StreamInfo other = default_info({make_object({-1, -1, -1}, 2, 12, 40, kAttrNormal)}, 200);
        Stream o = make_stream(other, 0xBADC0DE, 21);
        p.insert(p.begin() + long(pts), o.packets.points[0]);
        p.insert(p.begin() + long(pts), o.packets.stream_info[0]);
        w.write("faulty", "mixed_stream_ids", "two packets of another stream (id 0x0BADC0DE) in the middle: rejected (stream mismatch)", p);
    }
    {
        Packets p = base;
        Packet info2 = p[0];
        put32(info2, kHeaderSize + 12, get32(info2, kHeaderSize + 12) ^ 1);  // content_id
        reseal(info2);
        p.insert(p.begin() + long(pts), info2);
        w.write("faulty", "contradicting_stream_info", "a second STREAM_INFO with another content_id: rejected (stream mismatch); the first one stays", p);
    }
    {
        Packets p = base;
        put16(p[ell], 16, 5);
        reseal(p[ell]);
        w.write("faulty", "unknown_object", "the first ELLIPSOIDS packet names object 5 of a 1-object stream: rejected (unknown object)", p);
    }
    {
        Packets p = base;
        put16(p[0], 16, 0);
        reseal(p[0]);
        w.write("faulty", "stream_info_object_id", "STREAM_INFO with object_id 0 instead of 0xFFFF: rejected (malformed payload)", p);
    }
    {
        Packets p(base.begin() + 1, base.end());
        w.write("faulty", "no_stream_info", "no STREAM_INFO at all: every object packet is held, nothing can be decoded (no stream info)", p);
    }
    {
        Packets p = base;
        p.erase(p.begin() + long(pts) + 1);
        p.erase(p.begin() + long(ell));
        w.write("faulty", "incomplete", "the first ELLIPSOIDS packet and the second POINTS packet are missing (lost): every packet is intact, but the object is incomplete", p);
    }
    {
        Packets p = base;
        put16(p[0], kHeaderSize + 4, 128);
        reseal(p[0]);
        w.write("faulty", "packet_over_declared_size", "STREAM_INFO declares packet_size 128 but the packets are up to 200 bytes: decoders take them; a validator reports the sender's error", p);
    }
    {
        Packets p = base;
        Rng rng(22);
        Packet garbage(37);
        for (auto& b : garbage) b = uint8_t(rng.next());
        garbage[5] = 0xE1;  // a false start of a packet inside the garbage
        p.insert(p.begin() + long(pts), garbage);
        w.write("faulty", "garbage_between_packets", "37 bytes of noise (with a stray E1) between two packets: a damaged region; every packet is kept", p);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: ellicast_make_vectors OUTPUT_DIR   (spec/vectors)\n";
        return 2;
    }
    Writer w;
    w.root = argv[1];
    valid_vectors(w);
    unusual_vectors(w);
    faulty_vectors(w);
    std::printf("%zu vectors, %zu bytes with their JSON\n", w.written.size(), w.total_bytes);
    return 0;
}
