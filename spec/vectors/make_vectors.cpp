// Writes the conformance vectors of spec/vectors/: valid/, unusual/ and faulty/ container files, each
// with its expected decode (NAME.json) beside it. Deterministic: the same program writes the same bytes.
//
//   ellicast_make_vectors spec/vectors        (from the repository root)
//
// Streams are made with the reference library (quantize, packetize_stream, write_container); the
// unusual and faulty ones are then edited byte by byte the way a channel, a newer encoder or a broken
// encoder would, and resealed (checksum recomputed) where the defect must not be a checksum error.
#include "expected_decode.h"
#include "../../samples/jpeg_images.h"

#include <ellicast/auth.h>
#include <ellicast/format.h>

#include <sodium.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <fstream>
#include <iostream>
#include <string>
#include <tuple>
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
        // Batches of count 0 (spec 6 and 7: a decoder takes them as packets that bring nothing new),
        // and padding bits set to 1 after the last point record (spec 7: not required to be zero).
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 12, 40, kAttrNormal)}, 200);
        const Stream s = make_stream(info, kStreamId, 20);
        Packets p = s.all();
        size_t ell = 0, pts = 0;
        for (size_t i = p.size(); i-- > 0;) {
            if (p[i][6] == uint8_t(PacketType::Ellipsoids)) ell = i;
            if (p[i][6] == uint8_t(PacketType::Points)) pts = i;
        }
        std::vector<uint8_t> empty(8, 0);  // first_index 5, count 0, reserved 0
        empty[0] = 5;
        p.push_back(with_payload(p[ell], empty));
        p.push_back(with_payload(p[pts], empty));
        // Padding: records of 3 x 12 + 2 x 10 = 56 bits pack whole bytes, so the padding is
        // checked on the packet itself: set every bit past count x B.
        const size_t bits = size_t(get16(p[pts], kHeaderSize + 4)) * (3 * info.position_bits + 2 * info.normal_bits);
        if (bits % 8) {
            p[pts][kHeaderSize + 8 + bits / 8] |= uint8_t(0xFF << (bits % 8));
            reseal(p[pts]);
        }
        w.write("unusual", "count_zero_and_padding",
                std::string("an ELLIPSOIDS and a POINTS batch of count 0 at the end (duplicates: nothing new, spec 6, 7)") +
                    (bits % 8 ? "; the first POINTS packet's padding bits after its last record set to 1 (ignored, spec 7)" : ""),
                p);
    }
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
        // The same part again (a carousel's repetition, sequence 1): a part without entries counts as
        // accepted every time it is taken (spec 5.4).
        Packets twice = s.all();
        Packet again = twice.at(0);
        put32(again, 12, 1);
        reseal(again);
        twice.push_back(again);
        w.write("unusual", "no_objects_repeated",
                "the stream of unusual/no_objects with its STREAM_INFO packet (object_count 0, entry_count 0) sent again "
                "(sequence 1, resealed): a part without entries counts as accepted, also when repeated (spec 5.4), so "
                "both copies are accepted and neither is a duplicate",
                twice);
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
    {
        // Repetitions of STREAM_INFO that differ only where spec 5.4 does not compare: the entry's
        // reserved field (offset 26), the bytes after offset 43 of a longer entry, the reserved byte
        // at offset 11, and +0 against -0 in f32 fields. None contradicts the others.
        StreamInfo info = default_info({make_object({0, -1, 0}, 2, 8, 30, kAttrNormal | kAttrTexcoord)});
        Stream s = make_stream(info, kStreamId, 19);
        const Packet& original = s.packets.stream_info[0];
        // A copy in the layout of a later minor version: entry_size 52, 8 unknown bytes after each entry.
        auto grown = [&](uint8_t trailing, uint16_t reserved, uint32_t sequence) {
            const auto payload = payload_of(original);
            std::vector<uint8_t> out(payload.begin(), payload.begin() + 32);
            out[2] = 52;  // entry_size
            out.insert(out.end(), payload.begin() + 32, payload.begin() + 76);
            put16(out, 32 + 26, reserved);
            for (int k = 0; k < 8; ++k) out.push_back(uint8_t(trailing + k));
            Packet q = with_payload(original, out);
            q[5] = 1;  // minor version 1
            put32(q, 12, sequence);
            reseal(q);
            return q;
        };
        Packet first = grown(0xB0, 0xBEEF, 100);
        Packet later = grown(0xC0, 0x1234, 101);
        const size_t H = kHeaderSize, E = kHeaderSize + 32;
        later[H + 11] = 0x5A;              // the reserved stream-level byte
        put32(later, E + 0, 0x80000000u);  // frame_origin x: -0 where the others say +0
        put32(later, E + 8, 0x80000000u);  // frame_origin z: -0
        put32(later, E + 28, 0x80000000u); // texcoord_origin u: -0
        reseal(later);
        Packets sent = {first};
        for (const Packet& q : s.all()) sent.push_back(q);
        sent.push_back(later);
        w.write("unusual", "stream_info_uncompared_fields",
                "three STREAM_INFO packets with the same entry, differing only where spec 5.4 does not compare: the "
                "first (accepted) and the last say format 1.1 with entry_size 52 and 8 different unknown bytes after "
                "the entry, the entry's reserved field is BEEF, 0 and 1234, and the last has the reserved byte at "
                "offset 11 set and -0 where the others have +0 (frame_origin x and z, texcoord_origin u: f32 fields "
                "are compared as numbers); the second and third are duplicates, nothing is rejected",
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
        // An empty batch starting past the end: first_index + count > point_count (spec 6, 7).
        Packets p = base;
        std::vector<uint8_t> empty(8, 0);
        empty[0] = 41;  // first_index 41 of 40 points, count 0
        p.push_back(with_payload(p[pts], empty));
        w.write("faulty", "count_zero_past_end",
                "a POINTS batch of count 0 at first_index 41 of a 40-point object: rejected (index out of range: "
                "first_index + count must not exceed point_count, spec 6, 7); the rest decodes",
                p);
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

    // Every MUST-reject rule of spec 5.3 for STREAM_INFO, one vector each: the one STREAM_INFO packet
    // edited (checksum resealed), so it is rejected as malformed payload and every object packet
    // stays held. Offsets are into the payload: stream-level fields at 0, the entry at 32 (5.1, 5.2).
    struct InfoEdit {
        const char* name;
        const char* what;
        std::function<void(Packet&)> edit;
    };
    auto f32_bits = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    const size_t H = kHeaderSize, E = kHeaderSize + 32;
    const std::vector<InfoEdit> info_edits = {
        {"stream_info_info_size_31", "info_size 31 (below 32)", [&](Packet& q) { put16(q, H + 0, 31); }},
        {"stream_info_entry_size_43", "entry_size 43 (below 44)", [&](Packet& q) { put16(q, H + 2, 43); }},
        {"stream_info_length_mismatch", "info_size 33: payload_length 76 is not info_size + entry_count x entry_size = 77",
         [&](Packet& q) { put16(q, H + 0, 33); }},
        {"stream_info_packet_size_127", "packet_size 127 (below 128)", [&](Packet& q) { put16(q, H + 4, 127); }},
        {"stream_info_packet_size_65001", "packet_size 65001 (above 65000)", [&](Packet& q) { put16(q, H + 4, 65001); }},
        {"stream_info_normal_bits_3", "normal_bits 3 (below 4)", [&](Packet& q) { q[H + 7] = 3; }},
        {"stream_info_encoding_1", "ellipsoid_encoding 1 (only 0 is defined)", [&](Packet& q) { q[H + 10] = 1; }},
        {"stream_info_coverage_nan", "coverage_target a quiet NaN (7FC00000)", [&](Packet& q) { put32(q, H + 24, 0x7FC00000u); }},
        {"stream_info_entries_past_table", "first_object 1 with entry_count 1 in a table of 1 object",
         [&](Packet& q) { put16(q, H + 18, 1); }},
        {"stream_info_frame_scale_0", "the entry's frame_scale 0", [&](Packet& q) { put32(q, E + 12, 0); }},
        {"stream_info_frame_scale_negative", "the entry's frame_scale -2",
         [&](Packet& q) { put32(q, E + 12, f32_bits(-2.0f)); }},
        {"stream_info_origin_infinite", "the entry's frame_origin x is +infinity",
         [&](Packet& q) { put32(q, E + 0, 0x7F800000u); }},
        {"stream_info_frame_end_infinite",
         "the entry's frame_origin x 3.4028235e38 (the largest f32, 7F7FFFFF) and frame_scale 2^103: the far corner x, "
         "computed exactly, lies half-way between the largest f32 and 2^128 and rounds to infinity in f32",
         [&](Packet& q) {
             put32(q, E + 0, 0x7F7FFFFFu);
             put32(q, E + 12, f32_bits(0x1p103f));
         }},
        {"stream_info_texcoord_scale_negative", "the entry's texcoord_scale u is -1",
         [&](Packet& q) { put32(q, E + 36, f32_bits(-1.0f)); }},
        {"stream_info_texcoord_end_infinite",
         "the entry's texcoord_origin v and texcoord_scale v both 2^127: the range's end, 2^128, is infinite in f32 "
         "(checked whether or not the object has texture coordinates)",
         [&](Packet& q) {
             put32(q, E + 32, f32_bits(0x1p127f));
             put32(q, E + 40, f32_bits(0x1p127f));
         }},
        {"stream_info_kind_2", "the entry's kind 2 (0 and 1 are defined)", [&](Packet& q) { q[E + 24] = 2; }},
        {"stream_info_attribute_bit_4", "the entry's attributes with bit 4 set (unknown: the record size is unknown)",
         [&](Packet& q) { q[E + 25] |= 0x10; }},
        {"stream_info_alpha_without_colour", "the entry's attributes normal + alpha (bit 3) without colour (bit 2)",
         [&](Packet& q) { q[E + 25] = uint8_t(kAttrNormal | kAttrColorAlpha); }},
        {"stream_info_point_set_with_ellipsoids", "the entry's kind 1 (point set) with ellipsoid_count 12",
         [&](Packet& q) { q[E + 24] = 1; }},
    };
    for (const InfoEdit& e : info_edits) {
        Packets p = base;
        e.edit(p[0]);
        reseal(p[0]);
        std::string description = "STREAM_INFO with ";
        description += e.what;
        description += " (checksum valid): rejected (malformed payload, spec 5.3); with no stream info every object packet stays held";
        w.write("faulty", e.name, description, p);
    }
    {
        Packets p = base;
        Packet info2 = p[0];
        put32(info2, E + 20, get32(info2, E + 20) + 1);  // point_count 41
        reseal(info2);
        p.insert(p.begin() + long(pts), info2);
        w.write("faulty", "contradicting_object_entry",
                "a second STREAM_INFO with the same stream-level fields but the entry's point_count 41 instead of 40 "
                "(checksum valid): rejected (stream mismatch, spec 5.4); the first one stays",
                p);
    }
    {
        Packets p = base;
        put32(p[ell], kHeaderSize, 0xFFFFFFFFu);  // first_index + count > 2^32 - 1
        reseal(p[ell]);
        w.write("faulty", "index_overflow",
                "the first ELLIPSOIDS packet's first_index is 4294967295, so first_index + count exceeds 2^32 - 1 "
                "(checksum valid): rejected (malformed payload, spec 6)",
                p);
    }
    {
        Packets p = base;
        put32(p[ell], kHeaderSize, 10);  // ellipsoids 10.. of 12
        reseal(p[ell]);
        w.write("faulty", "ellipsoid_index_out_of_range",
                "the first ELLIPSOIDS packet starts at index 10 of 12 ellipsoids and runs past the end (checksum valid): "
                "rejected (index out of range, spec 6)",
                p);
    }
    {
        Packets p = base;
        std::vector<uint8_t> payload = payload_of(p[pts]);
        payload.push_back(0);
        p[pts] = with_payload(p[pts], payload);
        w.write("faulty", "points_length_mismatch",
                "the first POINTS packet carries one byte more than 8 + ceil(count x B / 8) (checksum valid): rejected "
                "(malformed payload, spec 7)",
                p);
    }
    {
        // Payloads too short for their 8 bytes of fixed fields (spec 6, 7): checked at step 13, once the
        // object's entry is known, so a copy sent before the STREAM_INFO is held, then rejected.
        auto short_first = [&](size_t at) {
            Packet copy = base[at];
            put32(copy, 12, 1000);
            std::vector<uint8_t> payload = payload_of(copy);
            payload.resize(7);
            Packets p = {with_payload(copy, payload)};
            p.insert(p.end(), base.begin(), base.end());
            return p;
        };
        w.write("faulty", "ellipsoids_payload_short",
                "a copy of the first ELLIPSOIDS packet (sequence 1000) cut to a payload of 7 bytes, too short for its "
                "fixed fields, before the STREAM_INFO: held (its checks need the object's entry, spec 11.1), then "
                "rejected when the STREAM_INFO releases it (malformed payload, spec 6: shorter than 8 bytes); the "
                "intact packets decode",
                short_first(ell));
        w.write("faulty", "points_payload_short",
                "a copy of the first POINTS packet (sequence 1000) cut to a payload of 7 bytes, too short for its fixed "
                "fields, before the STREAM_INFO: held (its checks need the object's entry, spec 11.1), then rejected "
                "when the STREAM_INFO releases it (malformed payload, spec 7: shorter than 8 bytes); the intact "
                "packets decode",
                short_first(pts));
    }
    {
        // Held packets and the order of their outcomes (spec 11.1, last paragraph): the stream of
        // valid/two_objects with STREAM_INFO last, and four defective copies held with the rest.
        // When the STREAM_INFO is accepted, the copies naming objects beyond its table are rejected
        // first (unknown object), in arrival order; then every held packet is released in arrival
        // order, not object by object, so object 1's rejection comes before object 0's.
        StreamInfo two = default_info({make_object({0, 0, 0}, 10, 10, 60, kAttrNormal | kAttrTexcoord),
                                       make_object({-5, 2, 0.5f}, 3, 6, 40, kAttrColor | kAttrColorAlpha)},
                                      512);
        Stream t = make_stream(two, kStreamId, 3);
        auto find = [&](const Packets& group, uint16_t object) {
            for (const Packet& q : group)
                if (get16(q, 16) == object) return q;
            std::exit(1);
        };
        Packet past_end = find(t.packets.points, 1);  // object 1's points from index 39 of 40
        put32(past_end, kHeaderSize, 39);
        put32(past_end, 12, 1000);  // sequence
        reseal(past_end);
        Packet object_5 = find(t.packets.ellipsoids, 0);  // object 0's ellipsoids, renamed object 5
        put16(object_5, 16, 5);
        put32(object_5, 12, 1001);
        reseal(object_5);
        Packet count_high = find(t.packets.points, 0);  // object 0's points, count one too high
        put16(count_high, kHeaderSize + 4, uint16_t(get16(count_high, kHeaderSize + 4) + 1));
        put32(count_high, 12, 1002);
        reseal(count_high);
        Packet object_2 = find(t.packets.ellipsoids, 1);  // object 1's ellipsoids, renamed object 2 = object_count
        put16(object_2, 16, 2);
        put32(object_2, 12, 1003);
        reseal(object_2);
        Packets sent = {past_end, object_5, count_high};
        for (const auto* group : {&t.packets.ellipsoids, &t.packets.points}) sent.insert(sent.end(), group->begin(), group->end());
        sent.push_back(object_2);
        sent.push_back(t.packets.stream_info[0]);
        w.write("faulty", "held_release_order",
                "the stream of valid/two_objects with its STREAM_INFO last and four defective copies (resealed) held "
                "before it, in this order: object 1's POINTS from index 39 of 40, object 0's ELLIPSOIDS renamed object 5, "
                "object 0's POINTS with its count one too high, and (after the intact packets) object 1's ELLIPSOIDS "
                "renamed object 2 (= object_count). When the STREAM_INFO is accepted, the held packets naming objects "
                "beyond its table are rejected first, in arrival order (unknown object: object 5, then object 2); then "
                "the held packets are released in arrival order, not object by object (index out of range for object "
                "1, then malformed payload for object 0), spec 11.1; the intact packets decode as valid/two_objects",
                sent);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.1: scene, materials, textures (spec section 15)

// CRC-32 of PNG chunks (ISO-HDLC, reflected polynomial 0xEDB88320), bitwise.
uint32_t png_crc(const uint8_t* p, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    while (n--) {
        c ^= *p++;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

// A real w x h RGB PNG file: signature, IHDR, one IDAT (zlib stream of stored deflate blocks), IEND.
// Every byte is fixed by (w, h, seed), so the vectors stay deterministic.
std::vector<uint8_t> make_png(uint32_t w, uint32_t h, uint64_t seed) {
    std::vector<uint8_t> raw;
    Rng rng(seed);
    for (uint32_t y = 0; y < h; ++y) {
        raw.push_back(0);  // filter: none
        for (uint32_t x = 0; x < w; ++x) {
            raw.push_back(uint8_t(x * 255 / std::max(1u, w - 1)));
            raw.push_back(uint8_t(y * 255 / std::max(1u, h - 1)));
            raw.push_back(uint8_t(rng.next()));
        }
    }
    std::vector<uint8_t> z = {0x78, 0x01};
    for (size_t at = 0; at < raw.size(); at += 65535) {
        const size_t n = std::min<size_t>(65535, raw.size() - at);
        z.push_back(at + n == raw.size() ? 1 : 0);
        z.push_back(uint8_t(n));
        z.push_back(uint8_t(n >> 8));
        z.push_back(uint8_t(~n));
        z.push_back(uint8_t(~n >> 8));
        z.insert(z.end(), raw.begin() + long(at), raw.begin() + long(at + n));
    }
    uint32_t a = 1, b = 0;
    for (uint8_t v : raw) {
        a = (a + v) % 65521;
        b = (b + a) % 65521;
    }
    const uint32_t adler = (b << 16) | a;
    for (int i = 3; i >= 0; --i) z.push_back(uint8_t(adler >> (8 * i)));

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    auto chunk = [&](const char* type, const std::vector<uint8_t>& data) {
        for (int i = 3; i >= 0; --i) png.push_back(uint8_t(data.size() >> (8 * i)));
        const size_t start = png.size();
        png.insert(png.end(), type, type + 4);
        png.insert(png.end(), data.begin(), data.end());
        const uint32_t crc = png_crc(png.data() + start, png.size() - start);
        for (int i = 3; i >= 0; --i) png.push_back(uint8_t(crc >> (8 * i)));
    };
    std::vector<uint8_t> ihdr;
    for (uint32_t v : {w, h})
        for (int i = 3; i >= 0; --i) ihdr.push_back(uint8_t(v >> (8 * i)));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filtering, no interlace
    chunk("IHDR", ihdr);
    chunk("IDAT", z);
    chunk("IEND", {});
    return png;
}

// A small car: a root, a body (matrix transform) with two instances of one wheel mesh (TRS), and a
// lamp node without mesh; two materials (a textured, double-sided MASK paint; a BLEND rubber with
// a normal map); two PNG textures.
SceneDescription make_scene() {
    SceneDescription s;
    SceneNode root;
    root.index = 0;
    root.name = "Car";
    root.translation = {1, 0, -2};
    root.rotation = {0, 0.38268343f, 0, 0.9238795f};  // 45 degrees about y
    SceneNode body;
    body.index = 1;
    body.parent = 0;
    body.mesh = 0;
    body.name = "Body";
    body.has_matrix = true;
    body.matrix = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0, 1};  // column-major: scale x 2, lift 0.5
    SceneNode front;
    front.index = 2;
    front.parent = 1;
    front.mesh = 1;
    front.name = "Wheel.Front";
    front.translation = {0.4f, -0.3f, 0};
    front.scale = {0.5f, 1, 1};
    SceneNode back = front;
    back.index = 3;
    back.name = "Wheel.Back";
    back.translation = {-0.4f, -0.3f, 0};
    SceneNode lamp;
    lamp.index = 4;
    lamp.parent = 0;
    lamp.name = "Lampe \xC3\xBC";  // UTF-8
    lamp.translation = {0, 1.5f, 0};
    s.nodes = {root, body, front, back, lamp};
    s.meshes = {{0, "Body", {{0, 0}}, {}}, {1, "Wheel", {{1, 1}}, {}}};

    Material paint;
    paint.name = "Paint";
    paint.base_color = {1, 0.9f, 0.8f, 1};
    paint.metallic = 0.25f;
    paint.roughness = 0.6f;
    paint.emissive = {0.1f, 0.05f, 0};
    paint.alpha_mode = AlphaMode::Mask;
    paint.alpha_cutoff = 0.3f;
    paint.double_sided = true;
    paint.base_color_texture = {0, 0, 1};
    Material rubber;
    rubber.name = "Rubber";
    rubber.base_color = {0.05f, 0.05f, 0.06f, 0.8f};
    rubber.metallic = 0;
    rubber.roughness = 0.9f;
    rubber.alpha_mode = AlphaMode::Blend;
    rubber.normal_texture = {1, 0, 0.5f};
    s.materials = {paint, rubber};

    SceneDescription::Texture checker;
    checker.info.image_type = ImageType::Png;
    checker.info.mag_filter = 9729;  // LINEAR
    checker.info.min_filter = 9987;  // LINEAR_MIPMAP_LINEAR
    checker.info.wrap_s = 33071;     // CLAMP_TO_EDGE
    checker.info.wrap_t = 10497;     // REPEAT
    checker.image = make_png(12, 12, 41);
    SceneDescription::Texture bumps;
    bumps.info.image_type = ImageType::Png;
    bumps.image = make_png(4, 4, 42);
    s.textures = {checker, bumps};
    return s;
}

// The car's geometry (format 1.1 packets, as the library writes them) and its scene packets,
// numbered after the geometry.
struct SceneStream {
    Stream geometry;
    ScenePackets scene;
    Packets all() const {
        Packets out = geometry.all();
        for (const auto* group : {&scene.scene, &scene.materials, &scene.textures, &scene.animations})
            out.insert(out.end(), group->begin(), group->end());
        return out;
    }
};

SceneStream make_scene_stream(const SceneDescription& scene, uint16_t packet_size) {
    SceneStream s;
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 6, 30, kAttrNormal | kAttrTexcoord),
                                    make_object({-0.5f, -0.5f, -0.5f}, 1, 4, 20, kAttrNormal)},
                                   packet_size);
    Rng rng(30);
    for (const ObjectInfo& o : info.objects) s.geometry.contents.push_back(make_content(info, o, rng));
    s.geometry.info = info;
    if (packetize_stream(info, s.geometry.contents, kStreamId, s.geometry.packets) != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed\n";
        std::exit(1);
    }
    const uint32_t next = uint32_t(s.geometry.all().size());
    if (packetize_scene(scene, packet_size, kStreamId, next, s.scene) != Error::Ok) {
        std::cerr << "make_vectors: packetize_scene failed\n";
        std::exit(1);
    }
    return s;
}

// A SCENE packet written from a batch as given (packetize_scene refuses bad references; the
// faulty vectors need them).
Packet scene_packet(const SceneBatch& batch, uint32_t sequence) {
    PacketHeader h;
    h.type = uint8_t(PacketType::Scene);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = kStreamObjectId;
    return write_packet(h, encode_scene_payload(batch));
}

// The whole node and mesh tables of `scene` in one SCENE packet.
SceneBatch whole_scene(const SceneDescription& scene) {
    return {uint16_t(scene.nodes.size()), uint16_t(scene.meshes.size()), scene.nodes, scene.meshes};
}

// The car's geometry, SCENE and MATERIAL packets in order, then its texture fragments shuffled
// (seeded), the second one sent twice (a byte-identical duplicate) and the first one again after the
// fourth with a new sequence number (a retransmission).
Packets with_shuffled_fragments(const SceneStream& stream, uint64_t seed) {
    Packets sent = stream.geometry.all();
    for (const auto* group : {&stream.scene.scene, &stream.scene.materials}) sent.insert(sent.end(), group->begin(), group->end());
    Packets frags = stream.scene.textures;
    Rng rng(seed);
    for (size_t i = frags.size(); i > 1; --i) std::swap(frags[i - 1], frags[rng.below(i)]);
    for (size_t i = 0; i < frags.size(); ++i) {
        sent.push_back(frags[i]);
        if (i == 1) sent.push_back(frags[i]);
        if (i == 3) {
            Packet again = frags[0];
            restamp_packet(again, 900);
            sent.push_back(again);
        }
    }
    return sent;
}

// Offsets in a TEXTURE_FRAGMENT payload (spec 15.3).
constexpr size_t kFragImageSize = kHeaderSize + 16, kFragImageCrc = kHeaderSize + 20, kFragOffset = kHeaderSize + 24,
                 kFragData = kHeaderSize + 28;

void scene_vectors(Writer& w) {
    const SceneDescription scene = make_scene();
    const SceneStream base = make_scene_stream(scene, 200);
    const Packets& fragments = base.scene.textures;  // texture 0: 4 fragments, texture 1: 1 fragment
    {
        const Packets sent = with_shuffled_fragments(base, 31);
        w.write("valid", "scene",
                "a format 1.1 scene (spec 15): 5 nodes (a root with TRS, a body with a matrix, one wheel mesh instanced "
                "by two nodes, a lamp without mesh, a UTF-8 name) over 3 SCENE packets, 2 materials (textured "
                "double-sided MASK paint with cutoff 0.3; BLEND rubber with a normal map of scale 0.5), 2 PNG textures "
                "(512 bytes in 4 fragments, 120 bytes in 1), the fragments out of order with a duplicate and a "
                "retransmission; every texture complete, every material shown",
                sent);
    }
    {
        // The same car with JPEG textures (image_type 2): real files from a JPEG encoder, baseline and
        // progressive (samples/jpeg_images.h), carried byte for byte like the PNGs.
        SceneDescription jpeg = scene;
        jpeg.textures[0].info.image_type = ImageType::Jpeg;
        jpeg.textures[0].image = samples::kJpegBaseline16;
        jpeg.textures[1].info.image_type = ImageType::Jpeg;
        jpeg.textures[1].image = samples::kJpegProgressive16;
        const SceneStream t = make_scene_stream(jpeg, 200);
        w.write("valid", "scene_jpeg",
                "the car of valid/scene with 2 JPEG textures (image_type 2; 16 x 16, made by a JPEG encoder): a "
                "baseline JPEG of 354 bytes in 3 fragments (the paint's base colour) and a progressive one of 583 "
                "bytes in 5 (the rubber's normal map), the fragments out of order with a duplicate and a "
                "retransmission; every texture complete, every material shown",
                with_shuffled_fragments(t, 32));
    }
    {
        // Smallest packets: one record per SCENE packet; everything scene-level sent first and twice.
        const SceneStream small = make_scene_stream(scene, kMinPacketSize);
        Packets sent;
        for (auto it = small.scene.textures.rbegin(); it != small.scene.textures.rend(); ++it) sent.push_back(*it);
        for (const auto& p : small.scene.materials) sent.push_back(p);
        for (auto it = small.scene.scene.rbegin(); it != small.scene.scene.rend(); ++it) sent.push_back(*it);
        uint32_t sequence = 2000;
        for (const auto* group : {&small.scene.scene, &small.scene.materials})
            for (Packet p : *group) {
                restamp_packet(p, sequence++);
                sent.push_back(p);
            }
        for (const auto& p : small.geometry.all()) sent.push_back(p);
        w.write("unusual", "scene_split_repeated",
                "packet size 128: the SCENE table split over one packet per record, sent in reverse order before the "
                "geometry, with the texture fragments (reversed) and materials first; SCENE and MATERIAL packets "
                "repeated with new sequence numbers are duplicates; decodes to the scene of valid/scene",
                sent);
    }
    {
        // What a later minor version may add (spec 15.1): a record of an unknown kind, and a node
        // record with fields appended after those of 1.1.
        Packets sent = base.geometry.all();
        std::vector<uint8_t> payload = payload_of(base.scene.scene[0]);
        put16(payload, 4, uint16_t(get16(payload, 4) + 1));  // record_count
        // Grow the first node record by 6 bytes.
        const uint16_t length = get16(payload, 9);
        put16(payload, 9, uint16_t(length + 6));
        const std::vector<uint8_t> extra = {0xE1, 0xE2, 0xE3, 0xE4, 0xE5, 0xE6};
        payload.insert(payload.begin() + 11 + length, extra.begin(), extra.end());
        const std::vector<uint8_t> unknown = {7, 5, 0, 'h', 'e', 'l', 'l', 'o'};  // kind 7, 5 bytes
        payload.insert(payload.begin() + 8, unknown.begin(), unknown.end());
        Packet grown = with_payload(base.scene.scene[0], payload);
        grown[5] = 2;  // minor version 2
        reseal(grown);
        sent.push_back(grown);
        sent.insert(sent.end(), base.scene.scene.begin() + 1, base.scene.scene.end());
        for (const auto* group : {&base.scene.materials, &base.scene.textures}) sent.insert(sent.end(), group->begin(), group->end());
        w.write("unusual", "scene_newer_records",
                "the first SCENE packet says format 1.2 and carries a record of the unknown kind 7 (skipped by its "
                "length) and 6 unknown bytes appended to its first node record (ignored: a packet that says 1.2 "
                "carries no skin field, spec 21), spec 15.1; decodes to the scene of valid/scene",
                sent);
    }
    {
        SceneDescription s = scene;
        s.materials[0].base_color_texture.texcoord = 1;
        const SceneStream t = make_scene_stream(s, 200);
        w.write("unusual", "scene_texcoord_1",
                "material 0's base colour texture on texture-coordinate set 1: the reference is ignored and the "
                "material shown without it (spec 15.4)",
                t.all());
    }
    {
        Packets sent;
        Packets geometry = base.geometry.all();
        mark_version_1_0(geometry);
        sent = geometry;
        for (const auto* group : {&base.scene.scene, &base.scene.materials, &base.scene.textures})
            sent.insert(sent.end(), group->begin(), group->end());
        w.write("unusual", "scene_geometry_1_0",
                "geometry packets say 1.0, scene packets 1.1 (spec 9 allows the lower minor version): a 1.1 decoder "
                "takes everything; a 1.0 decoder (as_1_0) skips the 10 scene packets and decodes the same objects",
                sent);
    }

    {
        // Table sizes 0 and 0 fix nothing (spec 15.1): an empty SCENE packet before the car's.
        Packets sent = base.geometry.all();
        sent.push_back(scene_packet(SceneBatch{}, 900));
        for (const auto* group : {&base.scene.scene, &base.scene.materials, &base.scene.textures})
            sent.insert(sent.end(), group->begin(), group->end());
        w.write("unusual", "scene_sizes_zero",
                "a SCENE packet with node_count 0, mesh_count 0 and no record before the car's SCENE packets: a "
                "duplicate (it brings no record) that fixes no table size (spec 15.1: sizes 0 and 0 fix nothing), so "
                "the SCENE packets after it, which say 5 nodes and 2 meshes, are accepted; decodes to the scene of "
                "valid/scene",
                sent);
    }

    // ---- faulty ----
    auto with_fragments = [&](const Packets& frags) {
        Packets sent = base.geometry.all();
        for (const auto* group : {&base.scene.scene, &base.scene.materials}) sent.insert(sent.end(), group->begin(), group->end());
        sent.insert(sent.end(), frags.begin(), frags.end());
        return sent;
    };
    // The stream with a u32 field of fragment `i` raised by `delta` (the packet resealed).
    auto with_fragment_u32 = [&](size_t i, size_t at, uint32_t delta) {
        Packets frags = fragments;
        put32(frags[i], at, get32(frags[i], at) + delta);
        reseal(frags[i]);
        return with_fragments(frags);
    };
    {
        Packets frags = {fragments[0], fragments[3], fragments[4]};
        w.write("faulty", "scene_texture_incomplete",
                "fragments 1 and 2 of texture 0 lost (bytes 148..443 of 512): no rejection; texture 0 is not complete "
                "and not shown, material 0 waits for it and is not shown either, its primitives get the default "
                "material (spec 15.4)",
                with_fragments(frags));
    }
    {
        Packets frags(fragments.begin(), fragments.begin() + 4);
        w.write("faulty", "scene_texture_lost",
                "every fragment of texture 1 lost: texture 1 is missing from the table, material 1 (its normal map) "
                "waits for it with 0 bytes received and is not shown (spec 15.4)",
                with_fragments(frags));
    }
    {
        w.write("faulty", "scene_fragment_past_end",
                "the last fragment of texture 0 moved one byte up, so that offset + data length exceeds image_size: "
                "rejected, malformed payload (spec 15.3: 'Malformed when ... offset + data length > image_size'); "
                "the texture stays incomplete",
                with_fragment_u32(3, kFragOffset, 1));
    }
    {
        w.write("faulty", "scene_fragment_size_mismatch",
                "fragment 2 of texture 0 declares image_size 612 where the others say 512: rejected, stream mismatch "
                "(spec 15.3: 'Fragments of one texture repeat the same description ..., else stream mismatch')",
                with_fragment_u32(2, kFragImageSize, 100));
    }
    {
        w.write("faulty", "scene_fragment_crc_mismatch",
                "fragment 1 of texture 0 declares another image_crc: rejected, stream mismatch (spec 15.3: 'Fragments "
                "of one texture repeat the same description ..., else stream mismatch')",
                with_fragment_u32(1, kFragImageCrc, 0x00010000u));
    }
    {
        Packets frags = fragments;
        frags[2][kFragData + 10] ^= 0x40;
        reseal(frags[2]);
        w.write("faulty", "scene_image_crc_wrong",
                "one image byte of fragment 2 of texture 0 changed (the packet checksum recomputed): every byte "
                "arrives, but the image's CRC-32C does not match image_crc; the completing fragment is rejected, "
                "stream mismatch, and the image's bytes are discarded (spec 15.3: 'When every byte has arrived, the "
                "image's CRC-32C MUST match image_crc; if it does not, the decoder discards the image's bytes and "
                "reports stream mismatch')",
                with_fragments(frags));
    }
    // The stream with every SCENE packet decoded, edited by `edit` and written again.
    auto edit_scene = [&](const std::function<void(SceneBatch&)>& edit) {
        Packets sent = base.all();
        for (Packet& p : sent) {
            if (p[6] != uint8_t(PacketType::Scene)) continue;
            SceneBatch b;
            if (decode_scene_payload(payload_of(p), b) != Error::Ok) std::exit(1);
            edit(b);
            p = scene_packet(b, get32(p, 12));
        }
        return sent;
    };
    auto edit_node = [&](uint16_t index, const std::function<void(SceneNode&)>& edit) {
        return edit_scene([&](SceneBatch& b) {
            for (SceneNode& n : b.nodes)
                if (n.index == index) edit(n);
        });
    };
    const size_t scene_sequence = base.geometry.all().size();
    {
        w.write("faulty", "scene_parent_out_of_range",
                "node 4 names parent 5 in a table of 5 nodes: the SCENE packet holding it is rejected, malformed payload "
                "(spec 15.1: 'The payload is malformed when ... a reference points outside its table'); the records of "
                "that packet (node 4, both meshes) are lost",
                edit_node(4, [](SceneNode& n) { n.parent = 5; }));
    }
    {
        w.write("faulty", "scene_node_own_parent",
                "node 4 names itself as its parent: the SCENE packet is rejected, malformed payload (spec 15.1: 'The "
                "payload is malformed when ... a node is its own parent'); the records of that packet are lost",
                edit_node(4, [](SceneNode& n) { n.parent = 4; }));
    }
    {
        w.write("faulty", "scene_name_not_utf8",
                "node 1's name holds bytes that are not UTF-8 (a lone 0xFF, a cut two-byte sequence 0xC3, an encoded "
                "surrogate 0xED 0xA0 0x80): nothing is rejected; a decoder shows the name with each maximal ill-formed "
                "subsequence replaced by U+FFFD (spec 15.1), and the stream does not conform",
                edit_node(1, [](SceneNode& n) { n.name = std::string("bad\xFF name \xC3 and \xED\xA0\x80"); }));
    }
    {
        w.write("faulty", "scene_parent_cycle",
                "nodes 2 and 3 name each other as parent: no packet can be rejected for it (spec 15.1: the links may "
                "arrive in different packets); neither node reaches a root, so both are left out like nodes whose "
                "parent chain did not arrive (spec 15.4); the stream does not conform (spec 15.4, completeness)",
                edit_scene([](SceneBatch& b) {
                    for (SceneNode& n : b.nodes)
                        if (n.index == 2 || n.index == 3) n.parent = uint16_t(5 - n.index);
                }));
    }
    {
        Packets sent = base.all();
        for (Packet& p : sent)
            if (p[6] == uint8_t(PacketType::Material) && get16(p, kHeaderSize) == 1) {
                p[kHeaderSize + 4] = 3;
                reseal(p);
            }
        w.write("faulty", "scene_alpha_mode_3",
                "material 1 with alpha_mode 3 (0..2 defined): rejected, malformed payload (spec 15.2: 'Malformed "
                "when ... alpha_mode > 2'); its primitives get the default material",
                sent);
    }
    {
        Packets sent = base.all();
        Packet& last_scene = sent[scene_sequence + base.scene.scene.size() - 1];
        auto payload = payload_of(last_scene);
        payload.resize(payload.size() - 10);
        last_scene = with_payload(last_scene, payload);
        w.write("faulty", "scene_truncated",
                "the last SCENE packet's payload cut by 10 bytes (payload_length and checksum follow): its last record "
                "runs past the payload, rejected, malformed payload (spec 15.1: 'The payload is malformed when a "
                "record runs past the payload'): node 4 and both meshes are lost, nodes 0..3 of the other SCENE "
                "packets are shown without meshes (spec 15.4)",
                sent);
    }
    {
        Packets sent = base.all();
        SceneBatch b = whole_scene(scene);
        b.nodes.resize(1);
        b.meshes.clear();
        b.nodes[0].translation[1] = 0.25f;
        sent.push_back(scene_packet(b, 999));
        w.write("faulty", "scene_contradicting_node",
                "a later SCENE packet repeats node 0 with another translation: rejected, stream mismatch (spec 15.1: "
                "'a record received twice is identical; otherwise stream mismatch'); the first node 0 stays",
                sent);
    }
    // The other rejections of spec 15, one vector each: a MATERIAL or TEXTURE_FRAGMENT payload field
    // edited (offsets into the payload as in 15.2 / 15.3), or a SCENE record, resealed.
    auto edit_packets = [&](PacketType type, const std::function<bool(Packet&)>& edit) {
        Packets sent = base.all();
        bool done = false;
        for (Packet& p : sent)
            if (!done && p[6] == uint8_t(type) && edit(p)) {
                reseal(p);
                done = true;
            }
        if (!done) std::exit(1);
        return sent;
    };
    const size_t H = kHeaderSize;
    auto material = [&](uint16_t index, const std::function<void(Packet&)>& edit) {
        return edit_packets(PacketType::Material, [&](Packet& p) {
            if (get16(p, H) != index) return false;
            edit(p);
            return true;
        });
    };
    auto first_fragment = [&](const std::function<void(Packet&)>& edit) {
        return edit_packets(PacketType::TextureFragment, [&](Packet& p) {
            edit(p);
            return true;
        });
    };
    w.write("faulty", "scene_node_mesh_out_of_range",
            "node 4 names mesh 9 in a table of 2 meshes: its SCENE packet is rejected, malformed payload (spec 15.1: "
            "'a node's parent or mesh is not 0xFFFF and not below node_count or mesh_count')",
            edit_node(4, [](SceneNode& n) { n.mesh = 9; }));
    w.write("faulty", "scene_transform_infinite",
            "node 1's transform holds +infinity (its translation x, or the matrix's when it has one): its SCENE packet "
            "is rejected, malformed payload (spec 15.1: 'a float is not finite')",
            edit_node(1, [](SceneNode& n) {
                const float inf = std::numeric_limits<float>::infinity();
                if (n.has_matrix) n.matrix[12] = inf;
                else n.translation[0] = inf;
            }));
    {
        Packets sent = base.all();
        SceneBatch b = whole_scene(scene);
        b.node_count = uint16_t(b.node_count + 1);
        b.nodes.resize(1);
        b.meshes.clear();
        sent.push_back(scene_packet(b, 998));
        w.write("faulty", "scene_table_size_contradicts",
                "a later SCENE packet says node_count 6 where the others say 5: rejected, stream mismatch (spec 15.1: "
                "'All SCENE packets of a stream carry the same table sizes')",
                sent);
    }
    w.write("faulty", "scene_material_index_out_of_range",
            "material 1 says index 2 in a table of 2 materials: rejected, malformed payload (spec 15.2: 'index >= "
            "material_count'); material 1 never arrives, its primitives get the default material",
            material(1, [&](Packet& p) { put16(p, H, 2); }));
    w.write("faulty", "scene_material_factor_nan",
            "material 1's metallic factor is NaN: rejected, malformed payload (spec 15.2: 'a float is not finite')",
            material(1, [&](Packet& p) { put32(p, H + 24, 0x7FC00000u); }));
    w.write("faulty", "scene_material_count_contradicts",
            "material 1 says material_count 3 where material 0 says 2: rejected, stream mismatch (spec 15.2: 'All "
            "MATERIAL packets of a stream carry the same material_count')",
            material(1, [&](Packet& p) { put16(p, H + 2, 3); }));
    w.write("faulty", "scene_texture_index_out_of_range",
            "the first texture fragment says index 2 in a table of 2 textures: rejected, malformed payload (spec 15.3: "
            "'index >= texture_count')",
            first_fragment([&](Packet& p) { put16(p, H, 2); }));
    w.write("faulty", "scene_texture_image_type_3",
            "the first texture fragment says image_type 3 (1 PNG, 2 JPEG): rejected, malformed payload (spec 15.3: "
            "'the image type is unknown')",
            first_fragment([&](Packet& p) { p[H + 4] = 3; }));
    {
        Packets sent = base.all();
        for (auto it = sent.rbegin(); it != sent.rend(); ++it)
            if ((*it)[6] == uint8_t(PacketType::TextureFragment)) {
                put16(*it, H + 2, 3);
                reseal(*it);
                break;
            }
        w.write("faulty", "scene_texture_count_contradicts",
                "the last texture fragment (texture 1's only one) says texture_count 3 where the others say 2: "
                "rejected, stream mismatch (spec 15.3: 'All fragments of a stream carry the same texture_count'); "
                "texture 1 never arrives and material 1 waits for it (spec 15.4)",
                sent);
    }
    {
        Packets sent = base.all();
        for (Packet& p : sent)
            if (p[6] == uint8_t(PacketType::TextureFragment)) {
                std::vector<uint8_t> payload = payload_of(p);
                payload.resize(28);  // the description without a data byte
                p = with_payload(p, payload);
                break;
            }
        w.write("faulty", "scene_texture_no_data",
                "the first texture fragment carries its 28-byte description and no image byte: rejected, malformed "
                "payload (spec 15.3: 'there is no data byte')",
                sent);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.2: signed streams (spec 16). Every signed vector is signed with vectors_key() (seed 00..1F)
// unless it says otherwise; the expected decode authenticates with that key.

// A small stream of 1.0 packets, and its MANIFEST parts at `packet_size` (several parts when small).
struct SignedStream {
    Packets manifests;  // MANIFEST parts, in part order
    Packets listed;     // the packets they list, in listed order
};

// Scheme 1 (format 1.2) unless told otherwise: the signed* vectors of section 16; the signed_bound*
// vectors of section 25 are signed with scheme 2.
SignedStream signed_stream(uint64_t seed, uint16_t packet_size, const auth::KeyPair& key,
                           uint8_t scheme = kManifestSchemeEd25519, uint32_t points = 48) {
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 6, points, kAttrNormal)}, packet_size);
    Stream s = make_stream(info, kStreamId, seed);
    SignedStream out;
    out.listed = s.all();
    std::string error;
    if (auth::sign_packets(out.listed, key, packet_size, 0, out.manifests, error, scheme) != Error::Ok) {
        std::cerr << "make_vectors: signing failed: " << error << "\n";
        std::exit(1);
    }
    return out;
}

// Packets numbered in file order.
Packets signed_numbered(Packets p) {
    for (uint32_t i = 0; i < p.size(); ++i) restamp_packet(p[i], i);
    return p;
}

// MANIFEST parts first, then the listed packets, numbered in file order.
Packets signed_file(const SignedStream& s) {
    Packets out = s.manifests;
    out.insert(out.end(), s.listed.begin(), s.listed.end());
    return signed_numbered(out);
}

// Offsets in a MANIFEST packet (header included).
constexpr size_t kManifestPart = kHeaderSize + 2, kManifestPartCount = kHeaderSize + 4,
                 kManifestDigestCount = kHeaderSize + 6, kManifestFirst = kHeaderSize + 12,
                 kManifestDigests = kHeaderSize + 24;

void signed_vectors(Writer& w) {
    const auth::KeyPair key = conformance::vectors_key();
    {
        // 300-byte packets: 10 digests per part, so the stream's 10 packets take two parts (the base
        // part lists the STREAM_INFO and ELLIPSOIDS packets, the detail part the POINTS packets).
        SignedStream s = signed_stream(41, 300, key);
        w.write("valid", "signed",
                "a signed stream (format 1.2): two MANIFEST parts (base, detail) before the 1.0 packets they list; "
                "every part verifies with the vectors' key and every packet passes",
                signed_file(s));
    }
    {
        // A carousel of a signed stream: each part goes before the packets it lists and comes again
        // later, packets repeat, sequence numbers count transmissions.
        SignedStream s = signed_stream(42, 300, key);
        Packets sent;
        for (int cycle = 0; cycle < 2; ++cycle)
            for (size_t m = 0; m < s.manifests.size(); ++m) {
                sent.push_back(s.manifests[m]);
                PacketView view;
                ManifestPart part;
                parse_packet(s.manifests[m], view);
                decode_manifest_payload(view.payload, part);
                for (size_t i = part.first; i < part.first + part.digests.size(); ++i) sent.push_back(s.listed[i]);
            }
        for (uint32_t i = 0; i < sent.size(); ++i) restamp_packet(sent[i], i);
        w.write("valid", "signed_carousel",
                "a signed stream sent twice as a carousel: every MANIFEST part before the packets it lists; the "
                "second copies are repeats (same digest whatever the sequence number)",
                sent);
    }
    {
        // The MANIFEST parts at the end of the file: a recording is authenticated as a whole.
        SignedStream s = signed_stream(43, 300, key);
        Packets out = s.listed;
        out.insert(out.end(), s.manifests.begin(), s.manifests.end());
        for (uint32_t i = 0; i < out.size(); ++i) restamp_packet(out[i], i);
        w.write("unusual", "signed_manifest_last",
                "a signed stream whose MANIFEST parts come after every packet they list: a recording is "
                "authenticated as a whole (spec 16.3), so every packet passes",
                out);
    }
    {
        SignedStream s = signed_stream(44, 300, key);
        Packets out = signed_file(s);
        // A MANIFEST of a later scheme (3) with a layout of its own: skipped, whatever its length.
        Packet later = s.manifests[0];
        std::vector<uint8_t> payload = {3, 0, 0xAB, 0xCD, 0xEF};
        out.insert(out.begin() + 1, with_payload(later, payload));
        for (uint32_t i = 0; i < out.size(); ++i) restamp_packet(out[i], i);
        w.write("unusual", "signed_unknown_scheme",
                "a signed stream plus a 5-byte MANIFEST of scheme 3: a decoder skips it (spec 16.2), with or "
                "without a key; the scheme-1 parts verify",
                out);
    }
    {
        const auth::KeyPair other = [] {
            auth::Seed seed;
            for (size_t i = 0; i < seed.size(); ++i) seed[i] = static_cast<uint8_t>(0x20 + i);
            return auth::key_pair_from_seed(seed);
        }();
        SignedStream s = signed_stream(45, 300, other);
        w.write("faulty", "signed_wrong_key",
                "a stream signed with another key (seed 20..3F): both MANIFEST parts are rejected with the vectors' "
                "key (bad manifest signature: another key id) and no packet is authenticated",
                signed_file(s));
    }
    {
        SignedStream s = signed_stream(46, 300, key);
        Packets out = signed_file(s);
        out[0][kManifestDigests] ^= 0x01;  // one bit of part 0's first digest, checksum resealed
        reseal(out[0]);
        w.write("faulty", "signed_tampered_manifest",
                "part 0 of the manifest has one bit of a digest flipped (checksum valid): its signature fails (bad "
                "manifest signature) and the packets only it listed are not authenticated",
                out);
    }
    {
        // Spec 16.3: R of small order is rejected. Part 0's signature replaced by (R, S) with R the encoding
        // of the neutral element (01 00 .. 00) and S = k a mod L (a the vectors' secret scalar, k the
        // SHA-512 of R || A || message mod L): [S]B - [k]A is then the neutral element, whose encoding is R,
        // so the cofactorless equation holds and only the small-order rule rejects the signature.
        SignedStream s = signed_stream(49, 300, key);
        Packets out = signed_file(s);
        Packet& m = out[0];
        PacketView view;
        ManifestPart part;
        if (parse_packet(m, view) != Error::Ok || decode_manifest_payload(view.payload, part) != Error::Ok ||
            sodium_init() < 0) {
            std::cerr << "make_vectors: cannot take part 0 of the signed stream apart\n";
            std::exit(1);
        }
        const std::vector<uint8_t> message = manifest_signed_message(m);
        std::array<uint8_t, 32> r{};
        r[0] = 1;
        uint8_t h[64], k[32], az[64], wide[64] = {}, a[32], sig_s[32];
        crypto_hash_sha512_state st;
        crypto_hash_sha512_init(&st);
        crypto_hash_sha512_update(&st, r.data(), r.size());
        crypto_hash_sha512_update(&st, key.public_key.data(), key.public_key.size());
        crypto_hash_sha512_update(&st, message.data(), message.size());
        crypto_hash_sha512_final(&st, h);
        crypto_core_ed25519_scalar_reduce(k, h);
        crypto_hash_sha512(az, key.seed.data(), key.seed.size());
        az[0] &= 248;
        az[31] &= 127;
        az[31] |= 64;
        std::memcpy(wide, az, 32);
        crypto_core_ed25519_scalar_reduce(a, wide);
        crypto_core_ed25519_scalar_mul(sig_s, k, a);
        // Check the equation: [S]B = [k]A.
        uint8_t sb[32], ka[32];
        if (crypto_scalarmult_ed25519_base_noclamp(sb, sig_s) != 0 ||
            crypto_scalarmult_ed25519_noclamp(ka, k, key.public_key.data()) != 0 || std::memcmp(sb, ka, 32) != 0) {
            std::cerr << "make_vectors: the small-order R signature does not meet the equation\n";
            std::exit(1);
        }
        std::copy(r.begin(), r.end(), part.signature.begin());
        std::copy(sig_s, sig_s + 32, part.signature.begin() + 32);
        m = write_packet(view.header, encode_manifest_payload(part));
        if (manifest_signed_message(m) != message) {
            std::cerr << "make_vectors: the signed message changed\n";
            std::exit(1);
        }
        w.write("faulty", "signed_small_order_r",
                "part 0 of the manifest with its signature replaced by R = 01 00 .. 00 (the encoding of the neutral "
                "element, a point of small order) and S = k a mod L (a the vectors' secret scalar, k = SHA-512(R || A "
                "|| message) mod L), so that [S]B - [k]A is the neutral element and its encoding equals R: the "
                "cofactorless equation holds, but R is of small order (spec 16.3): bad manifest signature; the "
                "packets only part 0 lists are not authenticated",
                out);
    }
    {
        SignedStream s = signed_stream(47, 300, key);
        Packets out = signed_file(s);
        // A forged POINTS packet: the last one with one coordinate byte changed, checksum resealed.
        Packet& points = out.back();
        points[kHeaderSize + 12] ^= 0x5A;
        reseal(points);
        w.write("faulty", "signed_forged_points",
                "the last POINTS packet altered after signing (checksum valid): without a key it is accepted; with "
                "the key its digest is listed nowhere and it is rejected (not authenticated)",
                out);
    }
    {
        SignedStream s = signed_stream(48, 300, key);
        Packets out = signed_file(s);
        // A packet the manifest does not list: a forger's copy of the first POINTS packet with other
        // positions, sent before the real stream info (so a decoder without a key holds it, then takes
        // it, and the real packet with the same point indices comes too late).
        Packet forged = s.listed[2];
        for (size_t i = kHeaderSize + 8; i < kHeaderSize + 40; ++i) forged[i] ^= 0x5A;
        reseal(forged);
        out.insert(out.begin() + 2, forged);
        for (uint32_t i = 0; i < out.size(); ++i) restamp_packet(out[i], i);
        w.write("faulty", "signed_unlisted_packet",
                "a signed stream with a CRC-valid POINTS packet no MANIFEST lists, before the stream info: without a key "
                "its points are taken and the real ones with the same indices are duplicates; with the key it is "
                "rejected (not authenticated) and every real point is taken",
                out);
    }
    // Malformed MANIFEST payloads (spec 16.2): each rejected as malformed payload, with or without a key.
    struct Malformed {
        const char* name;
        const char* description;
        std::function<void(Packet&)> edit;
    };
    const std::vector<Malformed> malformed = {
        {"signed_manifest_empty", "a MANIFEST with payload_length 0: malformed payload",
         [](Packet& p) { p = with_payload(p, {}); }},
        {"signed_manifest_short", "a scheme-1 MANIFEST of 87 bytes (less than 88): malformed payload",
         [](Packet& p) {
             std::vector<uint8_t> payload = payload_of(p);
             payload.resize(87);
             p = with_payload(p, payload);
         }},
        {"signed_manifest_count_mismatch",
         "a MANIFEST whose digest_count is one more than its length holds: malformed payload",
         [](Packet& p) {
             put16(p, kManifestDigestCount, uint16_t(get16(p, kManifestDigestCount) + 1));
             reseal(p);
         }},
        {"signed_manifest_part_count_zero", "a MANIFEST with part_count 0: malformed payload",
         [](Packet& p) {
             put16(p, kManifestPartCount, 0);
             reseal(p);
         }},
        {"signed_manifest_part_past_count", "a MANIFEST whose part equals its part_count: malformed payload",
         [](Packet& p) {
             put16(p, kManifestPart, get16(p, kManifestPartCount));
             reseal(p);
         }},
        {"signed_manifest_range_past_count",
         "a MANIFEST whose first + digest_count exceeds packet_count (first = 2^32 - 1, no overflow): malformed payload",
         [](Packet& p) {
             put32(p, kManifestFirst, 0xFFFFFFFFu);
             reseal(p);
         }},
    };
    uint64_t seed = 50;
    for (const Malformed& m : malformed) {
        SignedStream s = signed_stream(seed++, 300, key);
        Packets out = signed_file(s);
        m.edit(out[0]);
        w.write("faulty", m.name, m.description, out);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.9: MANIFEST scheme 2, bound to a content (spec 25). The same small 1.0 stream as the
// signed* vectors, signed with scheme 2: its MANIFEST packets say 1.9 and carry the content id of its
// STREAM_INFO.

void bound_manifest_vectors(Writer& w) {
    const auth::KeyPair key = conformance::vectors_key();
    {
        SignedStream s = signed_stream(70, 300, key, kManifestSchemeBound);
        w.write("valid", "signed_bound",
                "a stream signed with scheme 2 (format 1.9): two MANIFEST parts bound to the STREAM_INFO's content "
                "id before the 1.0 packets they list; the stream's content is set by its STREAM_INFO and every "
                "packet passes",
                signed_file(s));
    }
    {
        // The STREAM_INFO last: a recording takes the content from it, whatever its place (spec 25.2).
        SignedStream s = signed_stream(71, 300, key, kManifestSchemeBound);
        Packets out = s.manifests;
        out.insert(out.end(), s.listed.begin() + 1, s.listed.end());
        out.push_back(s.listed[0]);
        w.write("unusual", "signed_bound_info_last",
                "a scheme-2 signed stream whose only STREAM_INFO is its last packet: a recording takes the "
                "stream's content from it (spec 25.2), so the ELLIPSOIDS and POINTS packets before it pass too",
                signed_numbered(out));
    }
    {
        // Two contents signed with the same key under the same stream id, spliced: the first's manifest,
        // STREAM_INFO and ELLIPSOIDS, the second's manifest and POINTS (row 4 of the hostile streams).
        SignedStream a = signed_stream(72, 300, key, kManifestSchemeBound);
        SignedStream b = signed_stream(73, 300, key, kManifestSchemeBound, 40);  // other points: none shared
        Packets out = a.manifests;
        out.insert(out.end(), b.manifests.begin(), b.manifests.end());
        for (const Packet& p : a.listed)
            if (p[6] != uint8_t(PacketType::Points)) out.push_back(p);
        for (const Packet& p : b.listed)
            if (p[6] == uint8_t(PacketType::Points)) out.push_back(p);
        out.push_back(b.listed[0]);  // and last, the second's STREAM_INFO: it cannot switch the stream (rule 2)
        w.write("faulty", "signed_bound_spliced",
                "two contents signed with scheme 2 by the vectors' key under one stream id, spliced: the first's "
                "STREAM_INFO and ELLIPSOIDS (48 points declared), the second's POINTS (40 points on the same sphere, "
                "none the same packet), both manifests (all four parts verify), then the second's STREAM_INFO: the "
                "stream shows the first content, whose manifest does not list the POINTS packets: each is rejected (not "
                "authenticated), and so is the second STREAM_INFO (another content's). Without a key the points would "
                "be decoded as the first content's",
                signed_numbered(out));
    }
    {
        // A part bound to another content than its STREAM_INFO's (a signer's error): the STREAM_INFO is
        // rejected by rule 2, the stream gets no content, and nothing it lists passes.
        SignedStream s = signed_stream(74, 300, key, kManifestSchemeBound);
        Packets manifests;
        for (const Packet& m : s.manifests) {
            PacketView view;
            ManifestPart part;
            parse_packet(m, view);
            decode_manifest_payload(view.payload, part);
            part.content_id ^= 0x00010000u;
            manifests.push_back(auth::signed_manifest_packet(view.header, part, key));
        }
        const Packets out = signed_file({manifests, s.listed});
        w.write("faulty", "signed_bound_content_mismatch",
                "a scheme-2 manifest whose parts (signatures valid) are bound to content id 0x00010000 XOR that of "
                "the STREAM_INFO they list: the STREAM_INFO is rejected (not authenticated: listed for another "
                "content), the stream gets no content, and every other packet is rejected too",
                out);
    }
    {
        SignedStream s = signed_stream(75, 300, key, kManifestSchemeBound);
        Packets out = signed_file(s);
        std::vector<uint8_t> payload = payload_of(out[0]);
        payload.resize(91);
        out[0] = with_payload(out[0], payload);
        w.write("faulty", "signed_bound_manifest_short",
                "a scheme-2 MANIFEST of 91 bytes (less than 92): malformed payload; the packets only it listed are "
                "not authenticated",
                out);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.2: repair packets (POINTS_REPAIR, spec 17). The streams are 1.0 streams; their
// POINTS_REPAIR packets, made by packetize_repairs over the blocks plan_repair_blocks cuts, say 1.2.

// The repair vectors' stream: one object (12 ellipsoids, `points` points with normals) at packet size
// 200: records of B = 3 x 14 + 2 x 10 = 62 bits, 21 points a POINTS packet (a symbol of 164 bytes, 4
// padding bits after 21 records). Its blocks are the POINTS packets' batches of 21 points, at most
// `max_sources` a block; repairs[b] holds block b's POINTS_REPAIR packets of rows k .. k + rows - 1.
struct RepairStream {
    Stream s;
    std::vector<RepairBlock> blocks;
    std::vector<Packets> repairs;
    const Packet& info() const { return s.packets.stream_info[0]; }
    const Packet& ellipsoids(size_t i) const { return s.packets.ellipsoids[i]; }
    const Packet& points(size_t i) const { return s.packets.points[i]; }
    // Block b's packet of row r.
    const Packet& repair(size_t b, unsigned r) const { return repairs[b].at(r - blocks[b].source_count()); }
    // A POINTS packet of the points [first, first + count), cut where the packetizer would not cut.
    Packet points_packet(uint32_t first, uint32_t count) const {
        PointBatch batch;
        batch.first_index = first;
        batch.points.assign(s.contents[0].points.begin() + first, s.contents[0].points.begin() + first + count);
        PacketHeader h;
        h.version_minor = 0;
        h.type = uint8_t(PacketType::Points);
        h.stream_id = kStreamId;
        h.object_id = 0;
        return write_packet(h, encode_points_payload(batch, s.info, s.info.objects[0]));
    }
};

RepairStream repair_stream(uint32_t points, size_t max_sources, size_t rows, uint64_t seed) {
    RepairStream r;
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 12, points, kAttrNormal)}, 200);
    r.s = make_stream(info, kStreamId, seed);
    const auto batch = uint16_t(points_per_packet(info.packet_size, info, info.objects[0]));
    r.blocks = plan_repair_blocks(points, batch, max_sources);
    uint32_t sequence = uint32_t(r.s.all().size());
    for (const RepairBlock& b : r.blocks) {
        Packets out;
        if (packetize_repairs(info, 0, r.s.contents[0].points, {b}, rows, kStreamId, sequence, out) != Error::Ok) {
            std::cerr << "make_vectors: packetize_repairs failed\n";
            std::exit(1);
        }
        sequence += uint32_t(out.size());
        r.repairs.push_back(out);
    }
    return r;
}

// Packets numbered in file order from `first`.
Packets numbered(Packets p, uint32_t first = 0) {
    for (uint32_t i = 0; i < p.size(); ++i) restamp_packet(p[i], first + i);
    return p;
}

// Offsets in a POINTS_REPAIR packet (header included), spec 17.3.
constexpr size_t kRepairFirst = kHeaderSize, kRepairBatch = kHeaderSize + 4, kRepairSources = kHeaderSize + 6,
                 kRepairRow = kHeaderSize + 7, kRepairSymbol = kHeaderSize + 8;

void repair_vectors(Writer& w) {
    // 100 points: POINTS packets P0..P4 of points [0,21) [21,42) [42,63) [63,84) [84,100); at most 3
    // batches a block: block 0 = P0 P1 (k 2, rows 2..), block 1 = P2 P3 P4 from point 42 (k 3, rows 3..),
    // cut at the object's last point (58 points, the last batch 16).
    const RepairStream r = repair_stream(100, 3, 3, 60);
    {
        // As a carousel sends it (each block's POINTS and repair packets interleaved), under loss: the
        // packets lost leave gaps in the sequence numbers.
        struct Sent {
            Packet p;
            bool lost;
        };
        const std::vector<Sent> sent = {
            {r.info(), false},        {r.ellipsoids(0), false}, {r.ellipsoids(1), false}, {r.points(0), false},
            {r.repair(0, 2), false},  {r.points(1), true},      {r.repair(0, 3), true},   {r.points(2), true},
            {r.repair(1, 3), false},  {r.points(3), false},     {r.repair(1, 4), true},   {r.points(4), true},
            {r.repair(1, 5), false},
        };
        Packets file;
        for (uint32_t i = 0; i < sent.size(); ++i) {
            if (sent[i].lost) continue;
            Packet p = sent[i].p;
            restamp_packet(p, i);
            file.push_back(p);
        }
        w.write("valid", "repair",
                "repair packets (format 1.2, spec 17): one object, 12 ellipsoids, 100 points with normals, packet "
                "size 200, 5 POINTS packets of 21 points in 2 blocks (points 0..41: k 2; points 42..99: k 3, cut at "
                "the last point, its last batch 16 points), sent as a carousel interleaves them, with POINTS P1, P2, "
                "P4 and repair rows 3 of block 0 and 4 of block 1 lost (gaps in the sequence numbers): block 0 "
                "recovers P1 from row 2 as soon as it arrives; block 1 waits for P3, then recovers P2 and P4 from "
                "rows 3 and 5; every point is present, 58 of them recovered",
                file);
    }
    {
        // Repairs before the STREAM_INFO: held (11.2), released in arrival order (11.1) and used.
        const Packets file = numbered({r.repair(1, 3), r.repair(0, 2), r.repair(1, 4), r.ellipsoids(0), r.points(0),
                                       r.points(3), r.info(), r.ellipsoids(1)});
        w.write("unusual", "repair_before_stream_info",
                "the stream of valid/repair with three POINTS_REPAIR packets (block 1 row 3, block 0 row 2, block 1 "
                "row 4), an ELLIPSOIDS and POINTS P0 and P3 before the STREAM_INFO: all held (a POINTS_REPAIR is held "
                "like a POINTS packet, spec 17.3), then released in arrival order (11.1): the repairs first (their "
                "blocks hold no point yet), then P0, which lets block 0 recover P1 from row 2, and P3, which lets "
                "block 1 recover P2 and P4 from rows 3 and 4",
                file);
    }
    {
        // Blocks of one source batch (k = 1): a repair row is the batch times inv(row).
        const RepairStream one = repair_stream(100, 1, 254, 60);
        const Packets file = numbered({one.info(), one.ellipsoids(0), one.ellipsoids(1), one.points(0), one.repair(0, 1),
                                       one.repair(1, 1), one.points(2), one.points(3), one.repair(4, 254),
                                       one.repair(4, 2)});
        w.write("unusual", "repair_one_batch",
                "blocks of one source batch (k = 1, spec 17.2: row r is inv(r) times the batch's symbol): the stream "
                "of valid/repair in 5 blocks, one a POINTS packet; P1 and P4 lost; block 0's row 1 arrives after P0 "
                "(a duplicate: the block is complete, and held with no row), block 1's row 1 (C = 1: the symbol is "
                "the batch's records) recovers P1, block 4's row 254 (C = inv(254)) recovers P4's 16 points, its row "
                "2 after that is a duplicate",
                file);
    }
    {
        // More rows than needed: rows beyond the u a recovery takes, and repeats, are duplicates; a POINTS
        // packet that completes a batch starts the recovery.
        Packet again = r.repair(1, 3);
        const Packets file =
            numbered({r.info(), r.ellipsoids(0), r.ellipsoids(1), r.points(0), r.points(1), r.repair(0, 2),
                      r.repair(0, 3), r.repair(1, 3), r.repair(1, 4), r.points(3), r.repair(1, 5), r.points(2),
                      r.points(4), again});
        w.write("unusual", "repair_extra_rows",
                "more repair rows than needed: block 0's rows 2 and 3 arrive after P0 and P1 (duplicates: the block "
                "is complete); block 1's rows 3 and 4 are kept (all 3 batches missing), P3 then completes batch 1 "
                "and block 1 recovers P2 and P4 from rows 3 and 4 (spec 17.4: after accepting a POINTS packet); its "
                "row 5, P2, P4 and row 3 again (renumbered) are duplicates",
                file);
    }
    {
        // Source symbols are functions of the points, not of the packets (spec 17.1): POINTS packets of
        // 13 points, cut across the batches and across the blocks.
        Packets file = {r.info(), r.ellipsoids(0), r.ellipsoids(1)};
        for (uint32_t first : {0u, 13u, 39u, 65u, 78u, 91u}) file.push_back(r.points_packet(first, std::min(13u, 100 - first)));
        file.push_back(r.repair(0, 2));
        file.push_back(r.repair(1, 3));
        file.push_back(r.repair(1, 4));
        w.write("unusual", "repair_points_cut_differently",
                "the object of valid/repair sent in POINTS packets of 13 points (0..12, 13..25, 39..51, 65..77, 78..90, "
                "91..99; 26..38 and 52..64 lost), cut across the blocks' batches of 21 and across the blocks (39..51): "
                "source symbols are formed from the points held, however they came (spec 17.1); block 0 forms batch "
                "0 from two packets and recovers 26..38 from row 2 (batch 1's other points held are kept); block 1, "
                "with only batch 2 whole, recovers 52..64 from rows 3 and 4",
                numbered(file));
    }
    {
        // A block cut at the object's last point: 43 points, one block of 3 batches of 21 from point 0,
        // the last batch 1 point (its symbol: one 62-bit record, then zero bits to 164 bytes).
        const RepairStream s = repair_stream(43, 3, 3, 61);
        const Packets file = numbered({s.info(), s.ellipsoids(0), s.ellipsoids(1), s.points(1), s.repair(0, 4), s.repair(0, 5)});
        w.write("unusual", "repair_short_last_batch",
                "a block cut at the object's last point (spec 17.1): 43 points, one block of k = 3 batches of 21 from "
                "point 0, its last batch the single point 42; P0 and the 1-point P2 lost, recovered from rows 4 and 5",
                file);
    }

    // Faulty: the file of valid/repair plus one defective POINTS_REPAIR packet (resealed), every MUST-reject
    // rule of spec 17.3 one vector each.
    const Packets good = numbered({r.info(), r.ellipsoids(0), r.ellipsoids(1), r.points(0), r.repair(0, 2),
                                   r.repair(1, 3), r.points(3), r.repair(1, 5)});
    // A copy of block 1's row 4 (lost from the file) with `edit` applied, numbered 1000 and resealed.
    auto defective = [&](const std::function<void(Packet&)>& edit) {
        Packet p = r.repair(1, 4);
        put32(p, 12, 1000);
        edit(p);
        reseal(p);
        return p;
    };
    struct RepairEdit {
        const char* name;
        const char* description;
        std::function<void(Packet&)> edit;
        bool last;  // after the stream (else first, before the STREAM_INFO)
    };
    const std::vector<RepairEdit> edits = {
        {"repair_payload_short",
         "a POINTS_REPAIR packet whose payload is its 8-byte header without a symbol byte, before the STREAM_INFO: "
         "rejected at once (malformed payload, spec 17.3: shorter than 9 bytes; step 11 needs no stream info), not held",
         [](Packet& p) { p = with_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kRepairSymbol)); },
         false},
        {"repair_batch_zero",
         "a POINTS_REPAIR packet with batch 0, before the STREAM_INFO: rejected at once (malformed payload, spec 17.3), not held",
         [](Packet& p) { put16(p, kRepairBatch, 0); }, false},
        {"repair_source_count_zero",
         "a POINTS_REPAIR packet with source_count 0, before the STREAM_INFO: rejected at once (malformed payload, spec 17.3), not held",
         [](Packet& p) { p[kRepairSources] = 0; }, false},
        {"repair_row_below_source_count",
         "a POINTS_REPAIR packet with row 2 and source_count 3 (rows 0..2 are the source symbols themselves), before "
         "the STREAM_INFO: rejected at once (malformed payload, spec 17.3), not held",
         [](Packet& p) { p[kRepairRow] = 2; }, false},
        {"repair_row_255",
         "a POINTS_REPAIR packet with row 255 (rows end at 254), before the STREAM_INFO: rejected at once (malformed "
         "payload, spec 17.3), not held",
         [](Packet& p) { p[kRepairRow] = 255; }, false},
        {"repair_index_overflow",
         "a POINTS_REPAIR packet with first_index 4294967254 (2^32 - 42), batch 21, source_count 3: its last batch "
         "would start at 2^32, past 2^32 - 1 (0 in 32-bit arithmetic), before the STREAM_INFO: rejected at once "
         "(malformed payload, spec 17.3), not held",
         [](Packet& p) { put32(p, kRepairFirst, 0xFFFFFFD6u); }, false},
        {"repair_symbol_length",
         "a POINTS_REPAIR packet whose symbol is 163 bytes where batch 21 of 62-bit records makes 164, before the "
         "STREAM_INFO: held (the length needs the object's entry), then rejected when released (malformed payload, "
         "spec 17.3 step 13)",
         [](Packet& p) {
             std::vector<uint8_t> payload = payload_of(p);
             payload.pop_back();
             p = with_payload(p, payload);
         },
         false},
        {"repair_index_out_of_range",
         "a POINTS_REPAIR packet of a block from point 58, batch 21, source_count 3: its last batch would start at "
         "point 100, the object's point_count, before the STREAM_INFO: held, then rejected when released (index out "
         "of range, spec 17.3 step 14: every source batch holds at least one point)",
         [](Packet& p) { put32(p, kRepairFirst, 58); }, false},
        {"repair_block_contradicts",
         "after the stream, a POINTS_REPAIR packet of a block from point 0 (block 0's first_index) with "
         "source_count 3 instead of 2 (row 4): rejected (stream mismatch, spec 17.3: blocks are keyed by "
         "first_index and must not overlap)",
         [](Packet& p) { put32(p, kRepairFirst, 0); }, true},
        {"repair_block_overlap",
         "after the stream, a POINTS_REPAIR packet of a block from point 21 (batch 21, source_count 3, row 4), "
         "inside block 0 (points 0..41) and overlapping block 1: rejected (stream mismatch, spec 17.3)",
         [](Packet& p) { put32(p, kRepairFirst, 21); }, true},
    };
    for (const RepairEdit& e : edits) {
        Packets file = good;
        const Packet bad = defective(e.edit);
        if (e.last) file.push_back(bad);
        else file.insert(file.begin(), bad);
        w.write("faulty", e.name, e.description, file);
    }
    {
        // A forged symbol (valid checksum, wrong symbol): block 1's row 3 with one byte changed. Block 1
        // (points 42..99) holds parts of batches 0 and 1 and rows 3 (forged) and 4 when one POINTS packet
        // completes batches 0 and 1: u = 1, and the decoder recovers batch 2 from the FIRST row it
        // accepted, the forged one. The honest row 4 is then not R_4 of the points held: a validator
        // reports it (spec 17.4).
        Packet forged = r.repair(1, 3);
        forged[kRepairSymbol + 10] ^= 0x5A;  // bits 80..87 of batch 2's symbol: point 85's record
        reseal(forged);
        const Packets file = numbered({r.info(), r.ellipsoids(0), r.ellipsoids(1), r.points(0), r.points(1),
                                       r.points_packet(42, 13), r.points_packet(66, 18), forged, r.repair(1, 4),
                                       r.points_packet(55, 11)});
        w.write("faulty", "repair_forged_symbol",
                "a forged POINTS_REPAIR symbol (one byte changed, checksum valid) used in a recovery: block 1 holds "
                "points 42..54 and 66..83 of its batches 0 and 1 and rows 3 (forged) and 4 when the POINTS packet of "
                "55..65 completes both batches; u = 1 and the decoder recovers batch 2 (84..99) from the first row it "
                "accepted, row 3 (spec 17.4): point 85's y is wrong (9746 instead of 9138), and nothing in the block "
                "shows it to a decoder (one that took row 4 instead would recover the right points). A validator finds "
                "that row 4 is not the repair symbol of the points held (spec 11.5, 17.4)",
                file);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.3: material extensions (MATERIAL_EXTENSIONS, spec 18). The car of the scene vectors with a
// third texture (a clearcoat map) and a JSON patch on each material, at packet size 400 so that the
// patches fit: MATERIAL packets say 1.1 with flags bit 0 set, MATERIAL_EXTENSIONS packets say 1.3.

// Material 0 (the paint): a clearcoat with its own texture (2), an emissive strength, and a texture
// transform on its core base colour texture.
const std::string kPatchPaint =
    R"({"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":0.8,"clearcoatTexture":{"index":2},)"
    R"("clearcoatRoughnessFactor":0.2},"KHR_materials_emissive_strength":{"emissiveStrength":4.5}},)"
    R"("pbrMetallicRoughness":{"baseColorTexture":{"extensions":{"KHR_texture_transform":{"offset":[0.25,0],)"
    R"("rotation":0.5,"scale":[2,2]}}}}})";
// Material 1 (the rubber): an index of refraction, a specular colour texture (0) with an explicit
// texCoord 0, and a texture transform (texCoord 0) on its core normal texture.
const std::string kPatchRubber =
    R"({"extensions":{"KHR_materials_ior":{"ior":1.45},"KHR_materials_specular":{"specularFactor":0.5,)"
    R"("specularColorTexture":{"index":0,"texCoord":0}}},"normalTexture":{"extensions":{"KHR_texture_transform":)"
    R"({"offset":[0.5,0],"scale":[4,4],"texCoord":0}}}})";

// A patch that uses the corners of spec 18.2's grammar and still is well formed: whitespace of every
// kind, escapes (\u00e9, a surrogate pair, the short escapes, \u0000), raw UTF-8, a member name with
// an escape, numbers at the limits (1.7976931348623157e308 is finite, 1e-400 rounds to 0), nesting
// 32 deep, a core texture info for a slot without texture, texture references inside an array, with
// an escaped name, and inside another reference (document order is not breadth-first), and objects
// that are not texture references (a lower-case "texture", a "...Texture" without "index").
std::string syntax_patch() {
    std::string nested;
    for (int i = 0; i < 29; ++i) nested += "[";  // depth 4 .. 32 (spec 18.2 rule 7)
    nested += "1";
    for (int i = 0; i < 29; ++i) nested += "]";
    return std::string("{\r\n\t\"normalTexture\" : {\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,-0.25],"
                       "\"scale\":[4,4],\"texCoord\":0}}},\r\n") +
           "  \"occlusionTexture\":{\"extensions\":{}},\n"
           "  \"extensions\" : {\n"
           "    \"ELLICAST_vector_test\" : {\n"
           "      \"text\": \"caf\\u00e9 caf\\u00C9 caf\xC3\xA9 \\ud83d\\ude97 \xF0\x9F\x9A\x97 \\\"q\\\" \\\\ \\/ "
           "\\b\\f\\n\\r\\t \\u0000 \\u001f\",\n"
           "      \"caf\\u00e9\" : \"a member name with an escape\",\n"
           "      \"caf\xC3\xA9 2\" : true ,\n"
           "      \"numbers\": [0, -0, 1.5, -2.25e-3, 1E+2, 6.02e23, 1e-400, 1.7976931348623157e308, false, null],\n"
           "      \"empty\": [{}, [], \"\"],\n"
           "      \"nested\": " + nested + ",\n"
           "      \"layers\": [\n"
           "        {\"weight\": 0.5},\n"
           "        {\"colorTexture\": {\"index\": 2, \"texCoord\": 0, \"extensions\": {\"KHR_texture_transform\": "
           "{\"rotation\": 1.5707964}}}}\n"
           "      ],\n"
           "      \"layer\\u0054exture\": {\"index\": 0, \"extensions\": {\"ELLICAST_inner\": {\"innerTexture\": "
           "{\"index\": 1}}}},\n"
           "      \"lowercasetexture\": {\"index\": \"not a reference\"},\n"
           "      \"sourceTexture\": {\"source\": 7, \"texCoord\": 1},\n"
           "      \"note\": {\"texCoord\": 1}\n"
           "    }\n"
           "  }\n"
           "}\n";
}

SceneDescription extensions_scene() {
    SceneDescription s = make_scene();
    SceneDescription::Texture clearcoat;
    clearcoat.info.image_type = ImageType::Png;
    clearcoat.info.mag_filter = 9728;  // NEAREST
    clearcoat.image = make_png(10, 10, 43);
    s.textures.push_back(clearcoat);
    s.materials[0].extensions = kPatchPaint;
    s.materials[1].extensions = kPatchRubber;
    return s;
}

SceneStream make_extensions_stream(const SceneDescription& scene, uint16_t packet_size) {
    SceneStream s = make_scene_stream(scene, packet_size);
    if (!s.scene.extensions_too_large.empty()) {
        std::cerr << "make_vectors: a patch does not fit its packet\n";
        std::exit(1);
    }
    return s;
}

// `base` with `from` (which occurs exactly once) replaced by `to`: a patch with one defect.
std::string replaced(const std::string& base, const std::string& from, const std::string& to) {
    const size_t at = base.find(from);
    if (at == std::string::npos || base.find(from, at + 1) != std::string::npos) {
        std::cerr << "make_vectors: '" << from << "' is not in the patch exactly once\n";
        std::exit(1);
    }
    return base.substr(0, at) + to + base.substr(at + from.size());
}

std::vector<uint8_t> extensions_payload(uint16_t index, uint16_t count, const std::string& patch) {
    std::vector<uint8_t> p = {uint8_t(index), uint8_t(index >> 8), uint8_t(count), uint8_t(count >> 8)};
    p.insert(p.end(), patch.begin(), patch.end());
    return p;
}

// The position in `packets` of the packet of `type` whose payload starts with the u16 `index`.
size_t find_packet(const Packets& packets, PacketType type, uint16_t index) {
    for (size_t i = 0; i < packets.size(); ++i)
        if (packets[i][6] == uint8_t(type) && get16(packets[i], kHeaderSize) == index) return i;
    std::cerr << "make_vectors: no such packet\n";
    std::exit(1);
}

void extensions_vectors(Writer& w) {
    const SceneDescription scene = extensions_scene();
    const SceneStream base = make_extensions_stream(scene, 400);
    const Packets stream = base.all();
    const size_t H = kHeaderSize;
    const char* kCar =
        "the car of valid/scene_extensions (format 1.3: 2 materials with a MATERIAL_EXTENSIONS patch each, 3 "
        "textures, packet size 400)";
    w.write("valid", "scene_extensions",
            "format 1.3 (spec 18): the car at packet size 400 with a third texture (a 10 x 10 PNG clearcoat map, 378 "
            "bytes in 2 fragments) and each MATERIAL (flags bit 0 has_extensions set) followed by its "
            "MATERIAL_EXTENSIONS patch: the paint with KHR_materials_clearcoat (clearcoatTexture: texture 2), "
            "KHR_materials_emissive_strength and KHR_texture_transform on its core base colour texture; the rubber "
            "with KHR_materials_ior, KHR_materials_specular (specularColorTexture: texture 0, texCoord 0) and "
            "KHR_texture_transform (texCoord 0) on its core normal texture; every texture complete, every material "
            "shown with its patch",
            stream);

    // ---- unusual ----
    {
        Packets first, rest;
        for (const Packet& p : stream)
            (p[6] == uint8_t(PacketType::MaterialExtensions) ? first : rest).push_back(p);
        first.insert(first.end(), rest.begin(), rest.end());
        w.write("unusual", "scene_extensions_before_material",
                std::string(kCar) +
                    " with both MATERIAL_EXTENSIONS packets sent first, before the STREAM_INFO and their MATERIAL "
                    "packets: each patch is accepted and kept (its material_count fixes the table size the MATERIAL "
                    "packets are then checked against, spec 18.2) and applied once its material arrives (spec 18.4); "
                    "decodes to the scene of valid/scene_extensions",
                first);
    }
    {
        Packets sent = stream;
        Packet again = stream[find_packet(stream, PacketType::MaterialExtensions, 0)];
        sent.push_back(again);
        Packet renumbered = stream[find_packet(stream, PacketType::MaterialExtensions, 1)];
        restamp_packet(renumbered, 900);
        sent.push_back(renumbered);
        sent.push_back(again);
        w.write("unusual", "scene_extensions_repeated",
                std::string(kCar) +
                    " with material 0's patch sent twice more (byte-identical copies) and material 1's once more "
                    "with a new sequence number: the same bytes again are duplicates (spec 18.2); decodes to the "
                    "scene of valid/scene_extensions",
                sent);
    }
    {
        SceneDescription s = scene;
        s.materials[1].extensions = syntax_patch();
        const SceneStream t = make_extensions_stream(s, 1200);
        w.write("unusual", "scene_extensions_json_syntax",
                "the car of valid/scene_extensions at packet size 1200, material 1's patch replaced by one that uses "
                "the corners of spec 18.2's grammar and is well formed: CR LF, tabs and spaces around every token; "
                "escapes \\u00e9, \\u00C9, a surrogate pair (U+1F697), the short escapes and \\u0000, besides raw "
                "UTF-8; a member name written with an escape; numbers -0, 1E+2, 1.7976931348623157e308 (finite) and "
                "1e-400 (rounds to 0, finite); arrays nested to depth 32 (rule 7's limit); an occlusionTexture "
                "texture info for a slot the MATERIAL has no texture for (its extensions are left out, spec 18.4); "
                "texture references in document order (spec 18.3): layers/1/colorTexture (in an array: its position "
                "in the path), then layerTexture (its name written with \\u0054), then the innerTexture inside it "
                "(depth-first, not breadth-first); and objects that are not texture references (a lower-case "
                "'texture' member, a 'sourceTexture' without 'index', whose texCoord 1 is no texCoord of a "
                "reference); every texture complete, material 1 shown",
                t.all());
    }

    // ---- faulty: no rejection, but the stream does not conform (spec 18.4) ----
    {
        Packets sent = stream;
        // Texture 2's second fragment (the last packet of the stream).
        const size_t at = find_packet(sent, PacketType::TextureFragment, 2);
        sent.erase(sent.begin() + long(at) + 1);
        w.write("faulty", "scene_extensions_texture_incomplete",
                std::string(kCar) +
                    " without the second fragment of texture 2 (bytes 348..377 of 378): no rejection; material 0's "
                    "patch refers to texture 2 (extensions/KHR_materials_clearcoat/clearcoatTexture), so material 0 "
                    "is not shown and waits for it with that path as its slot (spec 18.4: 'a material whose patch has "
                    "arrived and refers to a texture that is not complete: the material is not shown'); material 1 "
                    "is shown",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(find_packet(sent, PacketType::MaterialExtensions, 0)));
        w.write("faulty", "scene_extensions_lost",
                std::string(kCar) +
                    " without material 0's MATERIAL_EXTENSIONS packet: no rejection; material 0's has_extensions bit "
                    "is set and its patch has not arrived, so it is not shown (waiting_extensions; spec 18.4: 'the "
                    "material is not shown, as if it had not arrived'); the stream is not complete (18.4)",
                sent);
    }
    {
        Packets sent = stream;
        Packet& m = sent[find_packet(sent, PacketType::Material, 1)];
        m[H + 7] = 0;
        reseal(m);
        w.write("faulty", "scene_extensions_without_flag",
                std::string(kCar) +
                    " with material 1's MATERIAL flags byte 0 (has_extensions not set, resealed) while its patch is "
                    "sent: no rejection; the patch is applied as if the bit were set (spec 18.4: 'a patch for a "
                    "material whose has_extensions bit is not set: the patch is applied as if the bit were set ... "
                    "(the stream does not conform)'); material 1 shown",
                sent);
    }
    {
        Packets sent = stream;
        const size_t at = find_packet(sent, PacketType::MaterialExtensions, 0);
        sent[at] = with_payload(sent[at], extensions_payload(0, 2, replaced(kPatchPaint, R"("index":2)", R"("index":65534)")));
        w.write("faulty", "scene_extensions_texture_past_table",
                std::string(kCar) +
                    " with material 0's clearcoatTexture index 65534 (the largest value spec 18.2 allows, resealed) in "
                    "a table of 3 textures: well formed, no rejection; material 0 waits for texture 65534, of which "
                    "nothing can arrive (spec 18.4: every texture reference must name a texture below texture_count "
                    "that is complete, else the stream does not conform)",
                sent);
    }

    // ---- faulty: rejections. Material 0's MATERIAL_EXTENSIONS packet replaced (same header, length and
    // checksum recomputed), or a packet added after the stream. Material 0 then waits for its patch. ----
    auto with_patch0_payload = [&](const std::vector<uint8_t>& payload) {
        Packets sent = stream;
        const size_t at = find_packet(sent, PacketType::MaterialExtensions, 0);
        sent[at] = with_payload(sent[at], payload);
        return sent;
    };
    auto bad = [&](const std::string& name, const std::string& what, const std::string& patch) {
        w.write("faulty", "scene_extensions_" + name,
                "material 0's MATERIAL_EXTENSIONS patch " + what +
                    " (resealed): rejected, malformed payload (spec 18.2); material 0's has_extensions bit is set and "
                    "its patch never arrives, so it waits for it (18.4)",
                with_patch0_payload(extensions_payload(0, 2, patch)));
    };
    const std::string P = kPatchPaint;
    {
        const std::string patch = "{";
        w.write("faulty", "scene_extensions_short",
                "material 0's MATERIAL_EXTENSIONS payload is 5 bytes: index, material_count and the patch '{' "
                "(resealed): rejected, malformed payload (spec 18.2 rule 1: 'shorter than 6 bytes'); material 0 "
                "waits for its patch",
                with_patch0_payload(extensions_payload(0, 2, patch)));
    }
    w.write("faulty", "scene_extensions_index_out_of_range",
            "material 0's MATERIAL_EXTENSIONS says index 2 in a table of 2 materials (resealed): rejected, malformed "
            "payload (spec 18.2 rule 1: 'index >= material_count'); material 0 waits for its patch",
            with_patch0_payload(extensions_payload(2, 2, P)));
    bad("not_utf8", "has the UTF-8 encoding of a surrogate (ED A0 80) in a member name (rule 2: not well-formed UTF-8)",
        replaced(P, "clearcoatRoughnessFactor", "clearcoat\xED\xA0\x80RoughnessFactor"));
    bad("byte_order_mark", "starts with a byte order mark EF BB BF (rule 2: 'a byte order mark counts as text, and is "
                           "not JSON')",
        "\xEF\xBB\xBF" + P);
    bad("second_value", "is followed by a second JSON value '{}' (rule 3: 'no second value after the first')", P + "{}");
    bad("trailing_garbage", "is followed by the bytes ' x' (rule 3: not one JSON text)", P + " x");
    bad("trailing_comma", "has a trailing comma in an object, '4.5,}' (rule 3: 'no trailing commas')",
        replaced(P, R"("emissiveStrength":4.5})", R"("emissiveStrength":4.5,})"));
    bad("nan", "has NaN as the clearcoatFactor (rule 3: 'no NaN or Infinity')",
        replaced(P, R"("clearcoatFactor":0.8)", R"("clearcoatFactor":NaN)"));
    bad("comment", "has a comment /* paint */ where whitespace may stand (rule 3: 'no comments')",
        replaced(P, R"({"extensions":{"KHR_materials_clearcoat")", R"({"extensions":/* paint */{"KHR_materials_clearcoat")"));
    bad("top_level_array", "is wrapped in an array, [{...}] (rule 3: 'its value is not an object')",
        "[" + P + "]");
    bad("control_character", "has an unescaped tab (09) inside a member name (rule 4: 'an unescaped character below "
                             "U+0020'; a tab is whitespace only between tokens)",
        replaced(P, "clearcoatFactor", "clearcoat\tFactor"));
    bad("lone_high_surrogate", "has the escape \\ud83d at the end of a member name, not followed by a low surrogate "
                               "escape (rule 4)",
        replaced(P, R"("clearcoatRoughnessFactor")", R"("clearcoatRoughnessFactor\ud83d")"));
    bad("lone_low_surrogate", "has the escape \\ude97 at the start of a member name, not preceded by a high surrogate "
                              "escape (rule 4)",
        replaced(P, R"("clearcoatRoughnessFactor")", R"("\ude97clearcoatRoughnessFactor")"));
    bad("number_infinite", "has the emissiveStrength 1e400, infinite once rounded to binary64 (rule 5)",
        replaced(P, "4.5", "1e400"));
    bad("duplicate_name", "has a second top-level member \"ext\\u0065nsions\", which is \"extensions\" once its escape is "
                          "decoded (rule 6: 'names compared after their escapes are decoded')",
        P.substr(0, P.size() - 1) + R"(,"ext\u0065nsions":{}})");
    {
        std::string nested;
        for (int i = 0; i < 30; ++i) nested += "[";
        nested += "1";
        for (int i = 0; i < 30; ++i) nested += "]";
        bad("depth_33", "has arrays nested 30 deep inside the clearcoat extension object, which is at depth 3: depth 33 "
                        "(rule 7: 'nest more than 32 deep')",
            replaced(P, R"("clearcoatFactor":0.8,)", R"("clearcoatFactor":0.8,"nested":)" + nested + ","));
    }
    bad("outside_shape", "has a top-level member \"extras\" (rule 8: 'at the top level, only the members extensions, "
                         "pbrMetallicRoughness, normalTexture, occlusionTexture, emissiveTexture')",
        P.substr(0, P.size() - 1) + R"(,"extras":{}})");
    bad("extension_not_object", "has the extension KHR_materials_emissive_strength as an array (rule 8: 'every member of "
                                "every extensions object ... has an object as its value')",
        replaced(P, R"({"emissiveStrength":4.5})", "[4.5]"));
    bad("index_leading_zero", "has the clearcoatTexture index 02 (rule 8: 'digits only, 0 or without leading zeros'; "
                              "RFC 8259's grammar, rule 3, refuses it too)",
        replaced(P, R"("index":2)", R"("index":02)"));
    bad("index_65535", "has the clearcoatTexture index 65535 (rule 8: 'of value at most 65534')",
        replaced(P, R"("index":2)", R"("index":65535)"));
    bad("index_fraction", "has the clearcoatTexture index 2.0 (rule 8: 'a number written with digits only')",
        replaced(P, R"("index":2)", R"("index":2.0)"));
    bad("index_exponent", "has the clearcoatTexture index 2e0 (rule 8: 'a number written with digits only')",
        replaced(P, R"("index":2)", R"("index":2e0)"));
    bad("texcoord_1", "has texCoord 1 on its clearcoatTexture reference (rule 8: 'a member texCoord of a texture "
                      "reference ... MUST be the number written 0')",
        replaced(P, R"({"index":2})", R"({"index":2,"texCoord":1})"));
    bad("transform_texcoord_1", "has texCoord 1 in the KHR_texture_transform of its base colour texture info (rule 8: "
                                "'a member texCoord of an object that is the value of a member named "
                                "KHR_texture_transform MUST be the number written 0')",
        replaced(P, R"("scale":[2,2]})", R"("scale":[2,2],"texCoord":1})"));
    w.write("faulty", "scene_extensions_count_contradicts",
            "material 0's MATERIAL_EXTENSIONS says material_count 3 where the MATERIAL packets say 2 (resealed): "
            "rejected, stream mismatch (spec 18.2: 'All MATERIAL and MATERIAL_EXTENSIONS packets of a stream carry "
            "the same material_count'); material 0 waits for its patch",
            with_patch0_payload(extensions_payload(0, 3, P)));
    {
        Packets sent = stream;
        Packet p = sent[find_packet(sent, PacketType::MaterialExtensions, 0)];
        p = with_payload(p, extensions_payload(0, 2, replaced(P, R"("clearcoatFactor":0.8)", R"("clearcoatFactor": 0.8)")));
        restamp_packet(p, 999);
        sent.push_back(p);
        w.write("faulty", "scene_extensions_contradicting_patch",
                std::string(kCar) +
                    ", then material 0's patch again with one space added after a colon (the same JSON value, other "
                    "bytes): rejected, stream mismatch (spec 18.2: 'a patch received twice is the same bytes; "
                    "otherwise stream mismatch'); the first patch stays",
                sent);
    }
    {
        Packets sent = stream;
        Packet p = sent[find_packet(sent, PacketType::Material, 0)];
        p[H + 7] = 0;
        reseal(p);
        restamp_packet(p, 999);
        sent.push_back(p);
        w.write("faulty", "scene_extensions_flag_contradicts",
                std::string(kCar) +
                    ", then material 0's MATERIAL again with flags bit 0 (has_extensions) cleared: rejected, stream "
                    "mismatch (spec 18.1: 'two records of one material that differ in it are a stream mismatch'); the "
                    "first material 0 stays",
                sent);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.3: the exact layer (CONNECTIVITY, spec 19). Three objects at packet size 256: a closed
// lumpy sphere (a twice subdivided octahedron: 66 points with normals, 128 triangles), a panel with a hole,
// a UV seam and a fin (56 points with normals and texture coordinates, 65 triangles), both with an
// exact layer, and a point set without one. The STREAM_INFO says 1.3 (its entries use flags bit 8),
// the ELLIPSOIDS and POINTS packets 1.0, the CONNECTIVITY packets 1.3.

// LZMA's binary range encoder (spec 19.3, 19.5), for coded connectivity no encoder would write (the
// unusable vectors): the library's encoder only codes real triangles.
class VectorRangeEncoder {
public:
    void bit(uint16_t& p, int b) {
        const uint32_t bound = (range_ >> 11) * p;
        if (b == 0) {
            range_ = bound;
            p = uint16_t(p + ((2048 - p) >> 5));
        } else {
            low_ += bound;
            range_ -= bound;
            p = uint16_t(p - (p >> 5));
        }
        normalize();
    }
    void direct(uint32_t value, int bits) {
        for (int k = bits - 1; k >= 0; --k) {
            range_ >>= 1;
            if ((value >> k) & 1) low_ += range_;
            normalize();
        }
    }
    std::vector<uint8_t> finish() {
        for (int i = 0; i < 5; ++i) shift_low();
        return out_;
    }

private:
    void normalize() {
        while (range_ < (1u << 24)) {
            range_ <<= 8;
            shift_low();
        }
    }
    void shift_low() {
        if (uint32_t(low_) < 0xFF000000u || (low_ >> 32) != 0) {
            uint8_t temp = cache_;
            do {
                out_.push_back(uint8_t(temp + uint8_t(low_ >> 32)));
                temp = 0xFF;
            } while (--cache_size_ != 0);
            cache_ = uint8_t(uint32_t(low_) >> 24);
        }
        ++cache_size_;
        low_ = uint64_t(uint32_t(low_) << 8);
    }
    uint64_t low_ = 0;
    uint32_t range_ = 0xFFFFFFFFu;
    uint8_t cache_ = 0;
    uint64_t cache_size_ = 1;
    std::vector<uint8_t> out_;
};

// Spec 19.2: w, the bits of n - 1 (at least 1).
int vector_index_bits(size_t n) {
    int w = 1;
    while ((uint64_t(1) << w) < n) ++w;
    return w;
}

// A mesh before it is sent: its points (float) and its triangles over them.
struct ExactMesh {
    std::vector<SurfacePoint> points;
    std::vector<Triangle> triangles;
};

// Renumbers the points in a seeded random order (Fisher-Yates), as an encoder that orders points for
// spreading (spec 7.2) would: point indices then say nothing about the triangles.
void shuffle_points(ExactMesh& m, Rng& rng) {
    std::vector<uint32_t> order(m.points.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
    std::vector<uint32_t> new_of(order.size());
    std::vector<SurfacePoint> points(order.size());
    for (uint32_t i = 0; i < order.size(); ++i) {
        points[i] = m.points[order[i]];
        new_of[order[i]] = i;
    }
    for (Triangle& t : m.triangles)
        for (uint32_t& v : t) v = new_of[v];
    m.points = std::move(points);
}

// A sphere of radius 0.8 around (0, 0, 0): an octahedron subdivided twice (66 vertices, 128
// triangles, wound outward), with normals; each vertex moved by up to 0.12 along each axis (about a third of an edge) (seeded), so
// that the parallelogram predictions miss and ranks beyond 2 occur. The surface-normals stream (format
// 1.8) subdivides it `levels` times with a smaller `jitter`.
ExactMesh exact_sphere(Rng& rng, int levels = 2, double jitter = 0.12) {
    std::vector<std::array<double, 3>> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<Triangle> t = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            std::array<double, 3> m;
            double len = 0;
            for (int k = 0; k < 3; ++k) {
                m[k] = v[a][k] + v[b][k];
                len += m[k] * m[k];
            }
            for (double& c : m) c /= std::sqrt(len);
            v.push_back(m);
            return mid[key] = uint32_t(v.size() - 1);
        };
        std::vector<Triangle> next;
        for (const Triangle& f : t) {
            const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({ab, f[1], bc});
            next.push_back({ca, bc, f[2]});
            next.push_back({ab, bc, ca});
        }
        t = std::move(next);
    }
    ExactMesh m;
    for (const auto& d : v) {
        SurfacePoint p;
        for (int k = 0; k < 3; ++k) {
            p.position[k] = float(0.8 * d[k] + rng.range(-jitter, jitter));
            p.normal[k] = float(d[k]);
        }
        m.points.push_back(p);
    }
    m.triangles = std::move(t);
    return m;
}

// A panel around (2, 0, -0.6): a 7 x 7 grid of spacing 0.25, gently bent, with normals and texture
// coordinates; a hole where its 4 middle quads are left out (its middle vertex, grid (3, 3), is a
// point no triangle uses); a UV seam along grid column 3, whose 6 used vertices are split (the quads
// right of it use copies with the same position and another texture coordinate), so that the panel
// is two pieces no edge joins; and a fin: one triangle from the bottom edge of quad (0, 0) up to a
// tip 1.5 above it. 56 points (49 + 6 copies + the tip), 65 triangles.
ExactMesh exact_panel() {
    ExactMesh m;
    auto grid = [](int i, int j, float u) {
        SurfacePoint p;
        p.position = {float(2 - 0.75 + 0.25 * i), float(-0.75 + 0.25 * j), float(-0.6 + 0.03 * std::sin(i) * std::cos(j))};
        p.normal = {0, 0, 1};
        p.texcoord = {u, float(j / 6.0)};
        return p;
    };
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 7; ++i) m.points.push_back(grid(i, j, i <= 3 ? float(i / 12.0) : float(0.5 + i / 12.0)));
    std::map<int, uint32_t> copy;  // grid row j -> the copy of vertex (3, j)
    for (int j = 0; j < 7; ++j) {
        if (j == 3) continue;
        copy[j] = uint32_t(m.points.size());
        m.points.push_back(grid(3, j, float(0.5 + 3 / 12.0)));
    }
    const uint32_t tip = uint32_t(m.points.size());
    SurfacePoint top = grid(0, 0, 0);
    top.position = {float(2 - 0.625), -0.75f, 0.9f};
    top.normal = {0, -1, 0};
    top.texcoord = {0.0f, 1.0f};
    m.points.push_back(top);
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) {
            if ((i == 2 || i == 3) && (j == 2 || j == 3)) continue;  // the hole
            // Right of the seam (i >= 3), column 3 is the copies.
            auto id = [&](int x, int y) { return x == 3 && i >= 3 ? copy.at(y) : uint32_t(y * 7 + x); };
            const uint32_t v00 = id(i, j), v10 = id(i + 1, j), v11 = id(i + 1, j + 1), v01 = id(i, j + 1);
            m.triangles.push_back({v00, v10, v11});
            m.triangles.push_back({v00, v11, v01});
        }
    m.triangles.push_back({1, 0, tip});  // the fin, beyond the edge 0 -> 1 of the first triangle
    return m;
}

struct ExactStream {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    std::vector<std::vector<uint8_t>> coded;  // per object (empty: none)
    std::vector<uint32_t> triangle_count;
    std::vector<std::vector<Triangle>> sent;  // what a decoder decodes
    Packets info_packets, ellipsoids, points;
    std::vector<Packets> connectivity;        // per object
    Packets all() const {
        Packets out = info_packets;
        out.insert(out.end(), ellipsoids.begin(), ellipsoids.end());
        out.insert(out.end(), points.begin(), points.end());
        for (const Packets& c : connectivity) out.insert(out.end(), c.begin(), c.end());
        return out;
    }
};

ExactStream exact_stream() {
    ExactStream s;
    s.info = default_info({make_object({-1, -1, -1}, 2, 8, 66, kAttrNormal),
                           make_object({1, -1, -1}, 2, 8, 56, kAttrNormal | kAttrTexcoord),
                           make_object({-1, 2, -1}, 1, 0, 20, kAttrColor, ObjectKind::PointSet)},
                          256);
    s.info.objects[0].exact_layer = true;
    s.info.objects[1].exact_layer = true;
    Rng rng(70);
    std::vector<ExactMesh> meshes = {exact_sphere(rng), exact_panel()};
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        const ObjectInfo& o = s.info.objects[i];
        // Ellipsoids (and, for the point set, its points) as the other vectors make them.
        ObjectContent c = make_content(s.info, o, rng);
        s.coded.emplace_back();
        s.triangle_count.push_back(0);
        s.sent.emplace_back();
        if (i < meshes.size()) {
            ExactMesh& m = meshes[i];
            shuffle_points(m, rng);
            if (m.points.size() != o.point_count) {
                std::cerr << "make_vectors: exact mesh " << i << " has " << m.points.size() << " points\n";
                std::exit(1);
            }
            c.points.clear();
            std::vector<std::array<uint32_t, 3>> positions;
            for (const SurfacePoint& p : m.points) {
                c.points.push_back(quantize_point(p, s.info, o));
                positions.push_back(c.points.back().position);
            }
            if (encode_connectivity(positions, m.triangles, s.coded[i], s.sent[i]) != Error::Ok) {
                std::cerr << "make_vectors: encode_connectivity failed\n";
                std::exit(1);
            }
            s.triangle_count[i] = uint32_t(m.triangles.size());
        }
        s.contents.push_back(std::move(c));
    }
    StreamPackets packets;
    if (packetize_stream(s.info, s.contents, kStreamId, packets) != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed\n";
        std::exit(1);
    }
    mark_version_1_0(packets);
    for (Packet& p : packets.stream_info) {
        p[5] = 3;  // its entries use flags bit 8 (format 1.3)
        reseal(p);
    }
    s.info_packets = packets.stream_info;
    s.ellipsoids = packets.ellipsoids;
    s.points = packets.points;
    uint32_t sequence = uint32_t(s.info_packets.size() + s.ellipsoids.size() + s.points.size());
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        Packets out;
        if (!s.coded[i].empty() &&
            packetize_connectivity(s.info, uint16_t(i), s.triangle_count[i], s.coded[i], kStreamId, sequence, out) != Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity failed\n";
            std::exit(1);
        }
        sequence += uint32_t(out.size());
        s.connectivity.push_back(out);
    }
    return s;
}

// A CONNECTIVITY packet as given (the faulty vectors need pieces no packetizer cuts).
Packet connectivity_packet(uint16_t object, uint32_t sequence, uint32_t triangle_count, uint32_t coded_size,
                           uint32_t coded_crc, uint32_t offset, std::vector<uint8_t> data) {
    ConnectivityPiece piece;
    piece.triangle_count = triangle_count;
    piece.coded_size = coded_size;
    piece.coded_crc = coded_crc;
    piece.offset = offset;
    piece.data = std::move(data);
    PacketHeader h;
    h.version_minor = kConnectivityMinor;
    h.type = uint8_t(PacketType::Connectivity);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = object;
    return write_packet(h, encode_connectivity_payload(piece));
}

// Offsets in a CONNECTIVITY packet (header included), spec 19.1.
constexpr size_t kConnTriangles = kHeaderSize, kConnSize = kHeaderSize + 4, kConnCrc = kHeaderSize + 8,
                 kConnOffset = kHeaderSize + 12, kConnData = kHeaderSize + 16;

void exact_vectors(Writer& w) {
    const ExactStream s = exact_stream();
    const Packets good = s.all();
    const std::string kExact =
        "the exact-layer stream of valid/exact (a lumpy sphere of 66 points and 128 triangles, a panel of 56 points and 65 "
        "triangles with a hole, a UV seam and a fin, both with an exact layer, and a point set)";
    w.write("valid", "exact",
            "format 1.3, the exact layer (spec 19): three objects at packet size 256: a closed lumpy sphere (an "
            "octahedron subdivided twice, its vertices jittered: 66 points with normals, 128 triangles; decoded with "
            "one seed and ranks 1, 2, 3, 5 and 7), a panel (a 7 x 7 grid with a hole of 4 quads whose middle vertex no "
            "triangle uses, a UV seam whose 6 split vertices cut it into two pieces no edge joins, and a fin whose tip "
            "is no candidate; 56 points with normals and texture coordinates, 65 triangles; decoded with two seeds, "
            "39 none bits, one explicit index, and ties between seam copies broken by index), both announcing an exact "
            "layer (entry flags bit 8) and sent with one CONNECTIVITY packet each after the points, and a point set "
            "without one; points in a shuffled order; every object exact",
            good);

    // Where object 0's CONNECTIVITY packet is in `good`.
    const size_t conn0 = s.info_packets.size() + s.ellipsoids.size() + s.points.size();
    {
        // The versions the reference packetizer writes (spec 9.1): STREAM_INFO, ELLIPSOIDS and POINTS say
        // 1.1, CONNECTIVITY 1.3. Flags bit 8 is read from a STREAM_INFO of any minor version (spec 5.2).
        Packets file = good;
        for (size_t i = 0; i < conn0; ++i) {
            file[i][5] = 1;
            reseal(file[i]);
        }
        w.write("valid", "exact_info_1_1",
                std::string(kExact) + ", with its STREAM_INFO, ELLIPSOIDS and POINTS packets saying 1.1 and its "
                "CONNECTIVITY packets 1.3, as the reference packetizer writes them (spec 9.1): flags bit 8 (the exact "
                "layer) is read from a STREAM_INFO packet whatever minor version it says, 1.0 to 1.2 included (spec "
                "5.2, 9), so objects 0 and 1 announce an exact layer, take their CONNECTIVITY packets and are exact; "
                "decodes as valid/exact",
                file);
    }
    if (s.connectivity[0].size() != 1 || s.connectivity[1].size() != 1) {
        std::cerr << "make_vectors: the exact objects should fit one CONNECTIVITY packet each\n";
        std::exit(1);
    }
    const std::vector<uint8_t>& coded0 = s.coded[0];
    const uint32_t size0 = uint32_t(coded0.size()), crc0 = crc32c(coded0.data(), coded0.size());
    {
        // Object 0's coded connectivity cut into pieces of 4 bytes, in an order no sender uses: the last
        // piece, a piece over bytes 2..5 (overlapping pieces 0 and 1), the middle pieces backwards,
        // piece 0, piece 0 again (a byte-identical duplicate), piece 1 (completes it), piece 2 again with
        // a new sequence number (a duplicate of a complete connectivity). Object 1's packet comes before
        // the points (the connectivity complete before every point is held).
        const size_t k = (coded0.size() + 3) / 4;
        if (k < 4) {
            std::cerr << "make_vectors: object 0's coded connectivity is too short to cut (" << coded0.size() << ")\n";
            std::exit(1);
        }
        auto piece = [&](uint32_t from, uint32_t to, uint32_t sequence) {
            to = std::min<uint32_t>(to, size0);
            return connectivity_packet(0, sequence, s.triangle_count[0], size0, crc0, from,
                                       std::vector<uint8_t>(coded0.begin() + from, coded0.begin() + to));
        };
        Packets file = s.info_packets;
        file.insert(file.end(), s.ellipsoids.begin(), s.ellipsoids.end());
        file.insert(file.end(), s.connectivity[1].begin(), s.connectivity[1].end());
        file.insert(file.end(), s.points.begin(), s.points.end());
        uint32_t seq = 100;
        file.push_back(piece(uint32_t(4 * (k - 1)), size0, seq++));
        file.push_back(piece(2, 6, seq++));
        for (size_t i = k - 2; i >= 2; --i) file.push_back(piece(uint32_t(4 * i), uint32_t(4 * i + 4), seq++));
        file.push_back(piece(0, 4, seq));
        file.push_back(piece(0, 4, seq++));
        file.push_back(piece(4, 8, seq++));
        file.push_back(piece(8, 12, seq++));
        w.write("unusual", "exact_pieces",
                std::string(kExact) + ", with object 0's coded connectivity (" + std::to_string(size0) +
                    " bytes) cut into pieces of 4 bytes (spec 19.1: any cut), sent out of order: the last piece, a "
                    "piece of bytes 2..5 overlapping pieces 0 and 1, the middle pieces backwards, piece 0 (accepted: "
                    "bytes 0..1 are new), piece 0 again (a duplicate), piece 1 (accepted: bytes 6..7 complete it), "
                    "piece 2 again with a new sequence number (a duplicate); object 1's CONNECTIVITY packet before its "
                    "points (decoded once every point is held); every object exact",
                file);
    }
    {
        Packets file = s.connectivity[1];
        file.insert(file.end(), s.connectivity[0].begin(), s.connectivity[0].end());
        const Packets rest = {good.begin(), good.begin() + long(conn0)};
        file.insert(file.end(), rest.begin(), rest.end());
        w.write("unusual", "exact_before_stream_info",
                std::string(kExact) + ", with both CONNECTIVITY packets (object 1's first) before the STREAM_INFO: "
                "held like POINTS packets (spec 19, 11.2), released in arrival order when the STREAM_INFO arrives "
                "and accepted; every object exact",
                file);
    }
    {
        Packets file = good;
        Packet& info = file[0];
        put16(info, kHeaderSize + 32 + 2 * 44 + 26, kEntryExactLayer);
        reseal(info);
        w.write("unusual", "exact_point_set_flag",
                std::string(kExact) + ", with flags bit 8 set in the point set's entry (object 2): the bit means "
                "nothing for a point set (spec 19); no exact layer is awaited for it and it has no CONNECTIVITY packet",
                file);
    }

    // Faulty: the stream of valid/exact with one defect.
    // A copy of object 0's CONNECTIVITY packet with `edit` applied, numbered 1000 and resealed.
    auto defective = [&](const std::function<void(Packet&)>& edit) {
        Packet p = good[conn0];
        put32(p, 12, 1000);
        edit(p);
        reseal(p);
        return p;
    };
    struct ExactEdit {
        const char* name;
        const char* description;
        std::function<void(Packet&)> edit;
        bool first;  // before the STREAM_INFO (else after the stream)
    };
    const uint32_t n0 = s.info.objects[0].point_count;
    const std::vector<ExactEdit> edits = {
        {"exact_no_data",
         "a CONNECTIVITY packet of object 0 with its 16-byte description and no data byte, before the STREAM_INFO: "
         "held (its checks need the object's entry, spec 11.1), then rejected when released (malformed payload, "
         "spec 19.1: no data byte)",
         [](Packet& p) { p = with_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kConnData)); },
         true},
        {"exact_payload_short",
         "a CONNECTIVITY packet of object 0 cut to a payload of 15 bytes (shorter than its 16 bytes of fixed fields: "
         "no offset, no data byte), before the STREAM_INFO: held (its checks need the object's entry, spec 11.1), then "
         "rejected when released (malformed payload, spec 19.1: shorter than 16 bytes)",
         [](Packet& p) { p = with_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kConnData - 1)); },
         true},
        {"exact_piece_past_end",
         "after the stream, a CONNECTIVITY packet of object 0 whose piece (all the coded bytes) starts at offset 1: "
         "offset + data length = coded_size + 1 (malformed payload, spec 19.1)",
         [](Packet& p) { put32(p, kConnOffset, 1); }, false},
        {"exact_triangle_count_zero",
         "after the stream, a CONNECTIVITY packet of object 0 with triangle_count 0 (malformed payload, spec 19.1)",
         [](Packet& p) { put32(p, kConnTriangles, 0); }, false},
        {"exact_too_many_triangles",
         "after the stream, a CONNECTIVITY packet of object 0 with triangle_count 529 = 8 x 66 + 1, more than 8 "
         "times the object's point_count (malformed payload, spec 19.1; 528 would pass)",
         [n0](Packet& p) { put32(p, kConnTriangles, 8 * n0 + 1); }, false},
        {"exact_coded_size_too_large",
         "after the stream, a CONNECTIVITY packet of object 0 with coded_size 2113 = 16 x 128 + 64 + 1 (malformed "
         "payload, spec 19.1; 2112 would pass)",
         [](Packet& p) { put32(p, kConnSize, 16 * get32(p, kConnTriangles) + 65); }, false},
        {"exact_point_set",
         "after the stream, object 0's CONNECTIVITY packet sent for object 2, a point set (malformed payload, spec "
         "19.1)",
         [](Packet& p) { put16(p, 16, 2); }, false},
        {"exact_unknown_object",
         "after the stream, object 0's CONNECTIVITY packet sent for object 3 of 3 (unknown object, spec 11.1 step 12)",
         [](Packet& p) { put16(p, 16, 3); }, false},
        {"exact_triangle_count_contradicts",
         "after the stream, object 0's CONNECTIVITY packet again with triangle_count 129 where the first said 128 "
         "(stream mismatch, spec 19.1), even though the connectivity is complete",
         [](Packet& p) { put32(p, kConnTriangles, get32(p, kConnTriangles) + 1); }, false},
        {"exact_coded_size_contradicts",
         "after the stream, object 0's CONNECTIVITY packet again with coded_size one more than the first said "
         "(stream mismatch, spec 19.1)",
         [](Packet& p) { put32(p, kConnSize, get32(p, kConnSize) + 1); }, false},
        {"exact_crc_contradicts",
         "after the stream, object 0's CONNECTIVITY packet again with another coded_crc (stream mismatch, spec 19.1)",
         [](Packet& p) { put32(p, kConnCrc, get32(p, kConnCrc) ^ 0x00010000u); }, false},
    };
    for (const ExactEdit& e : edits) {
        Packets file = good;
        const Packet bad = defective(e.edit);
        if (e.first) file.insert(file.begin(), bad);
        else file.push_back(bad);
        w.write("faulty", e.name, e.description, file);
    }
    {
        Packets file = good;
        file[conn0][kConnData + 3] ^= 0x20;
        reseal(file[conn0]);
        w.write("faulty", "exact_crc_wrong",
                std::string(kExact) + ", with one byte of object 0's coded connectivity changed (resealed): every "
                "byte arrives but its CRC-32C does not match coded_crc: the packet that completed it is rejected "
                "(stream mismatch) and the bytes discarded (spec 19.1); object 0 is not exact",
                file);
    }
    {
        // Spec 19.1: the connectivity's description outlives a CRC discard. After exact_crc_wrong, the
        // intact packet again is accepted and completes it; a packet whose coded_crc is that of the
        // changed bytes (and whose bytes match it) contradicts the kept description.
        Packets wrong = good;
        wrong[conn0][kConnData + 3] ^= 0x20;
        reseal(wrong[conn0]);
        Packets resent = wrong;
        Packet intact = good[conn0];
        put32(intact, 12, 1000);
        reseal(intact);
        resent.push_back(intact);
        w.write("faulty", "exact_crc_wrong_resent",
                std::string(kExact) + ", with one byte of object 0's coded connectivity changed in its only "
                "CONNECTIVITY packet (resealed), as in faulty/exact_crc_wrong, then (sequence 1000, after the stream) "
                "the intact packet: the first is rejected (stream mismatch) and the bytes discarded, the description "
                "kept (spec 19.1); the intact packet agrees with it, brings every byte anew and is accepted, the CRC-32C "
                "matches: object 0 is exact",
                resent);
        Packets other = wrong;
        Packet changed_crc = wrong[conn0];
        put32(changed_crc, 12, 1000);
        std::vector<uint8_t> bytes(changed_crc.begin() + kConnData, changed_crc.end() - kChecksumSize);
        put32(changed_crc, kConnCrc, crc32c(bytes.data(), bytes.size()));
        reseal(changed_crc);
        other.push_back(changed_crc);
        w.write("faulty", "exact_crc_wrong_description_kept",
                std::string(kExact) + ", with one byte of object 0's coded connectivity changed in its only "
                "CONNECTIVITY packet (resealed), as in faulty/exact_crc_wrong, then (sequence 1000, after the stream) "
                "the same changed bytes with coded_crc their CRC-32C: the first is rejected (stream mismatch) and its "
                "bytes discarded, but the description it set is kept (spec 19.1), so the second, whose coded_crc "
                "differs from it, is rejected too (stream mismatch) and brings nothing; object 0 is not exact",
                other);
    }
    {
        // Spec 3.1, 11.5: a skippable type written with bit 0 clear. A decoder that knows CONNECTIVITY
        // reads it all the same; one that does not would reject it: the file does not conform.
        Packets file = good;
        file[conn0][7] &= uint8_t(~kFlagSkippable);
        reseal(file[conn0]);
        w.write("faulty", "exact_marked_critical",
                std::string(kExact) + ", with object 0's CONNECTIVITY packet's flags bit 0 cleared (resealed): a "
                "decoder that knows the type decodes it as in valid/exact, both objects exact, nothing rejected; the "
                "file does not conform (spec 3.1: a skippable type's packets carry bit 0 set; a 1.2 decoder would "
                "reject this one as an unknown critical type)",
                file);
    }
    // Coded connectivity no encoder writes, with a matching CRC: unusable when decoded (spec 19.2).
    auto replaced_connectivity = [&](const std::vector<uint8_t>& coded) {
        Packets file = good;
        file[conn0] = connectivity_packet(0, get32(good[conn0], 12), s.triangle_count[0], uint32_t(coded.size()),
                                          crc32c(coded.data(), coded.size()), 0, coded);
        return file;
    };
    const int w0 = vector_index_bits(n0);
    {
        // The first seed of the real stream, then at its first gate: not none, no rank of 1..16, and the
        // explicit index n (w = 7 bits hold it).
        VectorRangeEncoder rc;
        for (uint32_t v : s.sent[0][0]) rc.direct(v, w0);
        uint16_t none = 1024;
        std::array<uint16_t, 16> rank;
        rank.fill(1024);
        rc.bit(none, 0);
        for (uint16_t& p : rank) rc.bit(p, 0);
        rc.direct(n0, w0);
        w.write("faulty", "exact_unusable_index",
                std::string(kExact) + ", with object 0's coded connectivity replaced by one with a matching CRC whose "
                "first gate escapes to the explicit index 66, not below the object's 66 points: no rejection (every "
                "packet is well formed), but the connectivity is unusable (spec 19.2 step 4): object 0 is not exact "
                "and the recording does not conform (spec 19.4: 'decodes to triangle_count triangles without being "
                "unusable'); a validator reports it",
                replaced_connectivity(rc.finish()));
    }
    {
        VectorRangeEncoder rc;
        for (uint32_t v : {5u, 5u, 9u}) rc.direct(v, w0);
        w.write("faulty", "exact_unusable_seed",
                std::string(kExact) + ", with object 0's coded connectivity replaced by one with a matching CRC whose "
                "seed names points 5, 5, 9 (two equal): no rejection, but the connectivity is unusable (spec 19.2 "
                "step 1): object 0 is not exact and the recording does not conform (spec 19.4); a validator reports it",
                replaced_connectivity(rc.finish()));
    }
    {
        Packets file = good;
        const size_t conn1 = conn0 + s.connectivity[0].size();
        file.erase(file.begin() + long(conn1), file.begin() + long(conn1 + s.connectivity[1].size()));
        w.write("faulty", "exact_layer_lost",
                std::string(kExact) + ", with object 1's CONNECTIVITY packet lost: no rejection; its entry announces an "
                "exact layer that never arrives: object 1 is not exact and the stream is not complete (spec 19.4); a "
                "validator reports it",
                file);
    }
    {
        // Spec 19: from format 1.3 on, bit 8 of an entry's flags is compared (5.4); its other bits, and
        // the bit in a point set's entry, are not.
        Packet again = good[0];
        put32(again, 12, 1000);
        put16(again, kHeaderSize + 32 + 0 * 44 + 26, 0xBFEF);
        put16(again, kHeaderSize + 32 + 1 * 44 + 26, 0x0101);
        put16(again, kHeaderSize + 32 + 2 * 44 + 26, 0x0100);
        reseal(again);
        Packets file = good;
        file.push_back(again);
        w.write("unusual", "exact_flags_uncompared",
                std::string(kExact) + ", then the STREAM_INFO again (sequence 1000, resealed) with the entries' flags "
                "BFEF, 0101 and 0100 where the first said 0100, 0100 and 0: bit 8 is the same for both surface objects "
                "and means nothing for the point set, the other bits are reserved: a duplicate (spec 5.4, 19)",
                file);
        Packet contradicting = good[0];
        put32(contradicting, 12, 1000);
        put16(contradicting, kHeaderSize + 32 + 0 * 44 + 26, 0);
        reseal(contradicting);
        file = good;
        file.push_back(contradicting);
        w.write("faulty", "exact_flag_contradicts",
                std::string(kExact) + ", then the STREAM_INFO again (sequence 1000, resealed) with flags bit 8 cleared "
                "in object 0's entry: rejected, stream mismatch (spec 19: 'From format 1.3 on, it is one of the fields "
                "section 5.4 compares'); the first entry stays",
                file);
    }
    {
        Packets file = good;
        put16(file[0], kHeaderSize + 32 + 0 * 44 + 26, 0);
        reseal(file[0]);
        w.write("faulty", "exact_without_flag",
                std::string(kExact) + ", with flags bit 8 cleared in object 0's entry (resealed) while its "
                "CONNECTIVITY packet is sent: no rejection; the connectivity is taken and decodes, but a recording "
                "with CONNECTIVITY packets for an object whose entry does not announce an exact layer does not "
                "conform (spec 19.4); a validator reports it",
                file);
    }
    {
        // Object 0's last POINTS packet without its last point (point 65).
        Packets file = good;
        size_t last = 0;
        uint32_t last_first = 0;
        for (size_t i = 0; i < file.size(); ++i) {
            PacketView v;
            if (parse_packet(file[i], v) != Error::Ok || v.header.type != uint8_t(PacketType::Points) || v.header.object_id != 0)
                continue;
            const uint32_t first = get32(file[i], kHeaderSize);
            if (last == 0 || first >= last_first) {
                last = i;
                last_first = first;
            }
        }
        PacketView v;
        parse_packet(file[last], v);
        PointBatch batch;
        batch.first_index = last_first;
        batch.points.assign(s.contents[0].points.begin() + last_first, s.contents[0].points.end() - 1);
        file[last] = write_packet(v.header, encode_points_payload(batch, s.info, s.info.objects[0]));
        w.write("faulty", "exact_point_missing",
                std::string(kExact) + ", with object 0's last POINTS packet one point short (point 65 never sent): no "
                "rejection; object 0's connectivity is complete but it is not decoded (spec 19.2: the candidates are "
                "points): the object is shown progressive (spec 19.4); the recording does not conform (spec 11.5: every "
                "element present); a validator reports it",
                file);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.3: repair packets for the exact layer (CONNECTIVITY_REPAIR, spec 19.5), over the stream of
// valid/exact. Object 0's coded connectivity (34 bytes) is cut into symbols of L = 8 bytes: k = 5
// source symbols (the last one 2 bytes and 6 padding zeros), repair rows 5 .. 254; its CONNECTIVITY
// pieces are those symbols (pieces 0..4), except where a vector says otherwise. Object 1's repair
// packets are those of the reference packetizer (L = the piece size of its CONNECTIVITY packets, 216
// bytes: k = 1).

constexpr size_t kRepL = 8;
constexpr size_t kCRepTriangles = kHeaderSize, kCRepSize = kHeaderSize + 4, kCRepCrc = kHeaderSize + 8,
                 kCRepSymbolSize = kHeaderSize + 12, kCRepRow = kHeaderSize + 14, kCRepReserved = kHeaderSize + 15,
                 kCRepSymbol = kHeaderSize + 16;

// The source symbols of spec 19.5: `coded` cut into `size`-byte symbols, the last padded with zeros.
std::vector<std::vector<uint8_t>> vector_connectivity_symbols(const std::vector<uint8_t>& coded, size_t size) {
    std::vector<std::vector<uint8_t>> out;
    for (size_t at = 0; at < coded.size(); at += size) {
        std::vector<uint8_t> s(coded.begin() + long(at), coded.begin() + long(std::min(coded.size(), at + size)));
        s.resize(size, 0);
        out.push_back(std::move(s));
    }
    return out;
}

// A CONNECTIVITY_REPAIR packet as given.
Packet connectivity_repair_packet(uint16_t object, uint32_t sequence, uint32_t triangle_count, uint32_t coded_size,
                                  uint32_t coded_crc, uint16_t symbol_size, uint8_t row, std::vector<uint8_t> symbol) {
    ConnectivityRepair r;
    r.triangle_count = triangle_count;
    r.coded_size = coded_size;
    r.coded_crc = coded_crc;
    r.symbol_size = symbol_size;
    r.row = row;
    r.symbol = std::move(symbol);
    PacketHeader h;
    h.version_minor = kConnectivityMinor;
    h.type = uint8_t(PacketType::ConnectivityRepair);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = object;
    return write_packet(h, encode_connectivity_repair_payload(r));
}

void exact_repair_vectors(Writer& w) {
    const ExactStream s = exact_stream();
    const Packets good = s.all();
    const size_t conn0 = s.info_packets.size() + s.ellipsoids.size() + s.points.size();
    const std::vector<uint8_t>& coded0 = s.coded[0];
    const uint32_t tc0 = s.triangle_count[0], size0 = uint32_t(coded0.size()), crc0 = crc32c(coded0.data(), coded0.size());
    const auto sources0 = vector_connectivity_symbols(coded0, kRepL);
    const size_t k0 = sources0.size();
    if (k0 != 5) {
        std::cerr << "make_vectors: object 0's coded connectivity should make 5 symbols of 8 bytes, not " << k0 << "\n";
        std::exit(1);
    }
    const uint32_t first_seq = get32(good[conn0], 12);
    // Object 0's bytes [from, to) as one CONNECTIVITY piece.
    auto piece = [&](uint32_t from, uint32_t to, uint32_t sequence) {
        to = std::min(to, size0);
        return connectivity_packet(0, sequence, tc0, size0, crc0, from,
                                   std::vector<uint8_t>(coded0.begin() + from, coded0.begin() + to));
    };
    auto sym = [&](size_t j, uint32_t sequence) { return piece(uint32_t(j * kRepL), uint32_t((j + 1) * kRepL), sequence); };
    auto row = [&](unsigned r, uint32_t sequence) {
        return connectivity_repair_packet(0, sequence, tc0, size0, crc0, uint16_t(kRepL), uint8_t(r),
                                          repair_symbol(sources0, r));
    };
    // Object 1's repair packets from the reference packetizer (k = 1: one row, row 1).
    Packets repairs1;
    if (packetize_connectivity_repairs(s.info, 1, s.triangle_count[1], s.coded[1], 1, kStreamId, 0, repairs1) != Error::Ok ||
        repairs1.size() != 1) {
        std::cerr << "make_vectors: packetize_connectivity_repairs failed\n";
        std::exit(1);
    }
    auto numbered_as = [](Packet p, uint32_t sequence) {
        put32(p, 12, sequence);
        reseal(p);
        return p;
    };
    const Packets head = {good.begin(), good.begin() + long(conn0)};  // STREAM_INFO, ELLIPSOIDS, POINTS
    const Packet conn1 = good[conn0 + 1];

    // The valid stream: sent piece 0, row 5, piece 1, row 6, piece 2, row 7, piece 3, piece 4, object
    // 1's CONNECTIVITY packet, its row 1 (sequence numbers counting transmissions); piece 1, row 6,
    // piece 3 and object 1's CONNECTIVITY packet lost.
    Packets tail0;
    {
        uint32_t q = first_seq;
        tail0.push_back(sym(0, q++));
        tail0.push_back(row(5, q++));
        ++q;  // piece 1 lost
        ++q;  // row 6 lost
        tail0.push_back(sym(2, q++));
        tail0.push_back(row(7, q++));
        ++q;  // piece 3 lost
        tail0.push_back(sym(4, q++));
        ++q;  // object 1's CONNECTIVITY packet lost
        tail0.push_back(numbered_as(repairs1[0], q++));
    }
    Packets valid = head;
    valid.insert(valid.end(), tail0.begin(), tail0.end());
    const std::string kRepairStream =
        "the exact-layer stream of valid/exact_repair (object 0's 34 coded bytes as 5 pieces of 8 bytes with rows 5 and "
        "7 at L = 8, pieces 1 and 3 lost, recovered when piece 4 arrives; object 1's CONNECTIVITY packet lost and "
        "recovered from its one repair row)";
    w.write("valid", "exact_repair",
            "format 1.3, repair packets for the exact layer (spec 19.5): the exact-layer stream of valid/exact, with "
            "object 0's coded connectivity (34 bytes) sent as 5 CONNECTIVITY pieces of 8 bytes interleaved with "
            "CONNECTIVITY_REPAIR rows 5, 6, 7 at L = 8 (k = 5), and object 1's with its one repair row as the reference "
            "encoder makes it (L = 216, k = 1, row 1); pieces 1 and 3, row 6 and object 1's CONNECTIVITY packet lost: "
            "object 0 holds source symbols 0, 2 and rows 5, 7 when piece 4 arrives and solves for symbols 1 and 3; "
            "object 1 is recovered from row 1 alone; both recovered and exact",
            valid);

    // Unusual.
    {
        // Repair symbols alone: rows 254, 5, 100, 6 and 7 (the fifth completes it), then row 8 (a
        // duplicate: complete); object 1 as in valid/exact.
        Packets file = head;
        uint32_t q = 100;
        for (unsigned r : {254u, 5u, 100u, 6u, 7u, 8u}) file.push_back(row(r, q++));
        file.push_back(conn1);
        w.write("unusual", "exact_repair_only",
                "the exact-layer stream of valid/exact with object 0's coded connectivity sent only as "
                "CONNECTIVITY_REPAIR packets (L = 8, k = 5, no CONNECTIVITY piece at all): rows 254, 5, 100, 6, 7 "
                "(the first repair packet starts the object's connectivity; the fifth row completes it: 5 unknown "
                "symbols solved from 5 rows, spec 19.5), then row 8 (a duplicate: complete); every object exact, "
                "object 0 recovered",
                file);
    }
    {
        // Pieces at offsets that are no symbol boundary: bytes 3..12, 13..26, 30..33 hold symbols 1, 2
        // and 4 (symbol 0 lacks bytes 0..2, symbol 3 bytes 27..29); rows 5, 6 then complete it; then
        // bytes 0..2 (a duplicate: complete).
        Packets file = head;
        uint32_t q = 100;
        file.push_back(piece(3, 13, q++));
        file.push_back(piece(13, 27, q++));
        file.push_back(piece(30, 34, q++));
        file.push_back(row(5, q++));
        file.push_back(row(6, q++));
        file.push_back(piece(0, 3, q++));
        file.push_back(conn1);
        w.write("unusual", "exact_repair_odd_pieces",
                "the exact-layer stream of valid/exact with object 0's coded connectivity in CONNECTIVITY pieces that "
                "do not follow the symbols (L = 8, k = 5): bytes 3..12, 13..26 and 30..33, so that source symbols 1, 2 "
                "and 4 are held (symbol 4 has only bytes 32..33 inside coded_size) and symbols 0 and 3 are not (bytes "
                "0..2 and 27..29 missing), then rows 5 and 6: the second row completes it (spec 19.5: a symbol is held "
                "when its bytes have arrived, whatever the pieces' offsets); then bytes 0..2 (a duplicate: complete); "
                "every object exact, object 0 recovered",
                file);
    }
    {
        Packets file = head;
        uint32_t q = 100;
        file.push_back(sym(0, q++));
        const Packet r5 = row(5, q++);
        file.push_back(r5);
        file.push_back(r5);
        file.push_back(row(5, q++));
        file.push_back(sym(2, q++));
        file.push_back(sym(4, q++));
        file.push_back(row(6, q++));
        file.push_back(row(7, q++));
        file.push_back(sym(1, q++));
        file.push_back(row(5, q++));
        file.push_back(conn1);
        w.write("unusual", "exact_repair_duplicates",
                "the exact-layer stream of valid/exact with object 0's coded connectivity (L = 8, k = 5) as piece 0, "
                "row 5, row 5 again (byte-identical: a duplicate), row 5 with a new sequence number (a duplicate: a "
                "row held, spec 19.5), pieces 2 and 4, row 6 (completes it: 3 symbols and 2 rows held), then more "
                "than it needs: row 7, piece 1 and row 5 again (duplicates: complete); every object exact, object 0 "
                "recovered",
                file);
    }
    {
        Packets file = head;
        Packets tail = tail0;
        tail[1][kCRepReserved] = 0xA5;
        reseal(tail[1]);
        file.insert(file.end(), tail.begin(), tail.end());
        w.write("unusual", "exact_repair_reserved",
                std::string(kRepairStream) + ", with the reserved byte of object 0's row 5 set to A5 (resealed): "
                "ignored when reading (spec 19.5); decodes as valid/exact_repair",
                file);
    }
    {
        Packets file = {tail0[1], tail0[3]};  // rows 5 and 7, before the STREAM_INFO
        file.insert(file.end(), head.begin(), head.end());
        for (size_t i = 0; i < tail0.size(); ++i)
            if (i != 1 && i != 3) file.push_back(tail0[i]);
        w.write("unusual", "exact_repair_before_stream_info",
                std::string(kRepairStream) + ", with object 0's rows 5 and 7 first, before the STREAM_INFO: held like "
                "POINTS packets (spec 19.5: checked once the object's entry is known), released and accepted when "
                "the STREAM_INFO arrives (the first starts the object's connectivity); recovered when piece 4 arrives, "
                "as in valid/exact_repair",
                file);
    }

    // Faulty: valid/exact_repair with one defect.
    // A copy of object 0's row 6 (lost in valid/exact_repair), numbered 1000, with `edit` applied, resealed.
    auto defective = [&](const std::function<void(Packet&)>& edit) {
        Packet p = row(6, 1000);
        edit(p);
        reseal(p);
        return p;
    };
    auto set_payload = [](Packet& p, std::vector<uint8_t> payload) { p = with_payload(p, payload); };
    struct RepairEdit {
        const char* name;
        const char* description;
        std::function<void(Packet&)> edit;
        bool first;  // before the STREAM_INFO (else after the stream)
    };
    const uint32_t n0 = s.info.objects[0].point_count;
    const std::vector<RepairEdit> edits = {
        {"exact_repair_payload_short",
         "after the stream, a CONNECTIVITY_REPAIR packet of object 0 with a payload of 15 bytes, too short for its "
         "fields (malformed payload, spec 19.5)",
         [&](Packet& p) { set_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kHeaderSize + 15)); },
         false},
        {"exact_repair_symbol_size_zero",
         "a CONNECTIVITY_REPAIR packet of object 0 with symbol_size 0 and no symbol byte, before the STREAM_INFO: held "
         "(its checks need the object's entry), then rejected when released (malformed payload, spec 19.5: L is 0)",
         [&](Packet& p) {
             put16(p, kCRepSymbolSize, 0);
             set_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kCRepSymbol));
         },
         true},
        {"exact_repair_symbol_length",
         "after the stream, object 0's row 6 with one byte more than its symbol_size 8 (payload 25 bytes, not 16 + L; "
         "malformed payload, spec 19.5)",
         [&](Packet& p) {
             std::vector<uint8_t> payload = payload_of(p);
             payload.push_back(0);
             set_payload(p, payload);
         },
         false},
        {"exact_repair_too_many_symbols",
         "after the stream, a CONNECTIVITY_REPAIR packet of object 0 with coded_size 255, symbol_size 1 and row 255: "
         "k = 255 > 254 (malformed payload, spec 19.5; the row is not below k)",
         [&](Packet& p) {
             put32(p, kCRepSize, 255);
             put16(p, kCRepSymbolSize, 1);
             p[kCRepRow] = 255;
             set_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kCRepSymbol + 1));
         },
         false},
        {"exact_repair_row_below_k",
         "after the stream, object 0's row 6 renumbered row 4, below k = 5 (rows 0..4 are the source symbols; "
         "malformed payload, spec 19.5)",
         [](Packet& p) { p[kCRepRow] = 4; }, false},
        {"exact_repair_triangle_count_zero",
         "after the stream, object 0's row 6 with triangle_count 0 (malformed payload, spec 19.5 by 19.1)",
         [](Packet& p) { put32(p, kCRepTriangles, 0); }, false},
        {"exact_repair_too_many_triangles",
         "after the stream, object 0's row 6 with triangle_count 529 = 8 x 66 + 1 (malformed payload, spec 19.5 by "
         "19.1)",
         [n0](Packet& p) { put32(p, kCRepTriangles, 8 * n0 + 1); }, false},
        {"exact_repair_coded_size_too_large",
         "after the stream, a CONNECTIVITY_REPAIR packet of object 0 with coded_size 2113 = 16 x 128 + 64 + 1, "
         "symbol_size 212 (k = 10, so that only this rule fails) and row 10 (malformed payload, spec 19.5 by 19.1)",
         [&](Packet& p) {
             put32(p, kCRepSize, 16 * get32(p, kCRepTriangles) + 65);
             put16(p, kCRepSymbolSize, 212);
             p[kCRepRow] = 10;
             std::vector<uint8_t> payload(p.begin() + kHeaderSize, p.begin() + kCRepSymbol);
             payload.resize(16 + 212, 0);
             set_payload(p, payload);
         },
         false},
        {"exact_repair_coded_size_zero",
         "after the stream, object 0's row 6 with coded_size 0 (k = 0; malformed payload in the reference decoder: a "
         "coded connectivity has at least one byte)",
         [](Packet& p) { put32(p, kCRepSize, 0); }, false},
        {"exact_repair_point_set",
         "after the stream, object 0's row 6 sent for object 2, a point set (malformed payload, spec 19.5 by 19.1)",
         [](Packet& p) { put16(p, 16, 2); }, false},
        {"exact_repair_unknown_object",
         "after the stream, object 0's row 6 sent for object 3 of 3 (unknown object, spec 11.1 step 12)",
         [](Packet& p) { put16(p, 16, 3); }, false},
        {"exact_repair_triangle_count_contradicts",
         "after the stream, object 0's row 6 with triangle_count 129 where its other packets say 128 (stream "
         "mismatch, spec 19.5)",
         [](Packet& p) { put32(p, kCRepTriangles, get32(p, kCRepTriangles) + 1); }, false},
        {"exact_repair_coded_size_contradicts",
         "after the stream, object 0's row 6 with coded_size 35 where its other packets say 34 (still k = 5; stream "
         "mismatch, spec 19.5)",
         [](Packet& p) { put32(p, kCRepSize, get32(p, kCRepSize) + 1); }, false},
        {"exact_repair_crc_contradicts",
         "after the stream, object 0's row 6 with another coded_crc (stream mismatch, spec 19.5)",
         [](Packet& p) { put32(p, kCRepCrc, get32(p, kCRepCrc) ^ 0x00010000u); }, false},
        {"exact_repair_symbol_size_contradicts",
         "after the stream, object 0's row 6 of the code at L = 16 (k = 3; the true symbol of that row for that "
         "cut) where its other repair packets say L = 8 (stream mismatch, spec 19.5: all its repair packets carry "
         "the same L)",
         [&](Packet& p) {
             ConnectivityRepair r;
             r.triangle_count = tc0;
             r.coded_size = size0;
             r.coded_crc = crc0;
             r.symbol_size = 16;
             r.row = 6;
             r.symbol = repair_symbol(vector_connectivity_symbols(coded0, 16), 6);
             set_payload(p, encode_connectivity_repair_payload(r));
         },
         false},
    };
    for (const RepairEdit& e : edits) {
        Packets file = valid;
        const Packet bad = defective(e.edit);
        if (e.first) file.insert(file.begin(), bad);
        else file.push_back(bad);
        w.write("faulty", e.name, e.description, file);
    }
    {
        // Pieces 0, 2, 4, row 5, then row 7 with a symbol byte changed: the fifth symbol held, the
        // recovered bytes fail the CRC; then row 5 again, held anew.
        Packets file = head;
        uint32_t q = 100;
        file.push_back(sym(0, q++));
        file.push_back(sym(2, q++));
        file.push_back(sym(4, q++));
        const Packet r5 = row(5, q++);
        file.push_back(r5);
        Packet forged = row(7, q++);
        forged[kCRepSymbol + 2] ^= 0x40;
        reseal(forged);
        file.push_back(forged);
        file.push_back(numbered_as(r5, q++));
        file.push_back(conn1);
        w.write("faulty", "exact_repair_crc_wrong",
                "the exact-layer stream of valid/exact with object 0's coded connectivity (L = 8, k = 5) as pieces 0, "
                "2, 4, row 5, then row 7 with one symbol byte changed (resealed: a forged symbol): it completes the "
                "symbols, but the recovered bytes fail the CRC-32C: row 7 is rejected (stream mismatch) and the "
                "bytes, rows and symbols discarded (spec 19.5); then row 5 again (new sequence number): accepted, held "
                "anew (received_bytes 0, rows [5]); object 0 is not exact",
                file);
    }
    {
        // Pieces 0 and 2, rows 5 and 6 (6 forged), then bytes 24..33 (symbols 3 and 4): 4 symbols held,
        // one missing, solved from row 5 alone.
        Packets file = head;
        uint32_t q = 100;
        file.push_back(sym(0, q++));
        file.push_back(sym(2, q++));
        file.push_back(row(5, q++));
        Packet forged = row(6, q++);
        forged[kCRepSymbol + 5] ^= 0x11;
        reseal(forged);
        file.push_back(forged);
        file.push_back(piece(24, 34, q++));
        file.push_back(conn1);
        w.write("faulty", "exact_repair_unused_forged",
                "the exact-layer stream of valid/exact with object 0's coded connectivity (L = 8, k = 5) as pieces 0 "
                "and 2, row 5, row 6 with one symbol byte changed (resealed: forged), then one piece of bytes 24..33 "
                "(symbols 3 and 4): one symbol missing, solved from the first row held, row 5 (spec 19.5), so the "
                "forged row is not used: no rejection, object 0 recovered and exact; but row 6's symbol is not that "
                "row of the code over the connectivity: the recording does not conform; a validator reports it",
                file);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.4: animations (ANIMATION, spec 20). The car of the scene vectors (packet size 200) with two
// animations; ANIMATION packets say 1.4, the other packets 1.1 as in the scene vectors.

// Animation 0 "Drive": track 0 turns the front wheel (node 2) about z, LINEAR rotation, 16 keys (3
// packets at packet size 200: keys 0..6, 7..13, 14..15); track 1 moves the car (node 0) forward in
// hops, STEP translation, 4 keys (1 packet). Animation 1 "Lamp pulse": track 0 scales the lamp (node
// 4), CUBICSPLINE, 5 keys (2 packets: keys 0..2, 3..4).
SceneAnimation drive_animation() {
    SceneAnimation drive;
    drive.name = "Drive";
    SceneAnimation::Track spin{2, AnimationPath::Rotation, Interpolation::Linear, 0, {}, {}};
    for (int k = 0; k < 16; ++k) {
        spin.times.push_back(0.125f * float(k));
        const double half = 0.25 * k;  // half the angle turned
        for (float v : {0.0f, 0.0f, float(std::sin(half)), float(std::cos(half))}) spin.values.push_back(v);
    }
    SceneAnimation::Track hop{0, AnimationPath::Translation, Interpolation::Step, 0, {}, {}};
    for (int k = 0; k < 4; ++k) {
        hop.times.push_back(0.5f * float(k));
        for (float v : {1.0f + 0.5f * float(k), 0.0f, -2.0f}) hop.values.push_back(v);
    }
    drive.tracks = {spin, hop};
    return drive;
}

SceneAnimation pulse_animation() {
    SceneAnimation pulse;
    pulse.name = "Lamp pulse";
    SceneAnimation::Track grow{4, AnimationPath::Scale, Interpolation::CubicSpline, 0, {}, {}};
    for (int k = 0; k < 5; ++k) {
        const double t = 0.25 * k;
        grow.times.push_back(float(t));
        const float value = float(1 + 0.5 * std::sin(M_PI * t)), tangent = float(0.5 * M_PI * std::cos(M_PI * t));
        for (float v : {tangent, value, tangent})  // in-tangent, value, out-tangent: x, y, z each
            for (int c = 0; c < 3; ++c) grow.values.push_back(v);
    }
    pulse.tracks = {grow};
    return pulse;
}

SceneDescription animated_car() {
    SceneDescription s = make_scene();
    s.animations = {drive_animation(), pulse_animation()};
    return s;
}

// Offsets in an ANIMATION packet (header included, spec 20.1).
constexpr size_t kAnimIndex = kHeaderSize, kAnimCount = kHeaderSize + 2, kAnimTrack = kHeaderSize + 4,
                 kAnimTrackCount = kHeaderSize + 6, kAnimNode = kHeaderSize + 8, kAnimPath = kHeaderSize + 10,
                 kAnimInterpolation = kHeaderSize + 11, kAnimKeyCount = kHeaderSize + 12,
                 kAnimFirstKey = kHeaderSize + 16, kAnimKeys = kHeaderSize + 20, kAnimReserved = kHeaderSize + 23;

AnimationPiece piece_of(const Packet& p) {
    AnimationPiece piece;
    if (decode_animation_payload(payload_of(p), piece) != Error::Ok) {
        std::cerr << "make_vectors: not an ANIMATION packet\n";
        std::exit(1);
    }
    return piece;
}

// An ANIMATION packet written from a piece as given (format 1.4, stream-level, skippable).
Packet animation_packet(const AnimationPiece& piece, uint32_t sequence) {
    PacketHeader h;
    h.version_minor = kAnimationMinor;
    h.type = uint8_t(PacketType::Animation);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = kStreamObjectId;
    return write_packet(h, encode_animation_payload(piece));
}

// Keys [first, first + count) of track `track` of animation `animation` of `scene`, as one piece.
AnimationPiece cut_piece(const SceneDescription& scene, uint16_t animation, uint16_t track, uint32_t first,
                         uint32_t count) {
    const SceneAnimation& a = scene.animations[animation];
    const SceneAnimation::Track& t = a.tracks[track];
    AnimationPiece piece;
    piece.animation = animation;
    piece.animation_count = uint16_t(scene.animations.size());
    piece.track = track;
    piece.track_count = uint16_t(a.tracks.size());
    piece.name = a.name;
    piece.info = {t.node, t.path, t.interpolation, uint32_t(t.times.size())};
    piece.first_key = first;
    const size_t per_key = animation_values_per_key(t.path, t.interpolation);
    piece.times.assign(t.times.begin() + first, t.times.begin() + first + count);
    piece.values.assign(t.values.begin() + std::ptrdiff_t(first * per_key),
                        t.values.begin() + std::ptrdiff_t((first + count) * per_key));
    return piece;
}

void put_f32(Packet& p, size_t at, float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    put32(p, at, v);
}

void animation_vectors(Writer& w) {
    const SceneDescription scene = animated_car();
    const SceneStream base = make_scene_stream(scene, 200);
    const Packets& anims = base.scene.animations;  // Drive 0: keys 0..6, 7..13, 14..15; Drive 1; Pulse: 0..2, 3..4
    if (anims.size() != 6) {
        std::cerr << "make_vectors: the animated car takes " << anims.size() << " ANIMATION packets, not 6\n";
        std::exit(1);
    }
    const Packets stream = base.all();  // the animated car in stream order
    const Packets before(stream.begin(), stream.end() - long(anims.size()));  // all but the ANIMATION packets
    const char* kCar =
        "the animated car of valid/animation (format 1.4: the car of valid/scene with animation 0 'Drive', a LINEAR "
        "rotation of node 2 in 16 keys over 3 packets and a STEP translation of node 0 in 4 keys, and animation 1 "
        "'Lamp pulse', a CUBICSPLINE scale of node 4 in 5 keys over 2 packets), packets in stream order";
    {
        Packets sent = before;
        Packets shuffled = anims;
        Rng rng(51);
        for (size_t i = shuffled.size(); i > 1; --i) std::swap(shuffled[i - 1], shuffled[rng.below(i)]);
        for (size_t i = 0; i < shuffled.size(); ++i) {
            sent.push_back(shuffled[i]);
            if (i == 1) sent.push_back(shuffled[i]);
            if (i == 4) {
                Packet again = shuffled[0];
                restamp_packet(again, 900);
                sent.push_back(again);
            }
        }
        w.write("valid", "animation",
                "format 1.4 (spec 20): the car of valid/scene with 2 animations: 'Drive' turns the front wheel (node "
                "2; LINEAR rotation, 16 keys in 3 packets) and moves the car (node 0; STEP translation, 4 keys), "
                "'Lamp pulse' scales the lamp (node 4; CUBICSPLINE, 5 keys of in-tangent, value, out-tangent in 2 "
                "packets); the ANIMATION packets (version 1.4) after the others, shuffled, one sent twice and one "
                "retransmitted with a new sequence number (duplicates); both animations complete and shown with "
                "every track",
                sent);
    }

    // ---- unusual ----
    {
        Packets sent = stream;
        Packet copy = anims[3];  // Drive track 1 (STEP translation): every y is +0, key 0's time +0
        AnimationPiece piece = piece_of(copy);
        piece.times[0] = -0.0f;
        for (float& v : piece.values)
            if (v == 0.0f) v = -0.0f;
        sent.push_back(animation_packet(piece, 1000));
        w.write("unusual", "animation_negative_zero",
                std::string(kCar) +
                    ", then Drive's translation packet again (sequence 1000) with -0 where it had +0: the time of key "
                    "0 and the y of every key: a duplicate, not a mismatch (spec 20.1: keys compare as numbers, +0 "
                    "and -0 agree), and not malformed (-0 is not a negative time)",
                sent);
    }
    {
        Packets sent = anims;
        sent.insert(sent.end(), before.begin(), before.end());
        w.write("unusual", "animation_before_scene",
                "the packets of the animated car with the 6 ANIMATION packets first, before the STREAM_INFO and the "
                "SCENE packets: stream-level packets are not held (spec 15, 20), each is accepted when it arrives; "
                "the animations are shown once the nodes they move have arrived (spec 20.2); decodes to the "
                "animations of valid/animation",
                sent);
    }
    {
        // Drive's rotation track cut another way: keys 9..15, 0..4, 3..9 (5..8 new, 3, 4, 9 compared),
        // then 2..6 (nothing new: a duplicate).
        Packets sent = before;
        uint32_t sequence = 1000;
        for (auto [first, count] : std::vector<std::pair<uint32_t, uint32_t>>{{9, 7}, {0, 5}, {3, 7}, {2, 5}}) {
            sent.push_back(animation_packet(cut_piece(scene, 0, 0, first, count), sequence++));
            if (sent.back().size() > 200) {
                std::cerr << "make_vectors: an ANIMATION packet larger than the packet size\n";
                std::exit(1);
            }
        }
        for (size_t i = 3; i < anims.size(); ++i) sent.push_back(anims[i]);
        w.write("unusual", "animation_overlapping_keys",
                "the animated car with Drive's rotation track (16 keys) in 4 packets that overlap, cut as no sender "
                "cuts: keys 9..15, 0..4, 3..9 (accepted: it brings 5..8; its keys 3, 4 and 9 are compared with "
                "those held and agree), then 2..6 (a duplicate: every key held); spec 20.1: keys are kept by index, "
                "whatever packets carried them; decodes to the animations of valid/animation",
                sent);
    }
    {
        Packets sent = before;
        for (Packet p : anims) {
            p[kAnimReserved] = 0xA5;
            reseal(p);
            sent.push_back(p);
        }
        Packet again = anims[0];
        again[kAnimReserved] = 0x5A;
        reseal(again);
        restamp_packet(again, 1000);
        sent.push_back(again);
        w.write("unusual", "animation_reserved",
                "the animated car with the reserved byte (payload offset 23) of every ANIMATION packet set to A5, "
                "and the first one again (sequence 1000) with 5A there: ignored when reading (spec 20.1), so the "
                "repeat is a duplicate; decodes to the animations of valid/animation",
                sent);
    }
    {
        // The smallest tracks: one key (LINEAR, STEP), two keys for a cubic spline.
        SceneDescription s = animated_car();
        SceneAnimation pose;
        pose.name = "Pose";
        pose.tracks.push_back({1, AnimationPath::Translation, Interpolation::Step, 0, {0.0f}, {0.0f, 0.75f, 0.0f}});
        pose.tracks.push_back({4, AnimationPath::Scale, Interpolation::CubicSpline, 0, {0.0f, 2.0f},
                               {0, 0, 0, 1, 1, 1, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 2, 2, 2, 0, 0, 0}});
        pose.tracks.push_back({3, AnimationPath::Rotation, Interpolation::Linear, 0, {1.5f}, {0, 0, 1, 0}});
        s.animations.push_back(pose);
        const SceneStream t = make_scene_stream(s, 200);
        w.write("unusual", "animation_smallest_tracks",
                "the animated car with a third animation 'Pose' of the smallest tracks spec 20.1 allows: a STEP "
                "translation of node 1 with 1 key, a CUBICSPLINE scale of node 4 with 2 keys (glTF's least), a LINEAR "
                "rotation of node 3 with 1 key at time 1.5; each complete and usable (one key's times increase), "
                "every animation shown",
                t.all());
    }

    // ---- faulty: no rejection, but the stream is not complete or does not conform (spec 20.2) ----
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(before.size()) + 1);  // Drive track 0, keys 7..13
        w.write("faulty", "animation_incomplete",
                std::string(kCar) +
                    ", without the packet of keys 7..13 of Drive's rotation track: no rejection; the track holds 9 of "
                    "16 keys (missing [7, 14)), Drive is not complete and not shown (spec 20.2: 'a receiver MUST NOT "
                    "play part of one'); Lamp pulse is complete and shown; the stream is not complete",
                sent);
    }
    {
        Packets sent(stream.begin(), stream.end() - 2);  // both packets of Lamp pulse
        w.write("faulty", "animation_lost",
                std::string(kCar) +
                    ", without the 2 packets of Lamp pulse: no rejection; animation_count says 2 and only Drive "
                    "arrived; Drive is shown; the stream is not complete (spec 20.2: 'complete only when every "
                    "animation of animation_count is complete')",
                sent);
    }
    {
        Packets sent = stream;
        Packet& last = sent[before.size() + 2];  // Drive track 0, keys 14..15 (times 1.75, 1.875)
        AnimationPiece piece = piece_of(last);
        piece.times = {0.8125f, 0.9375f};
        last = with_payload(last, encode_animation_payload(piece));
        w.write("faulty", "animation_track_unusable",
                std::string(kCar) +
                    ", with the times of keys 14 and 15 of Drive's rotation track (in its last packet) 0.8125 and "
                    "0.9375: the packet is well formed (its own times increase), but key 14 comes before key 13 "
                    "(1.625); no rejection; the track is complete and not usable, left out (spec 20.2); Drive shown "
                    "with track 1 alone; the stream does not conform",
                sent);
    }
    {
        SceneDescription s = animated_car();
        SceneAnimation::Track twin{2, AnimationPath::Rotation, Interpolation::Linear, 0, {0.0f, 1.0f},
                                   {0, 0, 0, 1, 0, 0, 1, 0}};
        SceneAnimation::Track slide{2, AnimationPath::Translation, Interpolation::Step, 0, {0.0f, 1.0f},
                                    {0.4f, -0.3f, 0, 0.4f, -0.2f, 0}};
        s.animations[0].tracks.push_back(twin);
        s.animations[0].tracks.push_back(slide);
        const SceneStream t = make_scene_stream(s, 200);
        w.write("faulty", "animation_duplicate_target",
                "the animated car with 2 more tracks in Drive: track 2, a LINEAR rotation of node 2 (2 keys), the "
                "node and path of track 0, and track 3, a STEP translation of node 2 (2 keys): no rejection; track "
                "2 is left out (spec 20.2: the same node and path as a track of a smaller index that is shown), track "
                "3 shown (same node, other path): Drive shown with tracks 0, 1, 3; the stream does not conform",
                t.all());
    }
    {
        // The target of an unusable track is free: Drive's track 0 made unusable as in
        // animation_track_unusable, and a track 2 with its node and path.
        SceneDescription s = animated_car();
        s.animations[0].tracks.push_back(
            {2, AnimationPath::Rotation, Interpolation::Linear, 0, {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, 1, 0}});
        const SceneStream t = make_scene_stream(s, 200);
        Packets sent = t.all();
        bool edited = false;
        for (Packet& p : sent)
            if (p[6] == uint8_t(PacketType::Animation) && get16(p, kAnimIndex) == 0 && get16(p, kAnimTrack) == 0 &&
                get32(p, kAnimFirstKey) == 14) {
                AnimationPiece piece = piece_of(p);
                piece.times = {0.8125f, 0.9375f};
                p = with_payload(p, encode_animation_payload(piece));
                edited = true;
            }
        if (!edited) std::exit(1);
        w.write("faulty", "animation_duplicate_target_freed",
                "the animated car with Drive's track 0 not usable (the times of its keys 14 and 15 0.8125 and "
                "0.9375, as in faulty/animation_track_unusable) and a track 2, a LINEAR rotation of node 2 (2 keys), "
                "its node and path: no rejection; track 0 is left out, so track 2 has no kept track of a smaller "
                "index with its node and path and is kept (spec 20.2): Drive shown with tracks 1 and 2; the stream "
                "does not conform (an unusable track, two tracks with one node and path)",
                sent);
    }
    {
        // Drive with a third track whose node is 5, in a table of 5 nodes (packetize_scene refuses it:
        // cut it for node 4, then edit the node).
        SceneDescription s = animated_car();
        s.animations[0].tracks.push_back(
            {4, AnimationPath::Translation, Interpolation::Linear, 0, {0.0f, 2.0f}, {0, 1.5f, 0, 0, 1.75f, 0}});
        const SceneStream t = make_scene_stream(s, 200);
        Packets sent = t.all();
        bool edited = false;
        for (Packet& p : sent)
            if (p[6] == uint8_t(PacketType::Animation) && get16(p, kAnimIndex) == 0 && get16(p, kAnimTrack) == 2) {
                put16(p, kAnimNode, 5);
                reseal(p);
                edited = true;
            }
        if (!edited) std::exit(1);
        w.write("faulty", "animation_node_past_table",
                "the animated car with a third track in Drive, a LINEAR translation of node 5 (2 keys) in a table of "
                "5 nodes (resealed): well formed (spec 20.1 does not check node against the SCENE table), no "
                "rejection; the track is complete and usable but its node is not shown, so it is left out (spec "
                "20.2); Drive shown with tracks 0 and 1; the stream does not conform",
                sent);
    }
    {
        Packets sent = stream;
        const size_t last_scene = base.geometry.all().size() + base.scene.scene.size() - 1;  // node 4, both meshes
        sent.erase(sent.begin() + long(last_scene));
        w.write("faulty", "animation_node_absent",
                std::string(kCar) +
                    ", without its last SCENE packet (node 4, the lamp, and both meshes): no rejection; Lamp pulse is "
                    "complete but its only track moves node 4, whose record did not arrive: the track is left out and "
                    "no track remains, so Lamp pulse is not shown (spec 20.2); Drive shown; the stream is not complete",
                sent);
    }
    {
        Packets sent = base.geometry.all();
        sent.insert(sent.end(), anims.begin(), anims.end());
        w.write("faulty", "animation_no_scene",
                "the geometry of the car and its 6 ANIMATION packets, without any SCENE, MATERIAL or TEXTURE_FRAGMENT "
                "packet: no rejection; both animations complete, none shown (spec 20.2: 'no SCENE packet at all: no "
                "animation is shown'); the stream does not conform (a track's node has no node record)",
                sent);
    }
    {
        SceneDescription s = animated_car();
        s.animations[1].name = std::string("Lamp \xFF pulse \xE2\x82");
        const SceneStream t = make_scene_stream(s, 200);
        w.write("faulty", "animation_name_not_utf8",
                "the animated car with Lamp pulse named with bytes that are not UTF-8 (a lone FF, a cut three-byte "
                "sequence E2 82 at the end): no rejection; the name shown as 'Lamp \\uFFFD pulse \\uFFFD' (spec 20.2 by "
                "15: each maximal ill-formed subsequence one U+FFFD); both animations shown; the stream does not "
                "conform",
                t.all());
    }

    // ---- faulty: rejections. A copy of Drive's first packet (track 0, keys 0..6, times 0 .. 0.75) with
    // one defect, sequence 1000, after the stream (resealed; a payload of another length gets its
    // payload_length and checksum). Everything else decodes as in valid/animation. ----
    const Packet& first = anims[0];
    auto after_stream = [&](Packet copy) {
        restamp_packet(copy, 1000);  // reseals
        Packets sent = stream;
        sent.push_back(copy);
        return sent;
    };
    auto edited = [&](const std::function<void(Packet&)>& edit) {
        Packet copy = first;
        edit(copy);
        reseal(copy);
        return after_stream(copy);
    };
    auto rebuilt = [&](const std::function<void(AnimationPiece&)>& edit) {
        AnimationPiece piece = piece_of(first);
        edit(piece);
        return after_stream(animation_packet(piece, 1000));
    };
    const std::string kCopy = std::string(kCar) + ", then a copy of Drive's first ANIMATION packet (track 0, keys 0..6) ";
    {
        std::vector<uint8_t> payload = payload_of(first);
        payload.resize(20);
        w.write("faulty", "animation_payload_short",
                kCopy + "cut to a payload of 20 bytes, shorter than the 24 bytes of its fields: rejected, malformed "
                        "payload (spec 20.1: 'payload_length MUST equal 24 + name_length + count * 4 * (1 + V)')",
                after_stream(with_payload(first, payload)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first);
        payload.push_back(0);
        w.write("faulty", "animation_length_mismatch",
                kCopy + "with one byte (00) more after its keys: rejected, malformed payload (spec 20.1: the length "
                        "differs from 24 + name_length + count * 4 * (1 + V))",
                after_stream(with_payload(first, payload)));
    }
    w.write("faulty", "animation_index_past_table",
            kCopy + "saying animation 2 of animation_count 2: rejected, malformed payload (spec 20.1: 'animation >= "
                    "animation_count')",
            edited([](Packet& p) { put16(p, kAnimIndex, 2); }));
    w.write("faulty", "animation_track_past_count",
            kCopy + "saying track 2 of track_count 2: rejected, malformed payload (spec 20.1: 'track >= track_count')",
            edited([](Packet& p) { put16(p, kAnimTrack, 2); }));
    w.write("faulty", "animation_path_3",
            kCopy + "with path 3 (0..2 defined): rejected, malformed payload (spec 20.1: 'path > 2')",
            edited([](Packet& p) { p[kAnimPath] = 3; }));
    w.write("faulty", "animation_interpolation_3",
            kCopy + "with interpolation 3 (0..2 defined): rejected, malformed payload (spec 20.1: 'interpolation > 2')",
            edited([](Packet& p) { p[kAnimInterpolation] = 3; }));
    w.write("faulty", "animation_key_count_zero",
            kCopy + "with key_count 0: rejected, malformed payload (spec 20.1: 'key_count is 0')",
            edited([](Packet& p) { put32(p, kAnimKeyCount, 0); }));
    {
        AnimationPiece piece = piece_of(anims[4]);  // Lamp pulse, keys 0..2
        piece.info.key_count = 1;
        piece.times.resize(1);
        piece.values.resize(9);
        w.write("faulty", "animation_cubicspline_one_key",
                std::string(kCar) +
                    ", then a packet of Lamp pulse's CUBICSPLINE track (sequence 1000) with key_count 1 and its first "
                    "key alone: rejected, malformed payload (spec 20.1: 'key_count ... below 2 with CUBICSPLINE, "
                    "which glTF requires')",
                after_stream(animation_packet(piece, 1000)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first);
        payload.resize(24 + payload[22]);  // the fields and the name, no key
        payload[20] = payload[21] = 0;
        w.write("faulty", "animation_count_zero",
                kCopy + "with count 0 and no key (a payload of 24 + 5 bytes, its length consistent): rejected, "
                        "malformed payload (spec 20.1: 'count is 0')",
                after_stream(with_payload(first, payload)));
    }
    w.write("faulty", "animation_keys_past_count",
            kCopy + "with first_key 10: 10 + 7 keys = 17 > key_count 16: rejected, malformed payload (spec 20.1: "
                    "'first_key + count > key_count')",
            edited([](Packet& p) { put32(p, kAnimFirstKey, 10); }));
    w.write("faulty", "animation_first_key_overflow",
            kCopy + "with first_key 4294967293 = 2^32 - 3: first_key + count = 2^32 + 4, which is 4 in 32-bit "
                    "arithmetic: rejected, malformed payload (spec 20.1: 'first_key + count > key_count (computed "
                    "without overflow)')",
            edited([](Packet& p) { put32(p, kAnimFirstKey, 4294967293u); }));
    const size_t key_bytes = 4 * (1 + 4);
    const size_t keys_at = kHeaderSize + 24 + 5;  // Drive's keys, after its 5-byte name
    w.write("faulty", "animation_time_infinite",
            kCopy + "with the time of its last key (6) +infinity: rejected, malformed payload (spec 20.1: 'a float "
                    "is not finite')",
            edited([&](Packet& p) { put32(p, keys_at + 6 * key_bytes, 0x7F800000u); }));
    w.write("faulty", "animation_value_nan",
            kCopy + "with the w of key 2's quaternion a NaN (7FC00000): rejected, malformed payload (spec 20.1: 'a "
                    "float is not finite')",
            edited([&](Packet& p) { put32(p, keys_at + 2 * key_bytes + 16, 0x7FC00000u); }));
    w.write("faulty", "animation_time_negative",
            kCopy + "with the time of key 0 -0.5 (the others 0.125 .. 0.75): rejected, malformed payload (spec 20.1: "
                    "'a time is negative')",
            edited([&](Packet& p) { put_f32(p, keys_at, -0.5f); }));
    w.write("faulty", "animation_times_not_increasing",
            kCopy + "with the time of key 4 0.375, that of key 3: rejected, malformed payload (spec 20.1: 'the times "
                    "of the packet do not strictly increase')",
            edited([&](Packet& p) { put_f32(p, keys_at + 4 * key_bytes, 0.375f); }));

    w.write("faulty", "animation_count_contradicts",
            kCopy + "saying animation_count 3 where every other says 2: rejected, stream mismatch (spec 20.1: its "
                    "animation_count against the one kept)",
            edited([](Packet& p) { put16(p, kAnimCount, 3); }));
    w.write("faulty", "animation_track_count_contradicts",
            kCopy + "saying track_count 3 where Drive's packets say 2: rejected, stream mismatch (spec 20.1)",
            edited([](Packet& p) { put16(p, kAnimTrackCount, 3); }));
    w.write("faulty", "animation_name_contradicts",
            kCopy + "naming the animation 'drive' where it is 'Drive': rejected, stream mismatch (spec 20.1: names "
                    "compared as bytes)",
            edited([](Packet& p) { p[kHeaderSize + 24] = 'd'; }));
    w.write("faulty", "animation_node_contradicts",
            kCopy + "saying node 3 where track 0's packets say 2: rejected, stream mismatch (spec 20.1: the track's "
                    "description)",
            edited([](Packet& p) { put16(p, kAnimNode, 3); }));
    w.write("faulty", "animation_path_contradicts",
            kCopy + "rebuilt as a translation (path 0; V = 3: each key's x, y, z of the quaternion, a payload of "
                    "24 + 5 + 7 x 16 bytes): well formed, rejected, stream mismatch (spec 20.1: the track's "
                    "description)",
            rebuilt([](AnimationPiece& a) {
                a.info.path = AnimationPath::Translation;
                std::vector<float> values;
                for (size_t k = 0; k < a.times.size(); ++k)
                    for (size_t c = 0; c < 3; ++c) values.push_back(a.values[4 * k + c]);
                a.values = values;
            }));
    w.write("faulty", "animation_interpolation_contradicts",
            kCopy + "saying interpolation 1 (STEP) where track 0's packets say 0 (LINEAR): rejected, stream mismatch "
                    "(spec 20.1: the track's description)",
            edited([](Packet& p) { p[kAnimInterpolation] = 1; }));
    w.write("faulty", "animation_key_count_contradicts",
            kCopy + "saying key_count 17 where track 0's packets say 16: rejected, stream mismatch (spec 20.1: the "
                    "track's description)",
            edited([](Packet& p) { put32(p, kAnimKeyCount, 17); }));
    w.write("faulty", "animation_time_contradicts",
            kCopy + "with the time of key 3 0.4375 where it was 0.375 (its times still increase): rejected, stream "
                    "mismatch (spec 20.1: each of its keys against the key of the same index kept)",
            edited([&](Packet& p) { put_f32(p, keys_at + 3 * key_bytes, 0.4375f); }));
    {
        // Before the track is complete: right after Drive's first packet (keys 0..6), a packet of keys
        // 4..9 whose key 5 differs; keys 7..9 (new) are not kept either, they come with the next packet.
        AnimationPiece piece = cut_piece(scene, 0, 0, 4, 6);
        piece.values[(5 - 4) * 4 + 2] += 0.125f;
        Packets sent = stream;
        sent.insert(sent.begin() + long(before.size()) + 1, animation_packet(piece, 1000));
        w.write("faulty", "animation_value_contradicts",
                std::string(kCar) +
                    ", with a packet of keys 4..9 of Drive's rotation track (sequence 1000) right after its first "
                    "packet (keys 0..6), the z of key 5's quaternion 0.125 more: rejected, stream mismatch (spec "
                    "20.1: a key against the key of the same index kept, also while the track is not complete), and "
                    "nothing of it is kept (keys 7..9 arrive with the next packet); the animations as in "
                    "valid/animation",
                sent);
    }
}

// ------------------------------------------------------------------------------------------------
// Format 1.5: skins (SKIN and JOINT_WEIGHTS, spec 21). The arm: 6 nodes (a root "Rig", a chain of 4
// joints "Upper", "Lower", "Hand", "Finger", and "Arm", which shows mesh 0 with skin 0), one mesh of
// one object (6 ellipsoids, 40 points with normals, packet size 200), one skin "Arm skin" of the 4
// joint nodes 1..4 (skeleton node 1), and an influence record for every point. The geometry and the
// SCENE packets without a skin field say 1.1, the SCENE packet with node 5's record 1.5, the SKIN and
// JOINT_WEIGHTS packets 1.5.

SceneDescription skinned_arm() {
    SceneDescription s;
    SceneNode rig;
    rig.index = 0;
    rig.name = "Rig";
    rig.translation = {0, 0, -3};
    SceneNode upper;
    upper.index = 1;
    upper.parent = 0;
    upper.name = "Upper";
    upper.translation = {0, -1, 0};
    SceneNode lower;
    lower.index = 2;
    lower.parent = 1;
    lower.name = "Lower";
    lower.translation = {0, 0.75f, 0};
    lower.rotation = {0, 0, 0.25881904f, 0.9659258f};  // 30 degrees about z
    SceneNode hand;
    hand.index = 3;
    hand.parent = 2;
    hand.name = "Hand";
    hand.translation = {0, 0.75f, 0};
    SceneNode finger;
    finger.index = 4;
    finger.parent = 3;
    finger.name = "Finger";
    finger.translation = {0, 0.5f, 0};
    SceneNode arm;
    arm.index = 5;
    arm.parent = 0;
    arm.mesh = 0;
    arm.skin = 0;
    arm.name = "Arm";
    s.nodes = {rig, upper, lower, hand, finger, arm};
    s.meshes = {{0, "Arm", {{0, kNone}}, {}}};
    SceneSkin skin;
    skin.name = "Arm skin";
    skin.skeleton = 1;
    // Inverse bind matrices: the joints stand at y = -1, -0.25, 0.5, 1 of the rig in the bind pose.
    for (auto [node, y] : std::vector<std::pair<uint16_t, float>>{{1, -1.0f}, {2, -0.25f}, {3, 0.5f}, {4, 1.0f}}) {
        SkinJoint j;
        j.node = node;
        j.inverse_bind[13] = -y;  // column-major: the translation is in the last column
        skin.joints.push_back(j);
    }
    s.skins = {skin};
    return s;
}

// Every point's record: hat functions of its height along the arm over the 4 joints (1 to 4
// influences), rounded by the library (spec 21.4); the top points follow the finger alone.
std::vector<Influences> arm_weights(const StreamInfo& info, const ObjectContent& c) {
    const ObjectInfo& o = info.objects[0];
    std::vector<float> ys;
    for (const QuantizedPoint& q : c.points) ys.push_back(dequantize_point(q, info, o).position[1]);
    const auto [lo, hi] = std::minmax_element(ys.begin(), ys.end());
    const float bottom = *lo, top = *hi;
    std::vector<Influences> out;
    for (float y : ys) {
        const float t = 3.0f * (y - bottom) / (top - bottom);
        std::vector<uint16_t> joints = {0, 1, 2, 3};
        std::vector<float> weights;
        for (int j = 0; j < 4; ++j) weights.push_back(std::max(0.0f, 1.6f - std::fabs(t - float(j))));
        if (t > 2.85f) weights = {0, 0, 0, 1};
        out.push_back(quantize_influences(joints, weights));
    }
    return out;
}

struct SkinStream {
    Stream geometry;
    ScenePackets scene;  // SCENE and SKIN packets
    std::vector<Influences> records;
    Packets weights;  // JOINT_WEIGHTS packets
    Packets before_weights() const {
        Packets out = geometry.all();
        out.insert(out.end(), scene.scene.begin(), scene.scene.end());
        out.insert(out.end(), scene.skins.begin(), scene.skins.end());
        return out;
    }
    Packets all() const {
        Packets out = before_weights();
        out.insert(out.end(), weights.begin(), weights.end());
        return out;
    }
};

SkinStream make_skin_stream(const SceneDescription& scene) {
    SkinStream s;
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 6, 40, kAttrNormal)}, 200);
    Rng rng(61);
    s.geometry.contents.push_back(make_content(info, info.objects[0], rng));
    s.geometry.info = info;
    if (packetize_stream(info, s.geometry.contents, kStreamId, s.geometry.packets) != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed\n";
        std::exit(1);
    }
    uint32_t next = uint32_t(s.geometry.all().size());
    if (packetize_scene(scene, 200, kStreamId, next, s.scene) != Error::Ok) {
        std::cerr << "make_vectors: packetize_scene failed (skins)\n";
        std::exit(1);
    }
    next += uint32_t(s.scene.scene.size() + s.scene.skins.size());
    s.records = arm_weights(info, s.geometry.contents[0]);
    if (packetize_joint_weights(info, 0, s.records, kStreamId, next, s.weights) != Error::Ok) {
        std::cerr << "make_vectors: packetize_joint_weights failed\n";
        std::exit(1);
    }
    return s;
}

// A SKIN packet written from a piece as given (format 1.5, stream-level, skippable).
Packet skin_packet(const SkinPiece& piece, uint32_t sequence) {
    PacketHeader h;
    h.version_minor = kSkinMinor;
    h.type = uint8_t(PacketType::Skin);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = kStreamObjectId;
    return write_packet(h, encode_skin_payload(piece));
}

SkinPiece skin_piece_of(const Packet& p) {
    SkinPiece piece;
    if (decode_skin_payload(payload_of(p), piece) != Error::Ok) {
        std::cerr << "make_vectors: not a SKIN packet\n";
        std::exit(1);
    }
    return piece;
}

// An influence record as bytes are written, also one that breaks spec 21.2 (n = joints.size()
// unless given).
struct RawRecord {
    std::vector<uint16_t> joints;
    std::vector<uint8_t> weights;
    int n = -1;
};
RawRecord raw(const Influences& r) {
    RawRecord out;
    for (size_t k = 0; k < r.count; ++k) {
        out.joints.push_back(r.joints[k]);
        out.weights.push_back(r.weights[k]);
    }
    return out;
}
// A JOINT_WEIGHTS payload written as given: joints of `joint_size` bytes (the library writes 1 when
// every joint is below 256), `count` as given (the records' number unless given).
std::vector<uint8_t> weights_payload(uint32_t first, const std::vector<RawRecord>& records, uint8_t joint_size,
                                     int count = -1) {
    std::vector<uint8_t> out;
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(first >> (8 * i)));
    const uint16_t c = count < 0 ? uint16_t(records.size()) : uint16_t(count);
    out.push_back(uint8_t(c));
    out.push_back(uint8_t(c >> 8));
    out.push_back(joint_size);
    out.push_back(0);
    for (const RawRecord& r : records) {
        out.push_back(uint8_t(r.n < 0 ? r.joints.size() : size_t(r.n)));
        for (uint16_t j : r.joints) {
            out.push_back(uint8_t(j));
            if (joint_size == 2) out.push_back(uint8_t(j >> 8));
        }
        for (uint8_t w : r.weights) out.push_back(w);
    }
    return out;
}
JointWeightsRun run_of(const Packet& p) {
    JointWeightsRun run;
    if (decode_joint_weights_payload(payload_of(p), run) != Error::Ok) {
        std::cerr << "make_vectors: not a JOINT_WEIGHTS packet\n";
        std::exit(1);
    }
    return run;
}
std::vector<RawRecord> raw_records(const JointWeightsRun& run) {
    std::vector<RawRecord> out;
    for (const Influences& r : run.records) out.push_back(raw(r));
    return out;
}
// A JOINT_WEIGHTS packet (format 1.5, skippable) of object `object`.
Packet weights_packet(uint16_t object, uint32_t sequence, const std::vector<uint8_t>& payload) {
    PacketHeader h;
    h.version_minor = kSkinMinor;
    h.type = uint8_t(PacketType::JointWeights);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = object;
    return write_packet(h, payload);
}

// A SCENE packet of one node record, as the library writes it (a skin field only when the node has
// a skin) followed by `extra` bytes in the record body; it says 1.5 when `minor` says so.
Packet one_node_scene_packet(const SceneDescription& scene, SceneNode n, const std::vector<uint8_t>& extra,
                             uint8_t minor, uint32_t sequence) {
    SceneBatch batch{uint16_t(scene.nodes.size()), uint16_t(scene.meshes.size()), {n}, {}};
    std::vector<uint8_t> payload = encode_scene_payload(batch);
    // header (8), kind (1), length (2), body: the only record ends the payload.
    payload.insert(payload.end(), extra.begin(), extra.end());
    const uint16_t length = uint16_t(payload[9] | (payload[10] << 8)) + uint16_t(extra.size());
    payload[9] = uint8_t(length);
    payload[10] = uint8_t(length >> 8);
    PacketHeader h;
    h.version_minor = minor;
    h.type = uint8_t(PacketType::Scene);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = kStreamObjectId;
    return write_packet(h, payload);
}

// `packets` with node `node`'s record edited in the SCENE packet that holds it (re-encoded; the
// packet says 1.5 when a record of it then carries a skin).
Packets edit_node(Packets packets, uint16_t node, const std::function<void(SceneNode&)>& edit) {
    bool found = false;
    for (Packet& p : packets) {
        if (p[6] != uint8_t(PacketType::Scene)) continue;
        SceneBatch batch;
        if (decode_scene_payload(payload_of(p), batch) != Error::Ok) continue;
        bool here = false;
        for (SceneNode& n : batch.nodes)
            if (n.index == node) {
                edit(n);
                here = true;
            }
        if (!here) continue;
        p = with_payload(p, encode_scene_payload(batch));
        const bool skinned = std::any_of(batch.nodes.begin(), batch.nodes.end(), [](const SceneNode& n) { return n.skin != kNone; });
        p[5] = skinned ? kSkinMinor : kFormatMinor;
        reseal(p);
        found = true;
    }
    if (!found) {
        std::cerr << "make_vectors: no SCENE packet holds node " << node << "\n";
        std::exit(1);
    }
    return packets;
}

// Offsets in a SKIN packet (header included, spec 21.1).
constexpr size_t kSkinIndex = kHeaderSize, kSkinCount = kHeaderSize + 2, kSkinJointCount = kHeaderSize + 4,
                 kSkinFirstJoint = kHeaderSize + 6, kSkinJoints = kHeaderSize + 8, kSkinSkeleton = kHeaderSize + 10,
                 kSkinReserved = kHeaderSize + 13, kSkinName = kHeaderSize + 14;
// Offsets in a JOINT_WEIGHTS packet (header included, spec 21.2).
constexpr size_t kWeightsFirst = kHeaderSize, kWeightsCount = kHeaderSize + 4, kWeightsJointSize = kHeaderSize + 6,
                 kWeightsReserved = kHeaderSize + 7;

void skin_vectors(Writer& w) {
    const SceneDescription scene = skinned_arm();
    const SkinStream base = make_skin_stream(scene);
    const Packets& skins = base.scene.skins;     // joints 0..1, 2..3
    const Packets& weights = base.weights;       // the records of points 0.., in runs
    if (skins.size() != 2 || weights.size() < 2) {
        std::cerr << "make_vectors: the arm takes " << skins.size() << " SKIN and " << weights.size()
                  << " JOINT_WEIGHTS packets, not 2 and 2 or more\n";
        std::exit(1);
    }
    const Packets stream = base.all();
    const Packets head = base.before_weights();
    const Packets geometry = base.geometry.all();
    const size_t scene_at = geometry.size(), skins_at = scene_at + base.scene.scene.size(),
                 weights_at = skins_at + skins.size();
    const char* kArm =
        "the skinned arm of valid/skin (format 1.5: 6 nodes, node 5 'Arm' showing mesh 0 (object 0: 6 ellipsoids, 40 "
        "points with normals) with skin 0 'Arm skin' of 4 joints (nodes 1..4, skeleton node 1) in 2 SKIN packets, "
        "and an influence record for every point in JOINT_WEIGHTS packets), packets in stream order";
    const std::string arm = kArm;
    w.write("valid", "skin",
            "format 1.5 (spec 21): a skinned arm: 6 nodes (a root 'Rig', a chain of 4 joints 'Upper', 'Lower', "
            "'Hand', 'Finger', and 'Arm', whose record names mesh 0 and skin 0: its SCENE packet says 1.5), mesh 0 "
            "of object 0 (6 ellipsoids, 40 points with normals, packet size 200), skin 0 'Arm skin' (skeleton node "
            "1) of the joint nodes 1..4 with their inverse bind matrices in 2 SKIN packets (joints 0..1, 2..3), and "
            "a record of 1 to 4 influences for every point in JOINT_WEIGHTS packets with one-byte joints; packets "
            "in stream order; the skin complete, every point weighted, node 5 shown skinned",
            stream);

    // ---- unusual ----
    {
        // The same records with two-byte joints, cut again into runs that fit the packet size of 200
        // bytes (176 of payload: 8 of header and records of 1 + 3n bytes).
        Packets sent = head;
        uint32_t sequence = 800;
        for (const Packet& p : weights) {
            const std::vector<RawRecord> records = raw_records(run_of(p));
            const uint32_t first = run_of(p).first_index;
            size_t begin = 0;
            while (begin < records.size()) {
                size_t end = begin, size = 8;
                while (end < records.size() && size + 1 + 3 * records[end].joints.size() <= 176)
                    size += 1 + 3 * records[end++].joints.size();
                const std::vector<RawRecord> part(records.begin() + long(begin), records.begin() + long(end));
                sent.push_back(weights_packet(0, sequence++, weights_payload(first + uint32_t(begin), part, 2)));
                begin = end;
            }
        }
        w.write("unusual", "weights_joint_size_2",
                arm + ", with the records of every JOINT_WEIGHTS packet written with two-byte joints (joint_size 2, "
                      "although every joint is below 256), cut again into runs that fit the packet size (sequence "
                      "800 on): the same records (spec 21.2); decodes as valid/skin",
                sent);
    }
    {
        Packets sent = skins;
        sent.insert(sent.end(), weights.begin(), weights.end());
        sent.insert(sent.end(), head.begin(), head.begin() + long(skins_at));
        w.write("unusual", "skin_before_stream_info",
                "the packets of the skinned arm with the 2 SKIN and the JOINT_WEIGHTS packets first, before the "
                "STREAM_INFO and the SCENE packets: the SKIN packets are stream-level and accepted at once (spec 21), "
                "the JOINT_WEIGHTS packets held like POINTS packets (spec 21.2, 11.2) and released in arrival order "
                "when the STREAM_INFO arrives, then accepted; decodes as valid/skin",
                sent);
    }
    {
        Packets sent = geometry;
        Packets rest(stream.begin() + long(scene_at), stream.end());
        Rng rng(71);
        for (size_t i = rest.size(); i > 1; --i) std::swap(rest[i - 1], rest[rng.below(i)]);
        for (size_t i = 0; i < rest.size(); ++i) {
            sent.push_back(rest[i]);
            if (i == 1) sent.push_back(rest[i]);
            if (i == 3) {
                Packet again = rest[0];
                restamp_packet(again, 900);
                sent.push_back(again);
            }
        }
        Packet again = skins[1];
        restamp_packet(again, 901);
        sent.push_back(again);
        again = weights[0];
        restamp_packet(again, 902);
        sent.push_back(again);
        w.write("unusual", "skin_shuffled_duplicates",
                "the skinned arm with its SCENE, SKIN and JOINT_WEIGHTS packets shuffled after the geometry, the "
                "second sent twice (byte-identical), the first again after the fourth with sequence number 900, and "
                "the second SKIN packet and the first JOINT_WEIGHTS packet again at the end (sequence 901, 902): "
                "duplicates (spec 21.1, 21.2: nothing new); decodes as valid/skin",
                sent);
    }
    {
        Packets sent = stream;
        JointWeightsRun run = run_of(weights[0]);
        std::vector<RawRecord> records = raw_records(run);
        records.resize(12);  // 12 records of at most 13 bytes fit the packet size with two-byte joints
        sent.push_back(weights_packet(0, 1000, weights_payload(run.first_index, records, 2)));
        w.write("unusual", "weights_joint_size_repeat",
                arm + ", then the records of points 0..11 again (sequence 1000) written with two-byte joints: "
                      "identical to those held (spec 21.2: joints compare as numbers, whatever joint_size carried "
                      "them): a duplicate",
                sent);
    }
    {
        // Runs cut as no sender cuts: 10..29 (two-byte joints), 0..14 (0..9 new, 10..14 compared), then the
        // rest from 30, then 5..34 (a duplicate).
        Packets sent = head;
        uint32_t sequence = 1000;
        const uint32_t n = uint32_t(base.records.size());
        for (auto [first, count, size] : std::vector<std::tuple<uint32_t, uint32_t, uint8_t>>{
                 {10, 20, 2}, {0, 15, 1}, {30, n - 30, 1}, {5, 20, 1}}) {
            std::vector<RawRecord> records;
            for (uint32_t i = first; i < first + count; ++i) records.push_back(raw(base.records[i]));
            sent.push_back(weights_packet(0, sequence++, weights_payload(first, records, size)));
            if (sent.back().size() > 200) {
                std::cerr << "make_vectors: a JOINT_WEIGHTS packet larger than the packet size\n";
                std::exit(1);
            }
        }
        w.write("unusual", "weights_overlapping_runs",
                "the skinned arm with its records in 4 JOINT_WEIGHTS packets that overlap, cut as no sender cuts "
                "(sequence 1000..1003): points 10..29 (two-byte joints), 0..14 (accepted: it brings 0..9; its records "
                "of 10..14 are compared with those held and agree), 30..39, then 5..24 (a duplicate: every record "
                "held); spec 21.2 keeps one record per point, whatever packets carried it; decodes as valid/skin",
                sent);
    }
    {
        Packets sent = stream;
        SkinPiece piece = skin_piece_of(skins[0]);
        size_t zeros = 0;
        for (SkinJoint& j : piece.joints)
            for (float& v : j.inverse_bind)
                if (v == 0.0f) {
                    v = -0.0f;
                    ++zeros;
                }
        if (zeros == 0) std::exit(1);
        sent.push_back(skin_packet(piece, 1000));
        w.write("unusual", "skin_negative_zero",
                arm + ", then the first SKIN packet again (sequence 1000) with -0 for every +0 of its two inverse bind "
                      "matrices: a duplicate, not a mismatch (spec 21.1: matrix entries compare as numbers, +0 and -0 "
                      "agree)",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t i = skins_at; i < sent.size(); ++i) {
            Packet& p = sent[i];
            p[i < weights_at ? kSkinReserved : kWeightsReserved] = 0xA5;
            reseal(p);
        }
        Packet again = skins[0];
        again[kSkinReserved] = 0x5A;
        reseal(again);
        restamp_packet(again, 1000);
        sent.push_back(again);
        w.write("unusual", "skin_reserved",
                arm + ", with the reserved byte of every SKIN packet (payload offset 13) and of every JOINT_WEIGHTS "
                      "packet (payload offset 7) set to A5, then the first SKIN packet again (sequence 1000) with 5A "
                      "there: ignored when reading (spec 21.1, 21.2), so the repeat is a duplicate; decodes as "
                      "valid/skin",
                sent);
    }
    {
        // Node 4's record with one stray byte after its transform: fewer than the two bytes of a skin field.
        Packets sent = geometry;
        sent.push_back(one_node_scene_packet(scene, scene.nodes[4], {0x00}, kSkinMinor, 1000));
        sent.insert(sent.end(), stream.begin() + long(scene_at), stream.end());
        w.write("unusual", "skin_node_stray_byte",
                "the skinned arm with, before its SCENE packets, a SCENE packet (version 1.5, sequence 1000) of node "
                "4's record followed by one stray byte 00 after its transform: fewer than the two bytes of a skin "
                "field, so the record has no skin (spec 21: 'a record without those two bytes has no skin'; 15.1: "
                "the byte is ignored) and compares equal to the record of the stream's SCENE packet, which is then a "
                "duplicate for that node; decodes as valid/skin",
                sent);
    }
    {
        // Every record without a skin written first with an explicit skin field 0xFFFF (SCENE packets that say
        // 1.5), then the stream's own SCENE packets, whose records of those nodes have no field.
        Packets sent = geometry;
        for (uint16_t i = 0; i < 5; ++i)
            sent.push_back(one_node_scene_packet(scene, scene.nodes[i], {0xFF, 0xFF}, kSkinMinor, 1000 + i));
        sent.insert(sent.end(), stream.begin() + long(scene_at), stream.end());
        w.write("unusual", "skin_field_none",
                "the skinned arm with, before its SCENE packets, one SCENE packet (version 1.5, sequence 1000..1004) "
                "for each of nodes 0..4 whose record carries an explicit skin field FFFF (none); the stream's own "
                "SCENE packets, whose records of those nodes have no skin field (as a 1.4 encoder writes them), then "
                "agree with them (spec 21: 'a record without it comparing as 0xFFFF'): the first is a duplicate, the "
                "one with node 5's record accepted; decodes as valid/skin",
                sent);
    }

    // ---- faulty: no rejection, but the stream is not complete or does not conform (spec 21.3) ----
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(skins_at) + 1);
        w.write("faulty", "skin_incomplete",
                arm + ", without the second SKIN packet (joints 2..3): no rejection; the skin holds 2 of 4 joints "
                      "(missing [2, 4)), is not complete, and node 5 is shown unskinned (spec 21.3: 'its record names "
                      "a skin ... and that skin is complete'); the stream is not complete",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(skins_at), sent.begin() + long(weights_at));
        w.write("faulty", "skin_lost",
                arm + ", without both SKIN packets: no rejection; skin_count null, no skin; node 5 names skin 0 and is "
                      "shown unskinned (spec 21.3); the stream is not complete",
                sent);
    }
    w.write("faulty", "skin_index_past_count",
            arm + ", with node 5's record naming skin 1 where skin_count is 1 (its SCENE packet re-encoded): no "
                  "rejection (spec 21: the field is not checked against the skin table in SCENE); node 5 is shown "
                  "unskinned; the stream does not conform ('every node whose record names a skin names one below "
                  "skin_count')",
            edit_node(stream, 5, [](SceneNode& n) { n.skin = 1; }));
    w.write("faulty", "skin_node_without_mesh",
            arm + ", with node 4's record (the finger, no mesh) naming skin 0 (its SCENE packet re-encoded, saying "
                  "1.5): no rejection; node 4 has no mesh to skin, node 5 is shown skinned; the stream does not "
                  "conform (spec 21.3: 'every node whose record names a skin ... has a mesh')",
            edit_node(stream, 4, [](SceneNode& n) { n.skin = 0; }));
    {
        Packets sent = stream;
        SkinPiece piece = skin_piece_of(skins[1]);
        piece.joints[1].node = 6;
        sent[skins_at + 1] = with_payload(skins[1], encode_skin_payload(piece));
        w.write("faulty", "skin_joint_node_past_table",
                arm + ", with joint 3's node 6 in a table of 6 nodes (the second SKIN packet re-encoded): no "
                      "rejection (spec 21.1 does not check node against the SCENE table); node 6 has no record and is "
                      "not shown, so node 5 is shown unskinned (21.3); the stream does not conform ('every joint's "
                      "node ... is below the SCENE node_count and has a node record')",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t k = 0; k < 2; ++k) {
            Packet& p = sent[skins_at + k];
            put16(p, kSkinSkeleton, 6);
            reseal(p);
        }
        w.write("faulty", "skin_skeleton_past_table",
                arm + ", with the skeleton node 6 in a table of 6 nodes in both SKIN packets (resealed): no "
                      "rejection; the skeleton is not shown, so node 5 is shown unskinned (spec 21.3: 'and the "
                      "skin's skeleton when it is not 0xFFFF'); the stream does not conform",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t k = 0; k < 2; ++k) {
            SkinPiece piece = skin_piece_of(skins[k]);
            piece.name = std::string("Arm \xC0\xAF skin");
            sent[skins_at + k] = with_payload(skins[k], encode_skin_payload(piece));
        }
        w.write("faulty", "skin_name_not_utf8",
                arm + ", with the skin named with the bytes 'Arm C0 AF skin' (an overlong encoding of '/', two "
                      "maximal ill-formed subsequences) in both SKIN packets: no rejection; the name shown as "
                      "'Arm \\uFFFD\\uFFFD skin' (spec 21.1 by 15); node 5 shown skinned; the stream does not conform",
                sent);
    }
    {
        Packets sent = stream;
        JointWeightsRun run = run_of(weights[0]);
        std::vector<RawRecord> records = raw_records(run);
        size_t at = 0;
        while (records[at].joints.size() < 2) ++at;
        records[at].joints.back() = 4;  // joint 4 of a skin of 4 joints
        sent[weights_at] = with_payload(weights[0], weights_payload(run.first_index, records, 1));
        w.write("faulty", "weights_joint_past_count",
                arm + ", with the last joint of point " + std::to_string(run.first_index + at) +
                    "'s record 4, past the skin's 4 joints (the first JOINT_WEIGHTS packet re-encoded): no rejection "
                    "(spec 21.2 does not check joints against a skin); node 5 is shown unskinned (21.3: 'every joint "
                    "index in the records held for those objects is below the skin's joint_count'); the stream does "
                    "not conform",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(weights_at) + 1);
        w.write("faulty", "weights_point_missing",
                arm + ", without the second JOINT_WEIGHTS packet: no rejection; object 0 is weighted (a held point "
                      "with its record), so node 5 is shown skinned (spec 21.3: each vertex gets the record of the "
                      "nearest held point with a record), but the stream is not complete ('every point of every "
                      "object shown by the mesh of a node whose record names a skin has its record')",
                sent);
    }
    w.write("faulty", "weights_lost",
            arm + ", without any JOINT_WEIGHTS packet: no rejection; object 0 is not weighted, so node 5 is shown "
                  "unskinned (spec 21.3: 'every object its mesh shows is weighted'); the stream is not complete",
            head);

    // ---- faulty: SKIN rejections. A copy of the first SKIN packet (joints 0..1) with one defect,
    // sequence 1000, after the stream (resealed; a payload of another length gets its payload_length
    // and checksum). Everything else decodes as in valid/skin. ----
    const Packet& first_skin = skins[0];
    auto after_stream = [&](Packet copy) {
        restamp_packet(copy, 1000);  // reseals
        Packets sent = stream;
        sent.push_back(copy);
        return sent;
    };
    auto skin_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet copy = first_skin;
        edit(copy);
        reseal(copy);
        return after_stream(copy);
    };
    auto skin_rebuilt = [&](const std::function<void(SkinPiece&)>& edit) {
        SkinPiece piece = skin_piece_of(first_skin);
        edit(piece);
        return after_stream(skin_packet(piece, 1000));
    };
    const std::string kSkinCopy = arm + ", then a copy of the first SKIN packet (joints 0..1) ";
    {
        std::vector<uint8_t> payload = payload_of(first_skin);
        payload.resize(13);
        w.write("faulty", "skin_payload_short",
                kSkinCopy + "cut to a payload of 13 bytes, shorter than its 14 bytes of fields: rejected, malformed "
                            "payload (spec 21.1: 'payload_length MUST equal 14 + name_length + 66 * count')",
                after_stream(with_payload(first_skin, payload)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first_skin);
        payload.push_back(0);
        w.write("faulty", "skin_length_mismatch",
                kSkinCopy + "with one byte (00) more after its joints: rejected, malformed payload (spec 21.1: the "
                            "length differs)",
                after_stream(with_payload(first_skin, payload)));
    }
    w.write("faulty", "skin_index_past_table",
            kSkinCopy + "saying skin 1 of skin_count 1: rejected, malformed payload (spec 21.1: 'skin >= skin_count')",
            skin_edited([](Packet& p) { put16(p, kSkinIndex, 1); }));
    w.write("faulty", "skin_table_empty",
            kSkinCopy + "saying skin_count 0: rejected, malformed payload (spec 21.1: skin 0 >= skin_count 0)",
            skin_edited([](Packet& p) { put16(p, kSkinCount, 0); }));
    w.write("faulty", "skin_joint_count_zero",
            kSkinCopy + "with joint_count 0: rejected, malformed payload (spec 21.1: 'joint_count is 0')",
            skin_edited([](Packet& p) { put16(p, kSkinJointCount, 0); }));
    {
        std::vector<uint8_t> payload = payload_of(first_skin);
        payload.resize(14 + payload[12]);  // the fields and the name, no joint
        payload[8] = payload[9] = 0;
        w.write("faulty", "skin_count_zero",
                kSkinCopy + "with count 0 and no joint (a payload of 14 + 8 bytes: its length agrees): rejected, "
                            "malformed payload (spec 21.1: 'count is 0')",
                after_stream(with_payload(first_skin, payload)));
    }
    w.write("faulty", "skin_joints_past_count",
            kSkinCopy + "with first_joint 3: 3 + 2 joints = 5 > joint_count 4: rejected, malformed payload (spec 21.1: "
                        "'first_joint + count > joint_count')",
            skin_edited([](Packet& p) { put16(p, kSkinFirstJoint, 3); }));
    w.write("faulty", "skin_first_joint_overflow",
            kSkinCopy + "with first_joint 65535: first_joint + count = 65537, which is 1 in 16-bit arithmetic: "
                        "rejected, malformed payload (spec 21.1: 'computed without overflow')",
            skin_edited([](Packet& p) { put16(p, kSkinFirstJoint, 65535); }));
    const size_t joints_at = kSkinName + 8;  // after the 8-byte name "Arm skin"
    w.write("faulty", "skin_matrix_infinite",
            kSkinCopy + "with entry 15 of joint 1's inverse bind matrix -infinity (FF800000): rejected, malformed "
                        "payload (spec 21.1: 'a float is not finite')",
            skin_edited([&](Packet& p) { put32(p, joints_at + 66 + 2 + 4 * 15, 0xFF800000u); }));
    w.write("faulty", "skin_matrix_nan",
            kSkinCopy + "with entry 5 of joint 0's inverse bind matrix a NaN (7FC00000): rejected, malformed payload "
                        "(spec 21.1: 'a float is not finite')",
            skin_edited([&](Packet& p) { put32(p, joints_at + 2 + 4 * 5, 0x7FC00000u); }));
    w.write("faulty", "skin_count_contradicts",
            kSkinCopy + "saying skin_count 2 where the others say 1: rejected, stream mismatch (spec 21.1: its "
                        "skin_count against the one kept)",
            skin_edited([](Packet& p) { put16(p, kSkinCount, 2); }));
    w.write("faulty", "skin_joint_count_contradicts",
            kSkinCopy + "saying joint_count 5 where the skin's packets say 4: rejected, stream mismatch (spec 21.1)",
            skin_edited([](Packet& p) { put16(p, kSkinJointCount, 5); }));
    w.write("faulty", "skin_skeleton_contradicts",
            kSkinCopy + "saying skeleton 0 where the skin's packets say 1: rejected, stream mismatch (spec 21.1)",
            skin_edited([](Packet& p) { put16(p, kSkinSkeleton, 0); }));
    w.write("faulty", "skin_name_contradicts",
            kSkinCopy + "naming the skin 'arm skin' where it is 'Arm skin': rejected, stream mismatch (spec 21.1: "
                        "names compared as bytes)",
            skin_edited([](Packet& p) { p[kSkinName] = 'a'; }));
    w.write("faulty", "skin_joint_node_contradicts",
            kSkinCopy + "saying node 3 for joint 1 where it is node 2: rejected, stream mismatch (spec 21.1: each "
                        "joint against the joint of the same index kept)",
            skin_edited([&](Packet& p) { put16(p, joints_at + 66, 3); }));
    w.write("faulty", "skin_matrix_contradicts",
            kSkinCopy + "with entry 13 of joint 0's inverse bind matrix 1.5 where it is 1: rejected, stream mismatch "
                        "(spec 21.1: the 16 matrix entries as numbers)",
            skin_rebuilt([](SkinPiece& s) { s.joints[0].inverse_bind[13] = 1.5f; }));
    {
        // Before the skin is complete: right after the first SKIN packet (joints 0..1), a packet of
        // joints 1..2 whose joint 1 differs; joint 2 (new) is not kept either, it comes with the next packet.
        SkinPiece piece = skin_piece_of(first_skin);
        SkinPiece second = skin_piece_of(skins[1]);
        piece.first_joint = 1;
        piece.joints = {piece.joints[1], second.joints[0]};
        piece.joints[0].inverse_bind[0] = 2.0f;
        Packets sent = stream;
        sent.insert(sent.begin() + long(skins_at) + 1, skin_packet(piece, 1000));
        w.write("faulty", "skin_joint_contradicts_partly_new",
                arm + ", with a SKIN packet of joints 1..2 (sequence 1000) right after the first (joints 0..1), "
                      "entry 0 of joint 1's matrix 2 where it is 1: rejected, stream mismatch (spec 21.1: also while "
                      "the skin is not complete), and nothing of it is kept (joint 2, not held then, arrives with the "
                      "next packet); the skin as in valid/skin",
                sent);
    }
    {
        SceneNode n = scene.nodes[5];
        n.skin = 1;
        Packets sent = stream;
        sent.push_back(one_node_scene_packet(scene, n, {}, kSkinMinor, 1000));
        w.write("faulty", "skin_node_skin_contradicts",
                arm + ", then a SCENE packet (version 1.5, sequence 1000) of node 5's record naming skin 1 where it "
                      "named skin 0: rejected, stream mismatch (spec 21: the field is compared like the record's other "
                      "fields, 15.1)",
                sent);
    }
    {
        SceneNode n = scene.nodes[5];
        n.skin = kNone;
        Packets sent = stream;
        sent.push_back(one_node_scene_packet(scene, n, {}, kFormatMinor, 1000));
        w.write("faulty", "skin_node_skin_dropped",
                arm + ", then a SCENE packet (version 1.1, sequence 1000) of node 5's record without the skin field, "
                      "as a 1.4 encoder writes it: rejected, stream mismatch (spec 21: 'a record without it comparing "
                      "as 0xFFFF', and node 5's names skin 0)",
                sent);
    }

    // ---- faulty: JOINT_WEIGHTS rejections. A copy of the first JOINT_WEIGHTS packet with one defect,
    // sequence 1000, after the stream (resealed; a payload of another length gets its payload_length
    // and checksum), unless the row says otherwise. Everything else decodes as in valid/skin. ----
    const Packet& first_weights = weights[0];
    const JointWeightsRun run0 = run_of(first_weights);
    const std::vector<RawRecord> records0 = raw_records(run0);
    size_t multi = 0;  // the first record with at least 2 influences of different weights
    while (records0[multi].joints.size() < 2 || records0[multi].weights[0] == records0[multi].weights[1]) ++multi;
    const std::string kWeightsCopy = arm + ", then a copy of the first JOINT_WEIGHTS packet (points 0.." +
                                     std::to_string(run0.records.size() - 1) + ") ";
    auto weights_rebuilt = [&](const std::function<void(std::vector<RawRecord>&)>& edit, uint8_t joint_size = 1) {
        std::vector<RawRecord> records = records0;
        edit(records);
        return with_payload(first_weights, weights_payload(run0.first_index, records, joint_size));
    };
    auto weights_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet copy = first_weights;
        edit(copy);
        reseal(copy);
        return after_stream(copy);
    };
    const std::string at_multi = "point " + std::to_string(multi) + "'s record";
    {
        std::vector<uint8_t> payload = payload_of(first_weights);
        payload.resize(7);
        w.write("faulty", "weights_payload_short",
                kWeightsCopy + "cut to a payload of 7 bytes, shorter than its 8 bytes of fields: rejected, malformed "
                               "payload (spec 21.2: 'shorter than 8 bytes')",
                after_stream(with_payload(first_weights, payload)));
    }
    w.write("faulty", "weights_count_zero",
            kWeightsCopy + "with count 0 and no record (an 8-byte payload): rejected, malformed payload (spec 21.2: "
                           "'count is 0')",
            after_stream(with_payload(first_weights, weights_payload(0, {}, 1))));
    w.write("faulty", "weights_joint_size_3",
            kWeightsCopy + "with joint_size 3: rejected, malformed payload (spec 21.2: 'joint_size is neither 1 nor 2')",
            weights_edited([](Packet& p) { p[kWeightsJointSize] = 3; }));
    {
        const uint32_t first = uint32_t(0x100000000ull - run0.records.size());
        w.write("faulty", "weights_index_overflow",
                kWeightsCopy + "with first_index " + std::to_string(first) + " = 2^32 - count: first_index + count = "
                               "2^32 > 2^32 - 1 (0 in 32-bit arithmetic): rejected, malformed payload (spec 21.2: "
                               "'computed without overflow'; checked at step 11, before the object's point_count)",
                weights_edited([&](Packet& p) { put32(p, kWeightsFirst, first); }));
    }
    w.write("faulty", "weights_n_zero",
            kWeightsCopy + "with point 0's record replaced by one of n 0 (one byte 00): rejected, malformed payload "
                           "(spec 21.2: 'a record's n is 0')",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{}, {}, 0}; })));
    w.write("faulty", "weights_n_5",
            kWeightsCopy + "with point 0's record replaced by one of 5 influences (joints 0..4, weights 51 each: "
                           "distinct, summing to 255): rejected, malformed payload (spec 21.2: 'above 4')",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) {
                r[0] = RawRecord{{0, 1, 2, 3, 4}, {51, 51, 51, 51, 51}};
            })));
    {
        std::vector<uint8_t> payload = payload_of(first_weights);
        payload.pop_back();
        w.write("faulty", "weights_record_past_payload",
                kWeightsCopy + "without its last byte (the last weight of its last record): rejected, malformed "
                               "payload (spec 21.2: 'a record runs past the payload')",
                after_stream(with_payload(first_weights, payload)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first_weights);
        payload.push_back(0);
        w.write("faulty", "weights_trailing_byte",
                kWeightsCopy + "with one byte (00) more after its last record: rejected, malformed payload (spec "
                               "21.2: 'bytes follow the last record')",
                after_stream(with_payload(first_weights, payload)));
    }
    w.write("faulty", "weights_weight_zero",
            kWeightsCopy + "with point 0's record replaced by joints 0, 1, 2 with weights 0, 200, 55 (summing to 255): "
                           "rejected, malformed payload (spec 21.2: 'a weight is 0')",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{0, 1, 2}, {0, 200, 55}}; })));
    w.write("faulty", "weights_sum_254",
            kWeightsCopy + "with point 0's record replaced by joints 0, 1 with weights 200, 54: rejected, malformed "
                           "payload (spec 21.2: 'a record's weights do not sum to 255')",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{0, 1}, {200, 54}}; })));
    w.write("faulty", "weights_sum_wraps",
            kWeightsCopy + "with point 0's record replaced by joints 0, 1, 2 with weights 255, 255, 1: they sum to 511, "
                           "which is 255 in 8-bit arithmetic: rejected, malformed payload (spec 21.2: the weights do "
                           "not sum to 255)",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{0, 1, 2}, {255, 255, 1}}; })));
    w.write("faulty", "weights_joint_twice",
            kWeightsCopy + "with point 0's record replaced by joints 1, 2, 1 with weights 100, 100, 55: rejected, "
                           "malformed payload (spec 21.2: 'a record names one joint twice')",
            after_stream(weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{1, 2, 1}, {100, 100, 55}}; })));
    {
        Packet bad = weights_rebuilt([](std::vector<RawRecord>& r) { r[0] = RawRecord{{0, 1, 2}, {0, 200, 55}}; });
        restamp_packet(bad, 1000);
        Packets sent = {bad};
        sent.insert(sent.end(), stream.begin(), stream.end());
        w.write("faulty", "weights_malformed_before_stream_info",
                "the skinned arm with, before its STREAM_INFO, the copy of faulty/weights_weight_zero (sequence "
                "1000): rejected when it arrives, malformed payload (spec 21.2: the checks that need no stream info "
                "are made at step 11, before a packet is held, 11.1); nothing held; the rest as in valid/skin",
                sent);
    }
    {
        Packet copy = first_weights;
        put16(copy, 16, 1);  // object_id (header offset 16)
        reseal(copy);
        w.write("faulty", "weights_unknown_object",
                kWeightsCopy + "sent for object 1 of a 1-object stream: rejected, unknown object (spec 21.2, 11.1 step "
                               "12)",
                after_stream(copy));
    }
    {
        const JointWeightsRun last = run_of(weights.back());
        Packet copy = weights.back();
        put32(copy, kWeightsFirst, last.first_index + 1);
        reseal(copy);
        w.write("faulty", "weights_index_out_of_range",
                arm + ", then a copy of the last JOINT_WEIGHTS packet (points " + std::to_string(last.first_index) +
                    "..39) saying first_index " + std::to_string(last.first_index + 1) +
                    " (sequence 1000): its last point 40 is not below point_count 40: rejected, index out of range "
                    "(spec 21.2, 11.1 step 14)",
                after_stream(copy));
        restamp_packet(copy, 1000);
        Packets sent = {copy};
        sent.insert(sent.end(), stream.begin(), stream.end());
        w.write("faulty", "weights_held_out_of_range",
                "the skinned arm with, before its STREAM_INFO, the copy of faulty/weights_index_out_of_range (sequence "
                "1000): well formed, so held (spec 21.2); when the STREAM_INFO releases it, rejected at its own "
                "offset 12, index out of range (11.1 step 14); the rest as in valid/skin",
                sent);
    }
    w.write("faulty", "weights_n_contradicts",
            kWeightsCopy + "with " + at_multi + " replaced by its first joint alone, weight 255 (well formed): "
                           "rejected, stream mismatch (spec 21.2: records identical only with the same n)",
            after_stream(weights_rebuilt([&](std::vector<RawRecord>& r) {
                r[multi] = RawRecord{{r[multi].joints[0]}, {255}};
            })));
    w.write("faulty", "weights_joint_contradicts",
            kWeightsCopy + "with " + at_multi + "'s first joint replaced by a joint it does not name (well formed): "
                           "rejected, stream mismatch (spec 21.2: the same joint indices)",
            after_stream(weights_rebuilt([&](std::vector<RawRecord>& r) {
                uint16_t other = 0;
                while (std::find(r[multi].joints.begin(), r[multi].joints.end(), other) != r[multi].joints.end()) ++other;
                r[multi].joints[0] = other;
            })));
    w.write("faulty", "weights_order_contradicts",
            kWeightsCopy + "with " + at_multi + "'s first two influences swapped (each joint keeps its weight: the "
                           "same influences in another order): rejected, stream mismatch (spec 21.2: 'the same joint "
                           "indices in the same order ... and the same weights in the same order')",
            after_stream(weights_rebuilt([&](std::vector<RawRecord>& r) {
                std::swap(r[multi].joints[0], r[multi].joints[1]);
                std::swap(r[multi].weights[0], r[multi].weights[1]);
            })));
    w.write("faulty", "weights_weight_contradicts",
            kWeightsCopy + "with " + at_multi + "'s first two weights swapped (the joints in place; still summing to "
                           "255): rejected, stream mismatch (spec 21.2: the same weights in the same order)",
            after_stream(weights_rebuilt([&](std::vector<RawRecord>& r) {
                std::swap(r[multi].weights[0], r[multi].weights[1]);
            })));
    {
        // Before the second run arrives: right after the first JOINT_WEIGHTS packet, one of the last 4 points
        // of its run and the first 4 of the next, the first of them with its record changed.
        const uint32_t n0 = uint32_t(run0.records.size());
        std::vector<RawRecord> records;
        for (uint32_t i = n0 - 4; i < n0 + 4; ++i) records.push_back(raw(base.records[i]));
        records[0] = RawRecord{{records[0].joints[0]}, {255}};
        if (base.records[n0 - 4].count == 1) records[0] = RawRecord{{uint16_t(records[0].joints[0] ^ 1)}, {255}};
        Packets sent = stream;
        sent.insert(sent.begin() + long(weights_at) + 1, weights_packet(0, 1000, weights_payload(n0 - 4, records, 1)));
        w.write("faulty", "weights_contradicts_partly_new",
                arm + ", with a JOINT_WEIGHTS packet of points " + std::to_string(n0 - 4) + ".." +
                    std::to_string(n0 + 3) + " (sequence 1000) right after the first (points 0.." +
                    std::to_string(n0 - 1) + "), point " + std::to_string(n0 - 4) +
                    "'s record changed: rejected, stream mismatch (spec 21.2), and nothing of it is kept (the records "
                    "of points " + std::to_string(n0) + ".." + std::to_string(n0 + 3) +
                    ", not held then, arrive with the next packet); as valid/skin",
                sent);
    }
}


// ------------------------------------------------------------------------------------------------
// Format 1.6: morph targets (MORPH_DELTAS and MORPH_ANIMATION, the SCENE mesh record's targets, spec
// 22). The morphing face: two objects at packet size 300 (object 0, 6 ellipsoids and 20 points with
// normals; object 1, 4 ellipsoids and 12 points with normals); 4 nodes ("Stage", the root; "Face" and
// "Mirror", which both show mesh 0; "Box", which shows mesh 1); mesh 0 "Face" of object 0 with 2
// targets and default weights 0.25, 0; mesh 1 "Box" of object 1 without targets; the displacements
// (position and normal) of every point of object 0; animation "Talk" (a translation of node 1 in one
// ANIMATION packet, and weights of nodes 1 and 3 in morph animation 0, which joins it) and morph
// animation 1 "Blink" (weights of node 1), which stands alone. The geometry says 1.1, the SCENE
// packet (which carries mesh 0's target field) 1.6, the ANIMATION packet 1.4, the MORPH_ANIMATION
// and MORPH_DELTAS packets 1.6.

SceneDescription morphing_face(bool talk_moves_node = true) {
    SceneDescription s;
    SceneNode stage;
    stage.index = 0;
    stage.name = "Stage";
    stage.translation = {0, 0, -3};
    SceneNode face;
    face.index = 1;
    face.parent = 0;
    face.mesh = 0;
    face.name = "Face";
    face.translation = {-1, 0, 0};
    SceneNode box;
    box.index = 2;
    box.parent = 0;
    box.mesh = 1;
    box.name = "Box";
    box.translation = {1, 0, 0};
    SceneNode mirror;
    mirror.index = 3;
    mirror.parent = 0;
    mirror.mesh = 0;
    mirror.name = "Mirror";
    mirror.translation = {0, 1.5f, 0};
    s.nodes = {stage, face, box, mirror};
    s.meshes = {{0, "Face", {{0, kNone}}, {0.25f, 0.0f}}, {1, "Box", {{1, kNone}}, {}}};
    // Talk: node 1 slides (ANIMATION 0), and its weights and node 3's move with it (morph animation 0).
    SceneAnimation talk;
    talk.name = "Talk";
    SceneAnimation::Track slide{1, AnimationPath::Translation, Interpolation::Linear, 0, {0, 1, 2},
                                {-1, 0, 0, -1, 0.25f, 0, -1, 0, 0}};
    SceneAnimation::Track mouth{1, AnimationPath::Weights, Interpolation::Linear, 2, {}, {}};
    for (int k = 0; k < 24; ++k) {
        mouth.times.push_back(0.125f * float(k));
        mouth.values.push_back(float(0.5 + 0.5 * std::sin(k / 3.0)));
        mouth.values.push_back(float(k % 4) * 0.25f);
    }
    SceneAnimation::Track echo{3, AnimationPath::Weights, Interpolation::Step, 2, {0, 1, 2}, {1, 0, 0, 1, 0.5f, 0.5f}};
    talk.tracks = {slide, mouth, echo};
    if (!talk_moves_node) talk.tracks.erase(talk.tracks.begin());
    SceneAnimation blink;
    blink.name = "Blink";
    blink.tracks.push_back({1, AnimationPath::Weights, Interpolation::Linear, 2, {0, 0.25f, 0.5f}, {0, 0, 0, 1, 0, 0}});
    s.animations = {talk, blink};
    return s;
}

// The displacement record of every point of object 0, `targets` targets, with the position
// (attributes bit 0) and normal (bit 1) parts, x, y, z its dequantized position: target 0 lifts the
// points of positive x by 0.1 x^2 and tilts their normals by (-0.2 x, 0, 0), and leaves the others
// (0: left out of their records, spec 22.1); target 1 pushes every point 0.15 along its normal; when
// asked for, target 2 moves every point 0.05 along z, target 3 moves the points of positive y by
// (0.04, 0, 0) and tilts their normals by (0, -0.1 y, 0), target 4 moves the points of positive z by
// (0, 0, 0.03 z) and tilts their normals by (0.05, 0.05, 0). The normal displacements of targets 1
// and 2 are 0.
std::vector<float> face_displacements(const StreamInfo& info, const ObjectContent& c, uint8_t targets,
                                      uint8_t attributes) {
    std::vector<float> out;
    for (const QuantizedPoint& q : c.points) {
        const SurfacePoint p = dequantize_point(q, info, info.objects[0]);
        const double x = p.position[0], y = p.position[1], z = p.position[2];
        for (uint8_t t = 0; t < targets; ++t) {
            std::array<double, 3> move{}, turn{};
            if (t == 0) {
                if (x > 0) {
                    move = {0, 0.1 * x * x, 0};
                    turn = {-0.2 * x, 0, 0};
                }
            } else if (t == 1) {
                move = {0.15 * p.normal[0], 0.15 * p.normal[1], 0.15 * p.normal[2]};
            } else if (t == 2) {
                move = {0, 0, 0.05};
            } else if (t == 3) {
                if (y > 0) {
                    move = {0.04, 0, 0};
                    turn = {0, -0.1 * y, 0};
                }
            } else if (z > 0) {
                move = {0, 0, 0.03 * z};
                turn = {0.05, 0.05, 0};
            }
            if (attributes & kMorphPosition)
                for (double v : move) out.push_back(float(v));
            if (attributes & kMorphNormal)
                for (double v : turn) out.push_back(float(v));
        }
    }
    return out;
}

// The morphing face of `morphing_face` with mesh 0's targets `targets` (its default weights and each
// weight track's keys padded with 0 for the targets past 2), so that it conforms with displacement
// records of that many targets.
SceneDescription morphing_face_with_targets(uint8_t targets, bool talk_moves_node = true) {
    SceneDescription s = morphing_face(talk_moves_node);
    s.meshes[0].weights.resize(targets, 0.0f);
    for (SceneAnimation& a : s.animations)
        for (SceneAnimation::Track& t : a.tracks) {
            if (t.path != AnimationPath::Weights) continue;
            std::vector<float> values;
            for (size_t at = 0; at < t.values.size(); at += t.targets) {
                values.insert(values.end(), t.values.begin() + long(at), t.values.begin() + long(at + t.targets));
                values.resize(values.size() + (targets - t.targets), 0.0f);
            }
            t.values = values;
            t.targets = targets;
        }
    return s;
}

struct MorphStream {
    Stream geometry;
    ScenePackets scene;  // SCENE; ANIMATION then MORPH_ANIMATION packets in scene.animations
    Packets deltas;      // MORPH_DELTAS of object 0
    Packets animations() const {  // the ANIMATION packets
        Packets out;
        for (const Packet& p : scene.animations)
            if (p[6] == uint8_t(PacketType::Animation)) out.push_back(p);
        return out;
    }
    Packets morph_animations() const {  // the MORPH_ANIMATION packets
        Packets out;
        for (const Packet& p : scene.animations)
            if (p[6] == uint8_t(PacketType::MorphAnimation)) out.push_back(p);
        return out;
    }
    Packets before_deltas() const {
        Packets out = geometry.all();
        out.insert(out.end(), scene.scene.begin(), scene.scene.end());
        out.insert(out.end(), scene.animations.begin(), scene.animations.end());
        return out;
    }
    Packets all() const {
        Packets out = before_deltas();
        out.insert(out.end(), deltas.begin(), deltas.end());
        return out;
    }
};

MorphStream make_morph_stream(const SceneDescription& scene, uint8_t targets = 2, uint8_t attributes = 3) {
    MorphStream s;
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 6, 20, kAttrNormal),
                                    make_object({-0.5f, -0.5f, -0.5f}, 1, 4, 12, kAttrNormal)},
                                   300);
    Rng rng(83);
    for (const ObjectInfo& o : info.objects) s.geometry.contents.push_back(make_content(info, o, rng));
    s.geometry.info = info;
    if (packetize_stream(info, s.geometry.contents, kStreamId, s.geometry.packets) != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed (morph)\n";
        std::exit(1);
    }
    uint32_t next = uint32_t(s.geometry.all().size());
    if (packetize_scene(scene, 300, kStreamId, next, s.scene) != Error::Ok) {
        std::cerr << "make_vectors: packetize_scene failed (morph)\n";
        std::exit(1);
    }
    next += uint32_t(s.scene.scene.size() + s.scene.animations.size());
    const std::vector<float> values = face_displacements(info, s.geometry.contents[0], targets, attributes);
    if (packetize_morph_deltas(info, 0, targets, attributes, values, kStreamId, next, s.deltas) != Error::Ok) {
        std::cerr << "make_vectors: packetize_morph_deltas failed\n";
        std::exit(1);
    }
    return s;
}

// A MORPH_ANIMATION packet written from a piece as given (format 1.6, stream-level, skippable).
Packet morph_animation_packet(const AnimationPiece& piece, uint32_t sequence) {
    return write_packet(skippable_header(PacketType::MorphAnimation, kMorphMinor, kStreamId, sequence, kStreamObjectId),
                        encode_morph_animation_payload(piece));
}
AnimationPiece morph_piece_of(const Packet& p) {
    AnimationPiece piece;
    if (decode_morph_animation_payload(payload_of(p), piece) != Error::Ok) {
        std::cerr << "make_vectors: not a MORPH_ANIMATION packet\n";
        std::exit(1);
    }
    return piece;
}
// A MORPH_DELTAS packet (format 1.6, skippable) of object `object` around a payload as given.
Packet deltas_packet(uint16_t object, uint32_t sequence, const std::vector<uint8_t>& payload) {
    return write_packet(skippable_header(PacketType::MorphDeltas, kMorphMinor, kStreamId, sequence, object), payload);
}
MorphDeltasRun deltas_run_of(const Packet& p) {
    MorphDeltasRun run;
    if (decode_morph_deltas_payload(payload_of(p), run) != Error::Ok) {
        std::cerr << "make_vectors: not a MORPH_DELTAS packet\n";
        std::exit(1);
    }
    return run;
}
// Every record of object 0 as one run (points 0 .. 19, the scales of the object), concatenated
// from the stream's MORPH_DELTAS packets, which cover the points in order.
MorphDeltasRun all_deltas(const Packets& deltas) {
    MorphDeltasRun all = deltas_run_of(deltas.front());
    for (size_t i = 1; i < deltas.size(); ++i) {
        const MorphDeltasRun run = deltas_run_of(deltas[i]);
        if (run.first_index != all.first_index + all.count || run.scales != all.scales) std::exit(1);
        all.values.insert(all.values.end(), run.values.begin(), run.values.end());
        all.count = uint16_t(all.count + run.count);
    }
    return all;
}
// The run of points [first, first + count) of `all` (a run from point 0).
MorphDeltasRun deltas_run(const MorphDeltasRun& all, uint32_t first, uint16_t count) {
    const size_t per_point = morph_record_values(all.target_count, all.attributes);
    if (first + count > all.count) {
        std::cerr << "make_vectors: a run past the records\n";
        std::exit(1);
    }
    MorphDeltasRun run = all;
    run.first_index = all.first_index + first;
    run.count = count;
    run.values.assign(all.values.begin() + long(first * per_point), all.values.begin() + long((first + count) * per_point));
    return run;
}
// The slots of a record (spec 22.1: S = target_count * a).
size_t deltas_slots(const MorphDeltasRun& run) { return morph_record_values(run.target_count, run.attributes) / 3; }
// A MORPH_DELTAS payload written here from the spec's words (22.1): the header, the scales, then per
// point the mask and the vectors of its set bits, a vector 0, 0, 0 left out (its bit clear) unless
// `explicit_zero(point, slot)` says to write it with its bit set. Without `explicit_zero` it is
// the reference encoder's payload (checked).
std::vector<uint8_t> deltas_payload(const MorphDeltasRun& run,
                                    const std::function<bool(size_t, size_t)>& explicit_zero = nullptr) {
    const size_t slots = deltas_slots(run), mask = (slots + 7) / 8;
    std::vector<uint8_t> out(kMorphDeltasHeaderSize);
    for (int i = 0; i < 4; ++i) out[size_t(i)] = uint8_t(run.first_index >> (8 * i));
    out[4] = uint8_t(run.count);
    out[5] = uint8_t(run.count >> 8);
    out[6] = run.target_count;
    out[7] = run.attributes;
    for (float f : run.scales) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        for (int i = 0; i < 4; ++i) out.push_back(uint8_t(u >> (8 * i)));
    }
    for (size_t i = 0; i < run.count; ++i) {
        const size_t at = out.size();
        out.resize(at + mask, 0);
        for (size_t k = 0; k < slots; ++k) {
            const int16_t* v = run.values.data() + (i * slots + k) * 3;
            if (v[0] == 0 && v[1] == 0 && v[2] == 0 && !(explicit_zero && explicit_zero(i, k))) continue;
            out[at + k / 8] |= uint8_t(1u << (k % 8));
            for (int c = 0; c < 3; ++c) {
                out.push_back(uint8_t(uint16_t(v[c])));
                out.push_back(uint8_t(uint16_t(v[c]) >> 8));
            }
        }
    }
    if (!explicit_zero && out != encode_morph_deltas_payload(run)) {
        std::cerr << "make_vectors: the MORPH_DELTAS payload written here differs from the reference encoder's\n";
        std::exit(1);
    }
    return out;
}
// The payload offset of point i's record (its mask) in a MORPH_DELTAS payload.
size_t deltas_record_at(const std::vector<uint8_t>& payload, size_t i) {
    const size_t slots = size_t(payload[6]) * size_t(std::popcount(unsigned(payload[7] & 3))), mask = (slots + 7) / 8;
    size_t at = kMorphDeltasHeaderSize + 4 * slots;
    for (size_t n = 0; n < i; ++n) {
        size_t set = 0;
        for (size_t k = 0; k < slots; ++k) set += (payload[at + k / 8] >> (k % 8)) & 1u;
        at += mask + 6 * set;
    }
    return at;
}

// The bytes of a mesh record's target field (spec 22): target_count (that of `weights` unless given)
// and the weights.
std::vector<uint8_t> target_field(const std::vector<float>& weights, int count = -1) {
    std::vector<uint8_t> out = {uint8_t(count < 0 ? weights.size() : size_t(count))};
    for (float w : weights) {
        uint32_t u;
        std::memcpy(&u, &w, 4);
        for (int i = 0; i < 4; ++i) out.push_back(uint8_t(u >> (8 * i)));
    }
    return out;
}
// A SCENE packet (saying 1.`minor`) of one mesh record: its index, name and primitives, then `tail`
// (a target field, or any bytes) in the record body.
Packet one_mesh_scene_packet(const SceneDescription& scene, SceneMesh m, const std::vector<uint8_t>& tail,
                             uint8_t minor, uint32_t sequence) {
    m.weights.clear();
    SceneBatch batch{uint16_t(scene.nodes.size()), uint16_t(scene.meshes.size()), {}, {m}};
    std::vector<uint8_t> payload = encode_scene_payload(batch);
    payload.insert(payload.end(), tail.begin(), tail.end());
    const uint16_t length = uint16_t(payload[9] | (payload[10] << 8)) + uint16_t(tail.size());
    payload[9] = uint8_t(length);
    payload[10] = uint8_t(length >> 8);
    return write_packet(skippable_header(PacketType::Scene, minor, kStreamId, sequence, kStreamObjectId), payload);
}
// `payload` (a SCENE payload) with `extra` bytes appended to the body of its record of kind `kind`
// and index `index`.
std::vector<uint8_t> append_to_record(std::vector<uint8_t> payload, uint8_t kind, uint16_t index,
                                      const std::vector<uint8_t>& extra) {
    const size_t records = size_t(payload[4] | (payload[5] << 8));
    size_t at = 8;
    for (size_t r = 0; r < records; ++r) {
        const size_t length = size_t(payload[at + 1] | (payload[at + 2] << 8));
        if (payload[at] == kind && uint16_t(payload[at + 3] | (payload[at + 4] << 8)) == index) {
            payload.insert(payload.begin() + long(at + 3 + length), extra.begin(), extra.end());
            payload[at + 1] = uint8_t(length + extra.size());
            payload[at + 2] = uint8_t((length + extra.size()) >> 8);
            return payload;
        }
        at += 3 + length;
    }
    std::cerr << "make_vectors: no such record\n";
    std::exit(1);
}

// Offsets in a MORPH_DELTAS packet (header included, spec 22.1).
constexpr size_t kDeltasFirst = kHeaderSize, kDeltasCount = kHeaderSize + 4, kDeltasTargets = kHeaderSize + 6,
                 kDeltasAttributes = kHeaderSize + 7, kDeltasScales = kHeaderSize + 8;
// Offsets in a MORPH_ANIMATION packet (header included, spec 22.2).
constexpr size_t kMorphIndex = kHeaderSize, kMorphCount = kHeaderSize + 2, kMorphTrack = kHeaderSize + 4,
                 kMorphTrackCount = kHeaderSize + 6, kMorphNode = kHeaderSize + 8, kMorphJoins = kHeaderSize + 10,
                 kMorphTargets = kHeaderSize + 12, kMorphInterpolation = kHeaderSize + 13,
                 kMorphKeys = kHeaderSize + 14, kMorphKeyCount = kHeaderSize + 16, kMorphFirstKey = kHeaderSize + 20,
                 kMorphNameLength = kHeaderSize + 24, kMorphReserved = kHeaderSize + 25, kMorphName = kHeaderSize + 26;

void morph_vectors(Writer& w) {
    const SceneDescription scene = morphing_face();
    const MorphStream base = make_morph_stream(scene);
    const Packets anims = base.animations();         // Talk's translation
    const Packets morphs = base.morph_animations();  // morph 0 track 0 keys 0..19, 20..23; morph 0 track 1; morph 1
    const Packets& deltas = base.deltas;             // points 0..17, 18..19
    const MorphDeltasRun records = all_deltas(deltas);
    // Points a MORPH_DELTAS packet carries, as "A..B".
    auto points_of = [](const Packet& p) {
        const MorphDeltasRun run = deltas_run_of(p);
        return std::to_string(run.first_index) +
               (run.count > 1 ? ".." + std::to_string(run.first_index + run.count - 1) : std::string());
    };
    const uint32_t n0 = deltas_run_of(deltas[0]).count;  // points of the first MORPH_DELTAS packet
    if (anims.size() != 1 || morphs.size() != 4 || deltas.size() != 2 || records.count != 20 || n0 != 18) {
        std::cerr << "make_vectors: the morphing face takes " << anims.size() << " ANIMATION, " << morphs.size()
                  << " MORPH_ANIMATION and " << deltas.size() << " MORPH_DELTAS packets, not 1, 4 and 2\n";
        std::exit(1);
    }
    const Packets stream = base.all();
    const Packets geometry = base.geometry.all();
    const size_t scene_at = geometry.size(), anim_at = scene_at + base.scene.scene.size(), morph_at = anim_at + 1,
                 deltas_at = morph_at + morphs.size();
    const std::string face =
        "the morphing face of valid/morph (format 1.6: mesh 0 'Face' of object 0 with 2 targets, default weights "
        "0.25 and 0, shown by nodes 1 'Face' and 3 'Mirror'; mesh 1 'Box' of object 1 without targets; the "
        "displacements of object 0's 20 points in 2 MORPH_DELTAS packets; animation 0 'Talk' joined by morph "
        "animation 0 (tracks on nodes 1 and 3), and morph animation 1 'Blink' standing alone), packets in stream order";
    w.write("valid", "morph",
            "format 1.6 (spec 22): the morphing face: objects 0 (6 ellipsoids, 20 points with normals) and 1 (4 "
            "ellipsoids, 12 points with normals), packet size 300; nodes 0 'Stage' (root), 1 'Face' and 3 'Mirror' "
            "(mesh 0), 2 'Box' (mesh 1); mesh 0 'Face' of object 0 whose record carries 2 targets with default "
            "weights 0.25, 0 (its SCENE packet says 1.6), mesh 1 'Box' of object 1 without targets; object 0's "
            "displacement records (position and normal of both targets: 4 slots quantized to i16 against 4 scales, "
            "the vectors 0, 0, 0 left out, spec 22.1) in 2 MORPH_DELTAS packets (points 0..17, 18..19); animation 0 "
            "'Talk' (a LINEAR translation of node 1, one ANIMATION packet) joined by morph animation 0 (empty name: "
            "a LINEAR track of 24 keys on node 1 in 2 packets, a STEP track of 3 keys on node 3), and morph animation "
            "1 'Blink' (a LINEAR track of 3 keys on node 1), which stands alone; packets in stream order; mesh 0 "
            "shown with its targets, Talk shown with its track and both morph tracks, Blink written after it",
            stream);

    // ---- unusual ----
    {
        Packets sent = stream;
        bool found = false;
        for (size_t i = scene_at; i < anim_at; ++i) {
            SceneBatch batch;
            if (decode_scene_payload(payload_of(sent[i]), batch, sent[i][5]) != Error::Ok) std::exit(1);
            if (std::none_of(batch.meshes.begin(), batch.meshes.end(), [](const SceneMesh& m) { return m.index == 0; }))
                continue;
            sent[i] = with_payload(sent[i], append_to_record(payload_of(sent[i]), 2, 0, {0xE1, 0xE2, 0xE3, 0xE4}));
            sent[i][5] = 7;
            reseal(sent[i]);
            found = true;
        }
        if (!found) std::exit(1);
        w.write("unusual", "morph_newer_minor",
                face + ", with the SCENE packet that holds mesh 0's record saying 1.7 and 4 bytes E1 E2 E3 E4 after "
                       "that record's default weights: fields of a later version, ignored (spec 15.1: 'ignores bytes "
                       "after the fields it knows at the end of a record body'; spec 9: a newer minor is decoded as "
                       "far as it is known); decodes as valid/morph but for newest_minor 7",
                sent);
    }
    {
        Packets sent = geometry;
        sent.push_back(one_mesh_scene_packet(scene, scene.meshes[1], target_field({1.0f, 0.0f}), kSkinMinor, 1000));
        sent.insert(sent.end(), stream.begin() + long(scene_at), stream.end());
        w.write("unusual", "morph_trailing_bytes_1_5",
                face + ", with, before its SCENE packet, a SCENE packet saying 1.5 (sequence 1000) of mesh 1's "
                       "record followed by the 9 bytes 02 0000803F 00000000 (what a target field of 2 targets, "
                       "weights 1 and 0, would be): in a packet that says 1.5 they are fields of a later version, "
                       "ignored, not targets (spec 22: 'A decoder reads the field only in a SCENE packet that says "
                       "version 1.6 or later'), so mesh 1 has no targets, and the stream's SCENE packet, whose mesh 1 "
                       "record has no field, agrees with it; decodes as valid/morph",
                sent);
    }
    {
        Packets sent = morphs;
        sent.insert(sent.end(), deltas.begin(), deltas.end());
        sent.insert(sent.end(), stream.begin(), stream.begin() + long(morph_at));
        w.write("unusual", "morph_before_stream_info",
                face + ", with its 4 MORPH_ANIMATION and 2 MORPH_DELTAS packets first, before the STREAM_INFO, the "
                       "SCENE and the ANIMATION packets: the MORPH_ANIMATION packets are stream-level and accepted "
                       "when they arrive (spec 22), the MORPH_DELTAS packets held like POINTS packets (spec 22.1, "
                       "11.2) and released in arrival order when the STREAM_INFO arrives, then accepted; decodes as "
                       "valid/morph",
                sent);
    }
    {
        Packets sent = geometry;
        Packets rest(stream.begin() + long(scene_at), stream.end());
        Rng rng(89);
        for (size_t i = rest.size(); i > 1; --i) std::swap(rest[i - 1], rest[rng.below(i)]);
        for (size_t i = 0; i < rest.size(); ++i) {
            sent.push_back(rest[i]);
            if (i == 1) sent.push_back(rest[i]);
            if (i == 3) {
                Packet again = rest[0];
                restamp_packet(again, 900);
                sent.push_back(again);
            }
        }
        Packet again = morphs[1];
        restamp_packet(again, 901);
        sent.push_back(again);
        again = deltas[1];
        restamp_packet(again, 902);
        sent.push_back(again);
        w.write("unusual", "morph_shuffled_duplicates",
                face + ", with its SCENE, ANIMATION, MORPH_ANIMATION and MORPH_DELTAS packets shuffled after the "
                       "geometry (seeded), the second of them sent twice (byte-identical), the first again after the "
                       "fourth with sequence number 900, and the second MORPH_ANIMATION packet and the second "
                       "MORPH_DELTAS packet again at the end (sequence 901, 902): 4 duplicates (spec 22.1, 22.2: "
                       "nothing new); decodes as valid/morph",
                sent);
    }
    {
        const MorphStream normals = make_morph_stream(scene, 2, kMorphNormal);
        if (normals.deltas.size() != 1) std::exit(1);
        w.write("unusual", "morph_normal_only",
                "the morphing face of valid/morph with displacement records of normals only (attributes 2, spec "
                "22.1: 2 slots, 2 scales, a mask of one byte a point; the points of x <= 0 have no normal "
                "displacement, their records the mask 00 alone): the normal displacements of valid/morph, all 20 "
                "points in one MORPH_DELTAS packet; mesh 0 is shown with its targets, its position displacements 0 "
                "('a displacement the record lacks is 0', spec 22.4)",
                normals.all());
    }
    {
        SceneDescription s = scene;
        SceneAnimation::Track& blink = s.animations[1].tracks[0];
        blink.interpolation = Interpolation::CubicSpline;
        // Per key: the in-tangents, the values, the out-tangents of both weights.
        blink.values = {0, 0, 0, 0, 0, 4, 0, 0, 0, 1, 0, 0, 0, -4, 0, 0, 0, 0};
        w.write("unusual", "morph_cubicspline",
                "the morphing face of valid/morph with Blink's track CUBICSPLINE (V = 3C = 6: the in-tangents, the "
                "values and the out-tangents of both weights per key, spec 22.2; 3 keys, one packet of 26 + 5 + 3 x "
                "28 bytes of payload); complete, usable and shown as in valid/morph",
                make_morph_stream(s).all());
    }
    w.write("unusual", "morph_weights_only",
            "the morphing face of valid/morph without Talk's translation track: an asset whose animations move "
            "weights only. No ANIMATION packet; morph animation 0 'Talk' (its name sent: it joins nothing) and "
            "morph animation 1 'Blink' both stand alone (joins FFFF) and are written after the (empty) ANIMATION "
            "table in morph animation order (spec 22.4); every morph track kept",
            make_morph_stream(morphing_face(false)).all());
    {
        Packets sent = stream;
        // Morph animation 0's STEP track (node 3): weights 1, 0, 0, 1, 0.5, 0.5, the time of key 0 0.
        AnimationPiece echo = morph_piece_of(morphs[2]);
        size_t zeros = 0;
        for (float& v : echo.values)
            if (v == 0.0f) v = -0.0f, ++zeros;
        echo.times[0] = -0.0f;
        if (zeros < 2) std::exit(1);
        sent.push_back(morph_animation_packet(echo, 1000));
        sent.push_back(one_mesh_scene_packet(scene, scene.meshes[0], target_field({0.25f, -0.0f}), kMorphMinor, 1001));
        w.write("unusual", "morph_negative_zero",
                face + ", then (sequence 1000, 1001) the packet of morph animation 0's track 1 with -0 for its +0 "
                       "weights and for the time of key 0, and a SCENE packet (1.6) of mesh 0's record with default "
                       "weights 0.25 and -0: two duplicates, not mismatches (spec 22.2, 22: values compare as "
                       "numbers, +0 and -0 agree), and not malformed (a time of -0 is not negative). (A MORPH_DELTAS "
                       "record holds integers, which have no -0: spec 22.1, q = 0 gives +0; see "
                       "unusual/morph_deltas_explicit_zero.)",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t i = morph_at; i < deltas_at; ++i) {
            sent[i][kMorphReserved] = 0xA5;
            reseal(sent[i]);
        }
        Packet again = morphs[0];
        again[kMorphReserved] = 0x5A;
        reseal(again);
        restamp_packet(again, 1000);
        sent.push_back(again);
        w.write("unusual", "morph_reserved",
                face + ", with the reserved byte (payload offset 25) of every MORPH_ANIMATION packet A5 (resealed), "
                       "then the first one again (sequence 1000) with 5A there: ignored when reading (spec 22.2), so "
                       "the repeat is a duplicate; decodes as valid/morph",
                sent);
    }
    {
        // Runs cut as no sender cuts (5 points each: well within the packet size).
        Packets sent = base.before_deltas();
        uint32_t sequence = 1000;
        for (auto [first, count] : std::vector<std::pair<uint32_t, uint16_t>>{
                 {3, 5}, {0, 5}, {8, 5}, {13, 5}, {15, 5}, {5, 5}})
            sent.push_back(deltas_packet(0, sequence++, deltas_payload(deltas_run(records, first, count))));
        w.write("unusual", "morph_overlapping_runs",
                face + ", with object 0's records in 6 MORPH_DELTAS packets that overlap, cut as no sender cuts "
                       "(sequence 1000..1005, each with the object's 4 scales): points 3..7, 0..4 (accepted: it "
                       "brings 0..2; its records of 3 and 4 are compared with those held and agree), 8..12, 13..17, "
                       "15..19 (accepted: it brings 18 and 19), then 5..9 (a duplicate: every record held); spec 22.1 "
                       "keeps one record per point, whatever packets carried it; decodes as valid/morph",
                sent);
    }
    {
        Packets sent = geometry;
        sent.push_back(one_mesh_scene_packet(scene, scene.meshes[1], {0x00}, kMorphMinor, 1000));
        sent.insert(sent.end(), stream.begin() + long(scene_at), stream.end());
        w.write("unusual", "morph_mesh_target_count_0",
                face + ", with, before its SCENE packet, a SCENE packet (1.6, sequence 1000) of mesh 1's record "
                       "carrying an explicit target field of target_count 0 (one byte 00, no weight): a record with "
                       "0 targets, which compares equal to the stream's mesh 1 record without the field (spec 22: 'a "
                       "record without the field comparing as 0 targets'); decodes as valid/morph",
                sent);
    }
    {
        // Morph animation 0's two tracks split into two morph animations that both join Talk.
        Packets sent(stream.begin(), stream.begin() + long(morph_at));
        for (size_t i = 0; i < morphs.size(); ++i) {
            AnimationPiece piece = morph_piece_of(morphs[i]);
            piece.animation_count = 3;
            if (piece.animation == 0) {
                piece.track_count = 1;
                if (piece.track == 1) piece.animation = 2, piece.track = 0;
            }
            sent.push_back(morph_animation_packet(piece, get32(morphs[i], 12)));
        }
        sent.insert(sent.end(), deltas.begin(), deltas.end());
        w.write("unusual", "morph_two_join_one",
                face + ", with morph animation 0's two tracks sent as two morph animations that both join Talk "
                       "(animation_count 3 in every MORPH_ANIMATION packet): morph animation 0 with the track of node "
                       "1, morph animation 2 with the track of node 3 (each track_count 1, joins 0, an empty name), "
                       "and Blink as morph animation 1: Talk is shown once every morph animation of the table has "
                       "taken a packet and both that join it are complete, with its track and the morph tracks of "
                       "morph animations 0 then 2 (spec 22.4: 'taken in morph animation order, then track order')",
                sent);
    }

    {
        // The first MORPH_DELTAS packet's records with every vector 0, 0, 0 written out (each mask 0F), cut
        // into packets within the packet size.
        const MorphDeltasRun run = deltas_run_of(deltas[0]);
        const uint32_t half = (run.count + 1) / 2;
        const auto all_set = [](size_t, size_t) { return true; };
        Packets sent(stream.begin(), stream.begin() + long(deltas_at));
        sent.push_back(deltas_packet(0, get32(deltas[0], 12), deltas_payload(deltas_run(records, 0, uint16_t(half)), all_set)));
        sent.push_back(deltas_packet(0, 1000, deltas_payload(deltas_run(records, half, uint16_t(run.count - half)), all_set)));
        sent.insert(sent.end(), stream.begin() + long(deltas_at) + 1, stream.end());
        Packet again = deltas[0];
        restamp_packet(again, 1001);
        sent.push_back(again);
        for (const Packet& p : sent)
            if (p.size() > 300) std::exit(1);
        w.write("unusual", "morph_deltas_explicit_zero",
                face + ", with the records of its first MORPH_DELTAS packet (points 0.." + std::to_string(n0 - 1) +
                       ") sent instead in 2 packets (points 0.." + std::to_string(half - 1) + " with the first's "
                       "sequence number, " + std::to_string(half) + ".." + std::to_string(n0 - 1) +
                       " with 1000) that write every vector 0, 0, 0 out: each record's mask 0F (all 4 slots set), "
                       "a slot the reference leaves out (target 1's normal displacement; target 0's for the points "
                       "of x <= 0) carried as 0, 0, 0; then the reference's first packet (sequence 1001) after the "
                       "stream: the same records (spec 22.1: 'a clear bit and a set bit with 0, 0, 0 are "
                       "identical'), so a duplicate, not a mismatch; decodes as valid/morph",
                sent);
    }
    {
        // Point 0's target 1 position displacement (slot 2) -32768, 32767, -1.
        MorphDeltasRun run = deltas_run_of(deltas[0]);
        if (deltas_slots(run) != 4) std::exit(1);
        run.values[2 * 3 + 0] = -32768;
        run.values[2 * 3 + 1] = 32767;
        run.values[2 * 3 + 2] = -1;
        Packets sent = stream;
        sent[deltas_at] = with_payload(deltas[0], deltas_payload(run));
        w.write("unusual", "morph_deltas_i16_extremes",
                face + ", with point 0's target 1 position displacement (slot 2) in the first MORPH_DELTAS packet "
                       "(re-encoded, the same size) the integers -32768, 32767, -1 (bytes 0080 FF7F FFFF): i16 "
                       "two's complement, -32768 included though the reference encoder writes none below -32767; "
                       "dequantized q * scale[2] in f32 (spec 22.1): -32768 s, 32767 s, -s with s = scale[2]; a "
                       "stream that conforms; decodes as valid/morph but for point 0's record",
                sent);
    }
    {
        // Slot 3 (target 1's normal displacement, 0 everywhere) with the scale 2^-149 (00000001, the
        // smallest subnormal) in both packets, and point 19's slot 3 the integers 1, -2, 32767.
        Packets sent = stream;
        for (size_t i = 0; i < deltas.size(); ++i) {
            MorphDeltasRun run = deltas_run_of(deltas[i]);
            uint32_t bits = 1;
            std::memcpy(&run.scales[3], &bits, 4);
            if (i + 1 == deltas.size()) {
                int16_t* v = run.values.data() + ((19 - run.first_index) * 4 + 3) * 3;
                v[0] = 1;
                v[1] = -2;
                v[2] = 32767;
            }
            sent[deltas_at + i] = with_payload(deltas[i], deltas_payload(run));
            if (sent[deltas_at + i].size() > 300) std::exit(1);
        }
        w.write("unusual", "morph_deltas_scale_subnormal",
                face + ", with the scale of slot 3 (target 1's normal displacement) 2^-149 (00000001, the smallest "
                       "subnormal f32) where the reference writes 1, in both MORPH_DELTAS packets (re-encoded), and "
                       "point 19's slot 3 the integers 1, -2, 32767: a subnormal scale is finite and above 0 (spec "
                       "22.1), and the products 2^-149, -2^-148 and 32767 x 2^-149 are subnormal f32 values, exact; "
                       "a stream that conforms; decodes as valid/morph but for the scales and point 19's record",
                sent);
    }
    for (const uint8_t targets : {uint8_t(4), uint8_t(5)}) {
        // Mesh 0 with `targets` targets (default weights and morph keys padded with 0) and object 0's records
        // of as many targets: S = 8 slots (a mask of one full byte) or 10 (masks of 2 bytes).
        const MorphStream m = make_morph_stream(morphing_face_with_targets(targets), targets, 3);
        std::string runs;
        for (const Packet& p : m.deltas) runs += (runs.empty() ? "" : ", ") + points_of(p);
        const bool eight = targets == 4;
        w.write("unusual", eight ? "morph_deltas_8_slots" : "morph_deltas_10_slots",
                "the morphing face of valid/morph with " + std::to_string(targets) + " targets: mesh 0's default "
                "weights 0.25, 0, 0, 0" + (eight ? "" : ", 0") + " and every morph track's keys with " +
                std::to_string(targets) + " weights (those of valid/morph, then 0), and object 0's records of " +
                std::to_string(targets) + " targets, position and normal (target 2 moves every point 0.05 along z; "
                "target 3 moves the points of y > 0 by (0.04, 0, 0) and tilts their normals by (0, -0.1 y, 0)" +
                (eight ? "" : "; target 4 moves the points of z > 0 by (0, 0, 0.03 z) and tilts their normals by "
                              "(0.05, 0.05, 0)") + "): S = " + std::to_string(2 * targets) + " slots, " +
                (eight ? "a multiple of 8: a mask of one full byte, bit 7 (slot 7, target 3's normal displacement) "
                         "set for the points of y > 0"
                       : "masks of 2 bytes (slot k is bit k mod 8 of byte floor(k / 8)): slots 8 and 9 (target 4) "
                         "in bits 0 and 1 of the second byte, set for the points of z > 0, its bits 2..7 0") +
                " (spec 22.1), " + std::to_string(m.deltas.size()) + " MORPH_DELTAS packets (points " + runs +
                "); mesh 0 shown with its targets and every morph track kept",
                m.all());
    }

    // ---- faulty: no rejection, but the stream is not complete or does not conform (spec 22.4) ----
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(deltas_at) + 1);
        w.write("faulty", "morph_deltas_incomplete",
                face + ", without the second MORPH_DELTAS packet (points " + points_of(deltas[1]) +
                       "): no rejection; object 0 is morphed "
                       "(a held point with its record), so mesh 0 is shown with its targets (spec 22.3: each vertex "
                       "gets the record of the nearest held point with one), but the stream is not complete ('every "
                       "point of every object shown by a mesh whose record carries target_count > 0 has its "
                       "displacement record')",
                sent);
    }
    w.write("faulty", "morph_deltas_lost",
            face + ", without any MORPH_DELTAS packet: no rejection; object 0 is not morphed, so mesh 0 is shown in "
                   "its base shape (spec 22.4), every morph track is left out ('whose mesh is not shown with its "
                   "targets'): Talk shown with its own track only, Blink not written (no track kept); the stream is "
                   "not complete",
            base.before_deltas());
    {
        Packets sent;
        for (const Packet& p : stream)
            if (!(p[6] == uint8_t(PacketType::Points) && get16(p, 16) == 0)) sent.push_back(p);
        w.write("faulty", "morph_points_lost",
                face + ", without object 0's POINTS packets: no rejection; object 0 has arrived (its ellipsoids) and "
                       "every displacement record is held, but no point: it is not morphed (spec 22.3: 'when the "
                       "receiver holds at least one of its points together with that point's displacement record'), "
                       "so mesh 0 is shown in its base shape and every morph track is left out, as in "
                       "faulty/morph_deltas_lost; the stream is not complete",
                sent);
    }
    {
        const MorphStream three = make_morph_stream(scene, 3, 3);
        Packets sent = base.before_deltas();
        sent.insert(sent.end(), three.deltas.begin(), three.deltas.end());
        std::string runs;
        for (const Packet& p : three.deltas) runs += (runs.empty() ? "" : ", ") + points_of(p);
        w.write("faulty", "morph_target_count_differs",
                face + ", with object 0's MORPH_DELTAS packets of 3 targets (a third target moving every point 0.05 "
                       "along z, its normal 0: S = 6 slots; " + std::to_string(three.deltas.size()) +
                       " packets, points " + runs + ") where mesh 0's record carries 2: no rejection; object 0 "
                       "is morphed with 3 targets, so mesh 0 is not shown with its targets ('every object it shows is "
                       "morphed with that target_count') and the morph tracks (C = 2) are left out; the stream does not "
                       "conform ('every object shown by a mesh with target_count > 0 has MORPH_DELTAS packets with "
                       "that target_count')",
                sent);
    }
    {
        Packets sent = stream;
        std::vector<float> values;
        for (uint32_t i = 0; i < 12; ++i)
            for (float v : {0.0f, 0.05f, 0.0f, 0.0f, -0.05f, 0.0f}) values.push_back(v);
        Packets box;
        if (packetize_morph_deltas(base.geometry.info, 1, 2, kMorphPosition, values, kStreamId, 1000, box) != Error::Ok)
            std::exit(1);
        sent.insert(sent.end(), box.begin(), box.end());
        w.write("faulty", "morph_deltas_unshown_object",
                face + ", with MORPH_DELTAS packets of object 1 too (2 targets, positions only, every point moved "
                       "0.05 up by target 0 and down by target 1; sequence 1000 on), whose mesh 1 record carries no "
                       "targets: no rejection; object 1 holds its records, mesh 1 is shown as before (no targets); "
                       "the stream does not conform ('an object with MORPH_DELTAS packets is shown by a mesh whose "
                       "record carries its target_count')",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(morph_at) + 1);
        w.write("faulty", "morph_animation_incomplete",
                face + ", without the second packet of morph animation 0's track 0 (keys 20..23): no rejection; morph "
                       "animation 0 is not complete and not shown, and Talk, which it joins, is not shown either "
                       "(spec 22.4: 'an animation of A that it joins is not shown either: a receiver MUST NOT play "
                       "part of one'); Blink shown; the stream is not complete",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(morph_at) + 3);
        w.write("faulty", "morph_animation_lost",
                face + ", without Blink's MORPH_ANIMATION packet: no rejection; the morph table (animation_count 2) "
                       "has morph animation 1 without a packet, so a receiver cannot know whether it joins Talk: Talk "
                       "is not shown (spec 22.4: 'shown only when, besides, every morph animation of the morph table "
                       "has taken a packet'); nothing is shown; the stream is not complete",
                sent);
    }
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(anim_at));
        w.write("faulty", "morph_joined_animation_lost",
                face + ", without Talk's ANIMATION packet: no rejection; morph animation 0 is complete and joins "
                       "animation 0, which never arrives (no ANIMATION packet at all, animation_count null): its "
                       "tracks are not shown (spec 22.4: 'if j is not below the ANIMATION animation_count or j never "
                       "arrives, they are not shown'); Blink shown; the stream does not conform ('every joins that is "
                       "not 0xFFFF is below the ANIMATION animation_count')",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t i = morph_at; i < morph_at + 3; ++i) {
            put16(sent[i], kMorphJoins, 1);
            reseal(sent[i]);
        }
        w.write("faulty", "morph_joins_past_table",
                face + ", with morph animation 0's 3 packets saying joins 1 where the ANIMATION animation_count is 1 "
                       "(resealed): no rejection (spec 22.2 does not check joins against the ANIMATION table); its "
                       "tracks are not shown, Talk is shown with its own track (no morph animation joins it), Blink "
                       "as before; the stream does not conform",
                sent);
    }
    auto blink_edited = [&](const std::function<void(Packet&)>& edit) {
        Packets sent = stream;
        edit(sent[morph_at + 3]);
        reseal(sent[morph_at + 3]);
        return sent;
    };
    w.write("faulty", "morph_track_node_past_table",
            face + ", with Blink's track on node 4 in a table of 4 nodes (resealed): no rejection (spec 22.2 does not "
                   "check node against the SCENE table); the track is left out (its node is not shown, spec 22.4) and "
                   "Blink, left without a track, is not written; the stream does not conform ('its node is below the "
                   "SCENE node_count, has a node record')",
            blink_edited([](Packet& p) { put16(p, kMorphNode, 4); }));
    w.write("faulty", "morph_track_node_without_mesh",
            face + ", with Blink's track on node 0 'Stage', which has no mesh (resealed): no rejection; the track is "
                   "left out ('has no mesh', spec 22.4), Blink not written; the stream does not conform ('names a mesh "
                   "whose target_count is the track's C')",
            blink_edited([](Packet& p) { put16(p, kMorphNode, 0); }));
    w.write("faulty", "morph_track_mesh_without_targets",
            face + ", with Blink's track on node 2 'Box', whose mesh 1 has no targets (resealed): no rejection; the "
                   "track is left out ('whose mesh is not shown with its targets'), Blink not written; the stream "
                   "does not conform",
            blink_edited([](Packet& p) { put16(p, kMorphNode, 2); }));
    {
        AnimationPiece piece = morph_piece_of(morphs[3]);
        piece.info.targets = 3;
        std::vector<float> values;
        for (size_t k = 0; k < piece.times.size(); ++k) {
            values.push_back(piece.values[2 * k]);
            values.push_back(piece.values[2 * k + 1]);
            values.push_back(0.5f);
        }
        piece.values = values;
        Packets sent = stream;
        sent[morph_at + 3] = morph_animation_packet(piece, get32(morphs[3], 12));
        w.write("faulty", "morph_track_target_count_differs",
                face + ", with Blink's track carrying 3 weights a key (target_count 3, a third weight 0.5; re-encoded) "
                       "where node 1's mesh has 2 targets: no rejection; the track is left out ('has another "
                       "target_count than the track's C'), Blink not written; the stream does not conform",
                sent);
    }
    {
        Packets sent = stream;
        Packet& p = sent[morph_at + 1];  // keys 20..23, after key 19 at time 2.375
        for (int k = 0; k < 4; ++k) put_f32(p, kMorphName + 12 * size_t(k), 0.25f + 0.125f * float(k));
        reseal(p);
        w.write("faulty", "morph_track_unusable",
                face + ", with the times of keys 20..23 of morph animation 0's track 0, in its second packet "
                       "(resealed), 0.25, 0.375, 0.5, 0.625: increasing within the packet, before key 19's 2.375: no "
                       "rejection; the track is complete and not usable, left out (spec 22.4): Talk shown with its "
                       "track and morph animation 0's track 1 only; the stream does not conform",
                sent);
    }
    {
        SceneDescription s = scene;
        s.animations[0].tracks.push_back({1, AnimationPath::Weights, Interpolation::Linear, 2, {0, 1}, {1, 1, 0, 0}});
        w.write("faulty", "morph_duplicate_node",
                "the morphing face of valid/morph with a third track in morph animation 0 (joining Talk): track 2, a "
                "LINEAR track of 2 keys on node 1, the node of its track 0: no rejection; track 2 is left out (spec "
                "22.4: 'a morph track with the same node as a track kept before it in the same written animation'); "
                "Talk shown with morph tracks (0, 0) and (0, 1); the stream does not conform",
                make_morph_stream(s).all());
    }
    {
        // A morph animation 2 joining Talk too, with a track on node 1.
        Packets sent(stream.begin(), stream.begin() + long(morph_at));
        for (size_t i = 0; i < morphs.size(); ++i) {
            AnimationPiece piece = morph_piece_of(morphs[i]);
            piece.animation_count = 3;
            sent.push_back(morph_animation_packet(piece, get32(morphs[i], 12)));
        }
        AnimationPiece extra = morph_piece_of(morphs[2]);  // node 3's STEP track, 3 keys
        extra.animation = 2;
        extra.animation_count = 3;
        extra.track = 0;
        extra.track_count = 1;
        extra.info.node = 1;
        sent.push_back(morph_animation_packet(extra, 1000));
        sent.insert(sent.end(), deltas.begin(), deltas.end());
        w.write("faulty", "morph_duplicate_node_across_joined",
                face + ", with a morph animation 2 that joins Talk too (animation_count 3 in every MORPH_ANIMATION "
                       "packet; sequence 1000, after the others): one STEP track of 3 keys on node 1, which morph "
                       "animation 0's track 0 moves: no rejection; Talk's morph tracks are taken in morph animation "
                       "order, then track order (spec 22.4), so morph animation 2's track is left out: Talk shown with "
                       "morph tracks (0, 0) and (0, 1); the stream does not conform ('no two morph tracks written into "
                       "one animation have the same node')",
                sent);
    }
    {
        AnimationPiece piece = morph_piece_of(morphs[3]);
        piece.name = std::string("Bl\xFFink");
        Packets sent = stream;
        sent[morph_at + 3] = morph_animation_packet(piece, get32(morphs[3], 12));
        w.write("faulty", "morph_name_not_utf8",
                face + ", with Blink named with the bytes 'Bl FF ink' (re-encoded): no rejection; the name shown as "
                       "'Bl\\uFFFDink' (spec 22.2 by 15); Blink written with its track; the stream does not conform",
                sent);
    }

    // ---- faulty: the mesh record's target field (spec 22, 15.1). A SCENE packet of mesh 0's record
    // (sequence 1000) after the stream; everything else decodes as in valid/morph. ----
    auto after_stream = [&](Packet copy) {
        restamp_packet(copy, 1000);  // reseals
        Packets sent = stream;
        sent.push_back(copy);
        return sent;
    };
    const std::string kMesh = face + ", then a SCENE packet (sequence 1000) of mesh 0's record ";
    w.write("faulty", "morph_mesh_weights_short",
            kMesh + "(1.6) whose target field says 2 targets and holds one weight (0.25): the body ends before the "
                    "weights it must hold: rejected, malformed payload (spec 22: 'then 4 * target_count bytes of "
                    "weights MUST follow')",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0], target_field({0.25f}, 2), kMorphMinor, 1000)));
    w.write("faulty", "morph_mesh_weight_infinite",
            kMesh + "(1.6) with default weights 0.25 and +infinity: rejected, malformed payload (spec 22: 'a weight "
                    "that is not finite makes the payload malformed')",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0],
                                               target_field({0.25f, std::numeric_limits<float>::infinity()}),
                                               kMorphMinor, 1000)));
    w.write("faulty", "morph_mesh_target_count_contradicts",
            kMesh + "(1.6) with 3 targets (default weights 0.25, 0, 0) where it has 2: rejected, stream mismatch "
                    "(spec 22: 'a 1.6 decoder compares it like the record's other fields: the target_count as a "
                    "value')",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0], target_field({0.25f, 0, 0}), kMorphMinor, 1000)));
    w.write("faulty", "morph_mesh_weight_contradicts",
            kMesh + "(1.6) with default weights 0.5 and 0 where they are 0.25 and 0: rejected, stream mismatch (spec "
                    "22: the weights compared as numbers)",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0], target_field({0.5f, 0}), kMorphMinor, 1000)));
    w.write("faulty", "morph_mesh_targets_dropped",
            kMesh + "without the target field, saying 1.1, as a 1.5 encoder writes it: rejected, stream mismatch "
                    "(spec 22: 'a record without the field comparing as 0 targets', and mesh 0's record carries 2)",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0], {}, kFormatMinor, 1000)));
    w.write("faulty", "morph_mesh_targets_in_1_5_packet",
            kMesh + "with the target field of valid/morph (2 targets, 0.25 and 0) in a packet that says 1.5: the "
                    "decoder does not read it (spec 22: 'only in a SCENE packet that says version 1.6 or later'), so "
                    "the record has 0 targets and contradicts mesh 0's 2: rejected, stream mismatch",
            after_stream(one_mesh_scene_packet(scene, scene.meshes[0], target_field({0.25f, 0}), kSkinMinor, 1000)));

    // ---- faulty: MORPH_DELTAS rejections. A copy of the first MORPH_DELTAS packet (points 0..n0 - 1) with
    // one defect, sequence 1000, after the stream (resealed; a payload of another length gets its
    // payload_length and checksum), unless the row says otherwise. Its payload: the header, the 4 scales
    // (slot 0: target 0's position displacement, 1: target 0's normal, 2: target 1's position, 3: target
    // 1's normal, all 0 so its scale 1), then the records, each a mask byte and 6 bytes per set bit. ----
    const Packet& first_deltas = deltas[0];
    const std::vector<uint8_t> first_payload = payload_of(first_deltas);
    const std::string first_points = points_of(first_deltas);
    const std::string kDeltasCopy = face + ", then a copy of the first MORPH_DELTAS packet (points " + first_points + ") ";
    auto deltas_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet copy = first_deltas;
        edit(copy);
        reseal(copy);
        return after_stream(copy);
    };
    auto deltas_cut = [&](size_t length, const std::function<void(std::vector<uint8_t>&)>& edit) {
        std::vector<uint8_t> payload = first_payload;
        payload.resize(length);
        edit(payload);
        return after_stream(with_payload(first_deltas, payload));
    };
    auto scale_at = [](size_t k) { return kDeltasScales + 4 * k; };  // slot k's scale in the packet
    {
        std::vector<uint8_t> payload = first_payload;
        payload.resize(7);
        w.write("faulty", "morph_deltas_payload_short",
                kDeltasCopy + "cut to a payload of 7 bytes: rejected, malformed payload (spec 22.1: 'shorter than 8 "
                              "bytes')",
                after_stream(with_payload(first_deltas, payload)));
    }
    w.write("faulty", "morph_deltas_count_zero",
            kDeltasCopy + "with count 0, its 4 scales and no record (a payload of 24 bytes = 8 + 4 S: nothing else is "
                          "wrong): rejected, malformed payload (spec 22.1: 'count is 0')",
            deltas_cut(24, [](std::vector<uint8_t>& p) { p[4] = p[5] = 0; }));
    w.write("faulty", "morph_deltas_target_count_zero",
            kDeltasCopy + "with target_count 0, no scale and no record (an 8-byte payload: with S = 0 there is no "
                          "scale and a record is 0 bytes, so nothing else is wrong): rejected, malformed payload (spec "
                          "22.1: 'target_count is 0')",
            deltas_cut(8, [](std::vector<uint8_t>& p) { p[6] = 0; }));
    w.write("faulty", "morph_deltas_attributes_zero",
            kDeltasCopy + "with attributes 0, no scale and no record (an 8-byte payload: a = 0, S = 0): rejected, "
                          "malformed payload (spec 22.1: 'attributes is 0')",
            deltas_cut(8, [](std::vector<uint8_t>& p) { p[7] = 0; }));
    w.write("faulty", "morph_deltas_attributes_bit_6",
            kDeltasCopy + "with attributes 43 (bits 0, 1 and 6; bits 0 and 1 give S = 4, the scales and records as "
                          "they were): rejected, malformed payload (spec 22.1: 'has a bit of 2..7 set')",
            deltas_edited([](Packet& p) { p[kDeltasAttributes] = 0x43; }));
    w.write("faulty", "morph_deltas_scales_short",
            kDeltasCopy + "cut to a payload of 20 bytes: the header and 3 of its 4 scales: rejected, malformed payload "
                          "(spec 22.1: 'it is shorter than 8 + 4 S')",
            deltas_cut(20, [](std::vector<uint8_t>&) {}));
    w.write("faulty", "morph_deltas_scale_zero",
            kDeltasCopy + "with the scale of slot 0 (target 0's position displacement) +0 (00000000): rejected, "
                          "malformed payload (spec 22.1: 'a scale is not finite or not above 0')",
            deltas_edited([&](Packet& p) { put32(p, scale_at(0), 0x00000000u); }));
    w.write("faulty", "morph_deltas_scale_negative_zero",
            kDeltasCopy + "with the scale of slot 0 -0 (80000000; -0 is not above 0): rejected, malformed payload "
                          "(spec 22.1: 'a scale is not finite or not above 0')",
            deltas_edited([&](Packet& p) { put32(p, scale_at(0), 0x80000000u); }));
    w.write("faulty", "morph_deltas_scale_negative",
            kDeltasCopy + "with the scale of slot 0 negated (its sign bit set; the same magnitude): rejected, "
                          "malformed payload (spec 22.1: 'a scale is not finite or not above 0')",
            deltas_edited([&](Packet& p) { p[scale_at(0) + 3] |= 0x80; }));
    w.write("faulty", "morph_deltas_scale_infinite",
            kDeltasCopy + "with the scale of slot 2 (target 1's position displacement) +infinity (7F800000): "
                          "rejected, malformed payload (spec 22.1: 'a scale is not finite')",
            deltas_edited([&](Packet& p) { put32(p, scale_at(2), 0x7F800000u); }));
    w.write("faulty", "morph_deltas_scale_too_large",
            kDeltasCopy + "with the scale of slot 2 (target 1's position displacement) 2^113 (78000000): finite, "
                          "but 32768 times it is not: rejected, malformed payload (spec 22.1: 'a scale ... at or "
                          "above 2^113')",
            deltas_edited([&](Packet& p) { put32(p, scale_at(2), 0x78000000u); }));
    w.write("faulty", "morph_deltas_scale_nan",
            kDeltasCopy + "with the scale of slot 2 (target 1's position displacement) NaN (7FC00000): rejected, "
                          "malformed payload (spec 22.1: 'a scale is not finite')",
            deltas_edited([&](Packet& p) { put32(p, scale_at(2), 0x7FC00000u); }));
    {
        Packet bad = first_deltas;
        put32(bad, scale_at(2), 0x7FC00000u);
        reseal(bad);
        restamp_packet(bad, 1000);
        Packets sent = {bad};
        sent.insert(sent.end(), stream.begin(), stream.end());
        w.write("faulty", "morph_deltas_malformed_before_stream_info",
                "the morphing face of valid/morph with, before its STREAM_INFO, the copy of faulty/morph_deltas_scale_nan "
                "(sequence 1000): rejected when it arrives, malformed payload (spec 22.1: the checks that need no "
                "stream info are made at step 11, before a packet is held, 11.1); nothing held; the rest as in "
                "valid/morph",
                sent);
    }
    const size_t last_record = deltas_record_at(first_payload, n0 - 1);  // payload offset of the last record
    if ((first_payload[last_record] & 0x08) != 0) std::exit(1);
    w.write("faulty", "morph_deltas_record_past_payload",
            kDeltasCopy + "with bit 3 (slot 3, target 1's normal displacement) set in the mask of its last record "
                          "(point " + std::to_string(n0 - 1) + ", payload offset " + std::to_string(last_record) +
                          "), whose vector then needs 6 bytes past the end of the payload: rejected, malformed "
                          "payload (spec 22.1: 'a record runs past the payload')",
            deltas_edited([&](Packet& p) { p[kHeaderSize + last_record] |= 0x08; }));
    w.write("faulty", "morph_deltas_record_cut",
            kDeltasCopy + "with the last 2 bytes of its payload cut (the z of the last vector of point " +
                          std::to_string(n0 - 1) + "'s record): rejected, malformed payload (spec 22.1: 'a record "
                          "runs past the payload')",
            deltas_cut(first_payload.size() - 2, [](std::vector<uint8_t>&) {}));
    w.write("faulty", "morph_deltas_record_missing",
            kDeltasCopy + "saying count " + std::to_string(n0 + 1) + " (points 0.." + std::to_string(n0) +
                          ") with its " + std::to_string(n0) + " records: the mask of point " + std::to_string(n0) +
                          "'s record lies past the end of the payload: rejected, malformed payload (spec 22.1: 'a "
                          "record runs past the payload')",
            deltas_edited([&](Packet& p) { put16(p, kDeltasCount, uint16_t(n0 + 1)); }));
    w.write("faulty", "morph_deltas_mask_bit_past_slots",
            kDeltasCopy + "with bit 4 set in the mask of point 0's record (S = 4: bits 4..7 of the mask byte MUST be "
                          "0; the record's bytes otherwise as they were): rejected, malformed payload (spec 22.1: 'a "
                          "mask bit from S on is set')",
            deltas_edited([&](Packet& p) { p[kHeaderSize + deltas_record_at(first_payload, 0)] |= 0x10; }));
    {
        const MorphStream ten = make_morph_stream(morphing_face_with_targets(5), 5, 3);
        Packet copy = ten.deltas[0];
        const std::vector<uint8_t> payload = payload_of(copy);
        copy[kHeaderSize + deltas_record_at(payload, 0) + 1] |= 0x04;  // bit 10: bit 2 of the second mask byte
        reseal(copy);
        restamp_packet(copy, 1000);
        Packets sent = ten.all();
        sent.push_back(copy);
        w.write("faulty", "morph_deltas_mask_bit_past_slots_second_byte",
                "the stream of unusual/morph_deltas_10_slots (mesh 0 and object 0's records with 5 targets, S = 10 "
                "slots, masks of 2 bytes), then a copy of its first MORPH_DELTAS packet (points " +
                    points_of(ten.deltas[0]) + "; sequence 1000) with bit 10 (bit 2 of the second mask byte) set in "
                    "point 0's record: rejected, malformed payload (spec 22.1: 'the bits from S up to the end of the "
                    "last mask byte MUST be 0'); the rest as in unusual/morph_deltas_10_slots",
                sent);
    }
    {
        std::vector<uint8_t> payload = first_payload;
        payload.push_back(0);
        w.write("faulty", "morph_deltas_trailing_bytes",
                kDeltasCopy + "with one byte (00) more after its last record: rejected, malformed payload (spec 22.1: "
                              "'bytes follow the last record')",
                after_stream(with_payload(first_deltas, payload)));
    }
    w.write("faulty", "morph_deltas_index_overflow",
            kDeltasCopy + "with first_index " + std::to_string(uint32_t(0u - n0)) + " = 2^32 - " +
                          std::to_string(n0) + ": first_index + count = 2^32 > 2^32 - 1 (0 in 32-bit arithmetic): "
                          "rejected, malformed payload (spec 22.1: 'computed without overflow'; at step 11, before "
                          "the object's point_count is looked at)",
            deltas_edited([&](Packet& p) { put32(p, kDeltasFirst, uint32_t(0u - n0)); }));
    w.write("faulty", "morph_deltas_unknown_object",
            kDeltasCopy + "sent for object 2 of a 2-object stream: rejected, unknown object (spec 22.1, 11.1 step 12)",
            deltas_edited([](Packet& p) { put16(p, 16, 2); }));
    {
        const MorphDeltasRun last = deltas_run_of(deltas.back());
        Packet copy = deltas.back();
        put32(copy, kDeltasFirst, last.first_index + 1);
        reseal(copy);
        w.write("faulty", "morph_deltas_index_out_of_range",
                face + ", then a copy of the last MORPH_DELTAS packet (points " + std::to_string(last.first_index) +
                    "..19) saying first_index " + std::to_string(last.first_index + 1) +
                    " (sequence 1000): its last point 20 is not below point_count 20: rejected, index out of range "
                    "(spec 22.1: 'a point first_index + count - 1 at or past the object's point_count'; 11.1 step 14)",
                after_stream(copy));
        restamp_packet(copy, 1000);
        Packets sent = {copy};
        sent.insert(sent.end(), stream.begin(), stream.end());
        w.write("faulty", "morph_deltas_held_out_of_range",
                "the morphing face of valid/morph with, before its STREAM_INFO, the copy of "
                "faulty/morph_deltas_index_out_of_range (sequence 1000): well formed, so held (spec 22.1); when the "
                "STREAM_INFO releases it, rejected at its own offset 12, index out of range (11.1 step 14); the rest "
                "as in valid/morph",
                sent);
    }
    {
        const MorphDeltasRun three = all_deltas(make_morph_stream(scene, 3, 3).deltas);
        w.write("faulty", "morph_deltas_target_count_contradicts",
                face + ", then a MORPH_DELTAS packet (sequence 1000) of points 0..2 with 3 targets (S = 6: the 6 "
                       "scales and the records of faulty/morph_target_count_differs) where object 0's packets say 2: "
                       "rejected, stream mismatch (spec 22.1: 'its target_count, attributes and scales (as numbers) "
                       "against those kept for its object')",
                after_stream(deltas_packet(0, 1000, deltas_payload(deltas_run(three, 0, 3)))));
        const MorphDeltasRun positions = all_deltas(make_morph_stream(scene, 2, kMorphPosition).deltas);
        w.write("faulty", "morph_deltas_attributes_contradicts",
                face + ", then a MORPH_DELTAS packet (sequence 1000) of points 0..4 with attributes 1 (their position "
                       "displacements alone: S = 2, the 2 scales of slots 0 and 2 of valid/morph) where object 0's "
                       "packets say 3: rejected, stream mismatch (spec 22.1)",
                after_stream(deltas_packet(0, 1000, deltas_payload(deltas_run(positions, 0, 5)))));
    }
    {
        // Slot 3 is 0 in every record (every bit 3 clear), so its scale changes no displacement.
        MorphDeltasRun run = deltas_run_of(first_deltas);
        if (run.scales[3] != 1.0f) std::exit(1);
        run.scales[3] = 0.5f;
        w.write("faulty", "morph_deltas_scale_contradicts",
                kDeltasCopy + "with the scale of slot 3 (target 1's normal displacement) 0.5 (3F000000) where object "
                              "0's packets say 1 (re-encoded): slot 3 is 0, 0, 0 in every record, so every record is "
                              "identical to the one held (the same integers, the same displacements), yet the scales "
                              "differ: rejected, stream mismatch, not a duplicate (spec 22.1: 'its target_count, "
                              "attributes and scales (as numbers) against those kept for its object')",
                after_stream(with_payload(first_deltas, deltas_payload(run))));
    }
    {
        // Point 2's target 1 position displacement (slot 2), its y one step further from 0.
        MorphDeltasRun run = deltas_run_of(first_deltas);
        int16_t& q = run.values[(2 * 4 + 2) * 3 + 1];
        const int16_t was = q;
        q = int16_t(q < 0 ? q - 1 : q + 1);
        w.write("faulty", "morph_deltas_value_contradicts",
                kDeltasCopy + "with the y of point 2's target 1 position displacement (slot 2) " + std::to_string(q) +
                              " where it is " + std::to_string(was) + " (one step; re-encoded): rejected, stream "
                              "mismatch (spec 22.1: 'each record for a point whose record the decoder holds against "
                              "that record'; the same integers)",
                after_stream(with_payload(first_deltas, deltas_payload(run))));
    }
    {
        const uint32_t from = n0 - 2, to = std::min<uint32_t>(n0 + 2, 19);  // 2 points held, the next ones not
        MorphDeltasRun run = deltas_run(records, from, uint16_t(to - from + 1));
        int16_t& q = run.values[2 * 3 + 0];  // point n0 - 2's target 1 position x (slot 2)
        const int16_t was = q;
        q = int16_t(q < 0 ? q - 1 : q + 1);
        Packets sent = stream;
        sent.insert(sent.begin() + long(deltas_at) + 1, deltas_packet(0, 1000, deltas_payload(run)));
        w.write("faulty", "morph_deltas_contradicts_partly_new",
                face + ", with a MORPH_DELTAS packet of points " + std::to_string(from) + ".." +
                       std::to_string(to) + " (sequence 1000) right after the first (points " + first_points +
                       "), point " + std::to_string(from) + "'s record changed (its target 1 position x " +
                       std::to_string(q) + " where it is " + std::to_string(was) + "): rejected, stream mismatch "
                       "(spec 22.1), and nothing of it is kept (the records of points " + std::to_string(n0) + ".." +
                       std::to_string(to) + ", not held then, arrive with the next packet); as valid/morph",
                sent);
    }

    // ---- faulty: MORPH_ANIMATION rejections. A copy of the first MORPH_ANIMATION packet (morph animation
    // 0, track 0, keys 0..19, times 0 .. 2.375, an empty name) with one defect, sequence 1000, after the
    // stream, unless the row says otherwise. ----
    const Packet& first_morph = morphs[0];
    const std::string kMorphCopy =
        face + ", then a copy of the first MORPH_ANIMATION packet (morph animation 0, track 0, keys 0..19) ";
    auto morph_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet copy = first_morph;
        edit(copy);
        reseal(copy);
        return after_stream(copy);
    };
    auto morph_rebuilt = [&](const std::function<void(AnimationPiece&)>& edit) {
        AnimationPiece piece = morph_piece_of(first_morph);
        edit(piece);
        return after_stream(morph_animation_packet(piece, 1000));
    };
    auto key_at = [](size_t k) { return kMorphName + 12 * k; };  // key k of the copy (no name, V = 2)
    {
        std::vector<uint8_t> payload = payload_of(first_morph);
        payload.resize(25);
        w.write("faulty", "morph_animation_payload_short",
                kMorphCopy + "cut to a payload of 25 bytes: rejected, malformed payload (spec 22.2: 'shorter than 26 "
                             "bytes')",
                after_stream(with_payload(first_morph, payload)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first_morph);
        payload.push_back(0);
        w.write("faulty", "morph_animation_length_mismatch",
                kMorphCopy + "with one byte (00) more after its keys: rejected, malformed payload (spec 22.2: "
                             "'payload_length MUST equal 26 + name_length + count * 4 * (1 + V)')",
                after_stream(with_payload(first_morph, payload)));
    }
    w.write("faulty", "morph_animation_index_past_table",
            kMorphCopy + "saying animation 2 of animation_count 2: rejected, malformed payload (spec 22.2: 'animation "
                         ">= animation_count')",
            morph_edited([](Packet& p) { put16(p, kMorphIndex, 2); }));
    w.write("faulty", "morph_animation_track_past_count",
            kMorphCopy + "saying track 2 of track_count 2: rejected, malformed payload (spec 22.2: 'track >= "
                         "track_count')",
            morph_edited([](Packet& p) { put16(p, kMorphTrack, 2); }));
    w.write("faulty", "morph_animation_target_count_zero",
            kMorphCopy + "with target_count 0: rejected, malformed payload (spec 22.2: 'target_count is 0'; checked "
                         "before the length, which depends on it)",
            morph_edited([](Packet& p) { p[kMorphTargets] = 0; }));
    w.write("faulty", "morph_animation_interpolation_3",
            kMorphCopy + "with interpolation 3: rejected, malformed payload (spec 22.2: 'interpolation > 2')",
            morph_edited([](Packet& p) { p[kMorphInterpolation] = 3; }));
    w.write("faulty", "morph_animation_key_count_zero",
            kMorphCopy + "with key_count 0: rejected, malformed payload (spec 22.2: 'key_count is 0')",
            morph_edited([](Packet& p) { put32(p, kMorphKeyCount, 0); }));
    {
        AnimationPiece piece = morph_piece_of(morphs[3]);  // Blink
        piece.info.interpolation = Interpolation::CubicSpline;
        piece.info.key_count = 1;
        piece.times = {0};
        piece.values = {0, 0, 0, 0, 0, 4};
        w.write("faulty", "morph_animation_cubicspline_one_key",
                face + ", then a MORPH_ANIMATION packet of Blink's track (sequence 1000) saying CUBICSPLINE with "
                       "key_count 1 and that key alone (first_key 0, count 1): rejected, malformed payload (spec 22.2: "
                       "'or below 2 with CUBICSPLINE')",
                after_stream(morph_animation_packet(piece, 1000)));
    }
    {
        std::vector<uint8_t> payload = payload_of(first_morph);
        payload.resize(26);  // the fields, an empty name, no key
        payload[14] = payload[15] = 0;
        w.write("faulty", "morph_animation_count_zero",
                kMorphCopy + "with count 0 and no key (a payload of 26 bytes: its length agrees): rejected, malformed "
                             "payload (spec 22.2: 'count is 0')",
                after_stream(with_payload(first_morph, payload)));
    }
    w.write("faulty", "morph_animation_keys_past_count",
            kMorphCopy + "with first_key 10: 10 + 20 = 30 > key_count 24: rejected, malformed payload (spec 22.2)",
            morph_edited([](Packet& p) { put32(p, kMorphFirstKey, 10); }));
    w.write("faulty", "morph_animation_first_key_overflow",
            kMorphCopy + "with first_key 4294967293 = 2^32 - 3: first_key + count = 2^32 + 17, which is 17 in 32-bit "
                         "arithmetic: rejected, malformed payload (spec 22.2: 'computed without overflow')",
            morph_edited([](Packet& p) { put32(p, kMorphFirstKey, 0xFFFFFFFDu); }));
    w.write("faulty", "morph_animation_time_infinite",
            kMorphCopy + "with the time of its last key (19) +infinity (7F800000; the times still increase): "
                         "rejected, malformed payload (spec 22.2: 'a float is not finite')",
            morph_edited([&](Packet& p) { put32(p, key_at(19), 0x7F800000u); }));
    w.write("faulty", "morph_animation_weight_nan",
            kMorphCopy + "with the second weight of key 2 NaN (7FC00000): rejected, malformed payload (spec 22.2)",
            morph_edited([&](Packet& p) { put32(p, key_at(2) + 8, 0x7FC00000u); }));
    w.write("faulty", "morph_animation_time_negative",
            kMorphCopy + "with the time of key 0 -0.5 (the others 0.125 .. 2.375): rejected, malformed payload (spec "
                         "22.2: 'a time is negative')",
            morph_edited([&](Packet& p) { put_f32(p, key_at(0), -0.5f); }));
    w.write("faulty", "morph_animation_times_not_increasing",
            kMorphCopy + "with the time of key 4 0.375, that of key 3: rejected, malformed payload (spec 22.2: 'the "
                         "times of the packet do not strictly increase')",
            morph_edited([&](Packet& p) { put_f32(p, key_at(4), 0.375f); }));
    w.write("faulty", "morph_animation_count_contradicts",
            kMorphCopy + "saying animation_count 3 where the others say 2: rejected, stream mismatch (spec 22.2: its "
                         "animation_count against the one kept)",
            morph_edited([](Packet& p) { put16(p, kMorphCount, 3); }));
    w.write("faulty", "morph_animation_track_count_contradicts",
            kMorphCopy + "saying track_count 3 where morph animation 0's packets say 2: rejected, stream mismatch "
                         "(spec 22.2)",
            morph_edited([](Packet& p) { put16(p, kMorphTrackCount, 3); }));
    w.write("faulty", "morph_animation_joins_contradicts",
            kMorphCopy + "saying joins FFFF (standing alone) where morph animation 0's packets say 0: rejected, stream "
                         "mismatch (spec 22.2: 'its track_count, joins and name')",
            morph_edited([](Packet& p) { put16(p, kMorphJoins, kNone); }));
    w.write("faulty", "morph_animation_name_contradicts",
            kMorphCopy + "naming its morph animation 'Talk' (re-encoded) where morph animation 0's packets carry an "
                         "empty name: rejected, stream mismatch (spec 22.2: names compared as bytes)",
            morph_rebuilt([](AnimationPiece& a) { a.name = "Talk"; }));
    w.write("faulty", "morph_animation_node_contradicts",
            kMorphCopy + "saying node 3 where track 0's packets say 1: rejected, stream mismatch (spec 22.2: its "
                         "track's description)",
            morph_edited([](Packet& p) { put16(p, kMorphNode, 3); }));
    w.write("faulty", "morph_animation_target_count_contradicts",
            face + ", then a MORPH_ANIMATION packet (sequence 1000) of keys 0..9 of morph animation 0's track 0 "
                   "with target_count 3 (its weights and a third 0 per key; well formed) where the track's packets say "
                   "2: rejected, stream mismatch (spec 22.2: the track's description)",
            morph_rebuilt([](AnimationPiece& a) {
                a.info.targets = 3;
                a.times.resize(10);
                std::vector<float> values;
                for (size_t k = 0; k < 10; ++k)
                    for (float v : {a.values[2 * k], a.values[2 * k + 1], 0.0f}) values.push_back(v);
                a.values = values;
            }));
    w.write("faulty", "morph_animation_interpolation_contradicts",
            kMorphCopy + "saying interpolation 1 (STEP; the same V) where track 0's packets say 0: rejected, stream "
                         "mismatch (spec 22.2)",
            morph_edited([](Packet& p) { p[kMorphInterpolation] = 1; }));
    w.write("faulty", "morph_animation_key_count_contradicts",
            kMorphCopy + "saying key_count 25 where track 0's packets say 24: rejected, stream mismatch (spec 22.2)",
            morph_edited([](Packet& p) { put32(p, kMorphKeyCount, 25); }));
    w.write("faulty", "morph_animation_weight_contradicts",
            kMorphCopy + "with the first weight of key 3 0.125 more: rejected, stream mismatch (spec 22.2: each key "
                         "against the key of the same index kept, the time and every weight as numbers)",
            morph_rebuilt([](AnimationPiece& a) { a.values[6] += 0.125f; }));
}

// ------------------------------------------------------------------------------------------------
// Format 1.7: mapped points (POINT_MAP, MAPPED_POINTS, spec 23). The mapped stream, at packet size 200:
// object 0 (8 ellipsoids, 240 points with normals, in pairs on a sphere) mapped at level 5 (D = 9) with batch
// 28 (the mapped records of B_m = 3 x 9 + 2 x 10 = 47 bits a 200-byte packet holds: 9 batches, the last of 16),
// object 1 (4 ellipsoids, 30 points with RGB colour) not mapped. Its STREAM_INFO (48-byte entries), POINT_MAP
// and MAPPED_POINTS packets say 1.7 (as the library writes them), its POINTS_REPAIR packets 1.2, its
// ELLIPSOIDS and POINTS packets 1.0.

constexpr uint8_t kMapLevel = 5;
constexpr uint16_t kMapBatch = 28;
constexpr uint32_t kMapPoints = 240;
constexpr uint32_t kMapBatches = (kMapPoints + kMapBatch - 1) / kMapBatch;

void set_minor(Packet& p, uint8_t minor) {
    p[5] = minor;
    reseal(p);
}

// Offsets in a POINT_MAP packet (header included), spec 23.3; in a STREAM_INFO packet of 48-byte entries
// (32-byte stream-level fields), the map fields of entry i (spec 23.1).
constexpr size_t kMapFirstRank = kHeaderSize, kMapPointTotal = kHeaderSize + 4, kMapRootLevel = kHeaderSize + 8,
                 kMapRice = kHeaderSize + 9, kMapRootCount = kHeaderSize + 10, kMapTree = kHeaderSize + 12;
constexpr size_t entry_map_level(size_t i) { return kHeaderSize + 32 + 48 * i + 44; }
constexpr size_t entry_map_batch(size_t i) { return kHeaderSize + 32 + 48 * i + 46; }

struct MapStream {
    StreamInfo info;
    std::vector<ObjectContent> contents;  // a mapped object's points in index order (mapped_order)
    StreamPackets packets;
    std::vector<PointMapFragment> fragments;  // object 0's, in the order of its POINT_MAP packets
    std::vector<RepairBlock> blocks;          // object 0's repair blocks (map_stream_repairs)
    std::vector<Packets> repairs;             // repairs[b]: block b's POINTS_REPAIR packets of rows k ..

    Packets base() const {
        Packets out = packets.stream_info;
        out.insert(out.end(), packets.ellipsoids.begin(), packets.ellipsoids.end());
        out.insert(out.end(), packets.maps.begin(), packets.maps.end());
        return out;
    }
    Packets all() const {
        Packets out = base();
        out.insert(out.end(), packets.points.begin(), packets.points.end());
        return out;
    }
    // The POINTS and MAPPED_POINTS packets of `object`, in stream order.
    Packets points_of(uint16_t object) const {
        Packets out;
        for (const Packet& p : packets.points)
            if (get16(p, 16) == object) out.push_back(p);
        return out;
    }
    const Packet& repair(size_t b, unsigned r) const { return repairs[b].at(r - blocks[b].source_count()); }
    // A MAPPED_POINTS (or, for an object without a map, POINTS) packet of the points [first, first + count) of
    // `object`, cut where the packetizer would not cut (spec 23.4: any run of consecutive indices).
    Packet points_packet(uint32_t first, uint32_t count, uint32_t sequence, uint16_t object = 0) const {
        PointBatch batch;
        batch.first_index = first;
        batch.points.assign(contents[object].points.begin() + first, contents[object].points.begin() + first + count);
        PacketHeader h;
        const bool mapped = info.objects[object].mapped();
        h.version_minor = mapped ? kMapMinor : 0;
        h.type = uint8_t(mapped ? PacketType::MappedPoints : PacketType::Points);
        h.stream_id = kStreamId;
        h.sequence = sequence;
        h.object_id = object;
        return write_packet(h, encode_points_payload(batch, info, info.objects[object]));
    }
    // A POINT_MAP packet of `f` for object 0 (encoded as given: the encoder writes point_total as given and
    // takes the roots from the cells in the order given).
    Packet map_packet(const PointMapFragment& f, uint32_t sequence, uint16_t object = 0) const {
        PacketHeader h;
        h.version_minor = kMapMinor;
        h.type = uint8_t(PacketType::PointMap);
        h.stream_id = kStreamId;
        h.sequence = sequence;
        h.object_id = object;
        return write_packet(h, encode_point_map_payload(f, info.objects[0].map_level));
    }
};

// Points in pairs on a sphere of radius 0.4 of the frame around its middle: `count` / 2 directions of a
// golden-angle spiral, the two points of a pair 0.01 of the frame or less from the spiral point along each
// axis, so that a cell of level 5 often holds both. Normals: the direction.
std::vector<QuantizedPoint> paired_points(const StreamInfo& info, const ObjectInfo& o, uint32_t count) {
    std::vector<QuantizedPoint> out;
    const double s = o.frame.scale, golden = M_PI * (3 - std::sqrt(5.0)), jitter = 0.02;
    const uint32_t pairs = count / 2;
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t c = i / 2, j = i % 2;
        const double z = 1 - 2 * (c + 0.5) / pairs, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = golden * c;
        const std::array<double, 3> dir = {r * std::cos(phi), r * std::sin(phi), z};
        const std::array<double, 3> off = {j ? -0.13 : -0.5, j ? 0.11 : -0.5, j ? 0.33 : -0.5};
        SurfacePoint p;
        for (int k = 0; k < 3; ++k) {
            p.position[k] = float(o.frame.origin[k] + s * (0.5 + 0.4 * dir[k] + off[k] * jitter));
            p.normal[k] = float(dir[k]);
        }
        out.push_back(quantize_point(p, info, o));
    }
    return out;
}

// The mapped points of a stream: each mapped object's points put in index order for its level and batch
// (mapped_order), packetized by the library; ELLIPSOIDS and POINTS packets then say 1.0. With `paired`,
// object 0's points are paired_points.
MapStream map_stream(StreamInfo info, uint64_t seed, bool paired = false) {
    MapStream m;
    m.info = info;
    Rng rng(seed);
    for (const ObjectInfo& o : info.objects) {
        ObjectContent c = make_content(info, o, rng);
        if (paired && m.contents.empty()) c.points = paired_points(info, o, o.point_count);
        if (o.mapped()) {
            const std::vector<uint32_t> order = mapped_order(c.points, info.position_bits, o.map_level, o.map_batch);
            std::vector<QuantizedPoint> sorted;
            for (uint32_t k : order) sorted.push_back(c.points[k]);
            c.points = sorted;
        }
        m.contents.push_back(c);
    }
    if (Error e = packetize_stream(info, m.contents, kStreamId, m.packets); e != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream (mapped) failed: " << error_name(e) << "\n";
        std::exit(1);
    }
    for (Packet& p : m.packets.ellipsoids) set_minor(p, 0);
    for (Packet& p : m.packets.points)
        if (p[6] == uint8_t(PacketType::Points)) set_minor(p, 0);
    for (const Packet& p : m.packets.maps) {
        PointMapFragment f;
        std::string why;
        const ObjectInfo& o = info.objects[get16(p, 16)];
        if (decode_point_map_payload(payload_of(p), info.position_bits, o.map_level, f, &why) != Error::Ok) {
            std::cerr << "make_vectors: the library's POINT_MAP packet does not decode: " << why << "\n";
            std::exit(1);
        }
        if (get16(p, 16) == 0) m.fragments.push_back(f);
    }
    return m;
}

StreamInfo mapped_info() {
    ObjectInfo o0 = make_object({-1, -1, -1}, 2, 8, kMapPoints, kAttrNormal);
    o0.map_level = kMapLevel;
    o0.map_batch = kMapBatch;
    return default_info({o0, make_object({0, 0, 0}, 1, 4, 30, kAttrColor)}, 200);
}

// The mapped stream with object 0's repair blocks (spec 23.5): its MAPPED_POINTS batches of 28, at most 3 a
// block, 3 rows each.
MapStream map_stream_repairs() {
    MapStream m = map_stream(mapped_info(), 230, true);
    m.blocks = plan_repair_blocks(kMapPoints, kMapBatch, 3);
    uint32_t sequence = uint32_t(m.all().size());
    for (const RepairBlock& b : m.blocks) {
        Packets out;
        if (packetize_repairs(m.info, 0, m.contents[0].points, {b}, 3, kStreamId, sequence, out) != Error::Ok) {
            std::cerr << "make_vectors: packetize_repairs (mapped) failed\n";
            std::exit(1);
        }
        sequence += uint32_t(out.size());
        m.repairs.push_back(out);
    }
    return m;
}

// "A..B" for a run of indices or ranks.
std::string run_text(uint64_t first, uint64_t count) {
    return std::to_string(first) + (count > 1 ? ".." + std::to_string(first + count - 1) : std::string());
}

void map_vectors(Writer& w) {
    const MapStream m = map_stream_repairs();
    const Packets stream = m.all();
    const Packets mapped = m.points_of(0), plain = m.points_of(1);
    const std::vector<PointMapFragment>& frags = m.fragments;
    if (m.packets.stream_info.size() != 1 || m.packets.maps.size() < 3 || mapped.size() != kMapBatches || m.blocks.size() < 3 ||
        m.packets.maps.size() != frags.size()) {
        std::cerr << "make_vectors: the mapped stream takes " << m.packets.stream_info.size() << " STREAM_INFO, "
                  << m.packets.maps.size() << " POINT_MAP, " << mapped.size() << " MAPPED_POINTS packets and "
                  << m.blocks.size() << " repair blocks, not 1, at least 3, " << kMapBatches << " and at least 3\n";
        std::exit(1);
    }
    const Packet& info = m.packets.stream_info[0];
    const size_t n_frags = frags.size();
    auto frag_text = [&](size_t i) {
        return "fragment " + std::to_string(i) + " (ranks " + run_text(frags[i].first_rank, frags[i].point_total) + ", " +
               std::to_string(frags[i].cells.size()) + " cells, root_level " + std::to_string(frags[i].root_level) +
               ", rice " + std::to_string(frags[i].rice) + ")";
    };
    const std::string mapped_desc =
        "the mapped stream (format 1.7, spec 23; packet size 200): object 0 (8 ellipsoids, 240 points with normals, "
        "in pairs on a sphere) mapped at map_level 5 with map_batch 28 (mapped records of 3 x 9 + 2 x 10 = 47 bits), "
        "its map in " + std::to_string(n_frags) + " POINT_MAP packets, its points in 9 MAPPED_POINTS packets of 28 "
        "points (the last 16); object 1 (4 ellipsoids, 30 points with RGB colour) not mapped, in POINTS packets; STREAM_INFO "
        "(48-byte entries), POINT_MAP and MAPPED_POINTS packets say 1.7, ELLIPSOIDS and POINTS 1.0";
    // Every packet of the stream but those of `lost` (positions in `stream`).
    auto without = [&](std::initializer_list<size_t> lost) {
        Packets out;
        for (size_t i = 0; i < stream.size(); ++i)
            if (std::find(lost.begin(), lost.end(), i) == lost.end()) out.push_back(stream[i]);
        return out;
    };
    const size_t maps_at = m.packets.stream_info.size() + m.packets.ellipsoids.size();  // fragment 0's position
    auto appended = [&](Packet p) {
        Packets out = stream;
        restamp_packet(p, 1000);
        out.push_back(p);
        return out;
    };
    auto before_info = [&](Packet p) {
        restamp_packet(p, 1000);
        Packets out = {p};
        out.insert(out.end(), stream.begin(), stream.end());
        return out;
    };

    w.write("valid", "map",
            mapped_desc + ", packets in stream order: every point of object 0 placed, its map complete (" +
                std::to_string(n_frags) + " fragments), nothing held unplaced",
            stream);

    // As a carousel sends object 0's MAPPED_POINTS packets with their repair rows, under loss.
    {
        // Per block, the source batches lost; then as many rows as were lost (at least one).
        const std::vector<std::vector<uint32_t>> lost_batches = {{1}, {0, 2}, {}, {1}};
        Packets file = m.base();
        file.insert(file.end(), plain.begin(), plain.end());
        std::string what;
        for (size_t b = 0; b < m.blocks.size(); ++b) {
            const RepairBlock& block = m.blocks[b];
            const std::vector<uint32_t> lost = b < lost_batches.size() ? lost_batches[b] : std::vector<uint32_t>{};
            const uint32_t first_batch = block.first_index / kMapBatch;
            for (uint32_t j = 0; j < block.source_count(); ++j)
                if (std::find(lost.begin(), lost.end(), j) == lost.end()) file.push_back(mapped[first_batch + j]);
            const size_t rows = std::max<size_t>(1, lost.size());
            for (size_t r = 0; r < rows; ++r) file.push_back(m.repair(b, block.source_count() + unsigned(r)));
            what += (b ? "; block " : "block ") + std::to_string(b) + " (points " + run_text(block.first_index, block.point_count) +
                    ", k " + std::to_string(block.source_count()) + "): ";
            if (lost.empty()) {
                what += "nothing lost, its row a duplicate";
            } else {
                what += lost.size() > 1 ? "batches " : "batch ";
                for (size_t j = 0; j < lost.size(); ++j)
                    what += (j ? " and " : "") + std::to_string(first_batch + lost[j]) + " (points " +
                            run_text((first_batch + lost[j]) * kMapBatch,
                                     std::min<uint32_t>(kMapBatch, kMapPoints - (first_batch + lost[j]) * kMapBatch)) + ")";
                what += " lost, recovered from " + std::to_string(rows) + " row" + (rows > 1 ? "s" : "");
            }
        }
        w.write("valid", "map_repair",
                mapped_desc + ", with object 0's repair blocks (spec 23.5: source symbols of mapped records, B_m = 47 "
                              "bits): the base, object 1's POINTS packets, then per block its MAPPED_POINTS packets "
                              "and repair rows, some lost: " + what + "; every point placed",
                numbered(file));
    }

    // ---- unusual ----
    {
        Packets file = m.packets.stream_info;
        file.insert(file.end(), m.packets.ellipsoids.begin(), m.packets.ellipsoids.end());
        file.insert(file.end(), m.packets.points.begin(), m.packets.points.end());
        file.insert(file.end(), m.packets.maps.begin(), m.packets.maps.end());
        w.write("unusual", "map_points_before_map",
                mapped_desc + ", with the POINT_MAP packets last, after every MAPPED_POINTS packet (the packets keep "
                              "their sequence numbers): each record is held but not placed until the fragment holding "
                              "its rank arrives, then placed (spec 23.4); decodes as valid/map",
                file);
    }
    {
        Packets file = {mapped[0], mapped[5], m.packets.maps[1], mapped[1]};
        file.push_back(m.packets.maps[0]);
        file.insert(file.end(), stream.begin(), stream.end());
        w.write("unusual", "map_before_stream_info",
                mapped_desc + ", with MAPPED_POINTS packets of points 0..27 and 140..167, the POINT_MAP packet of " +
                    frag_text(1) + ", MAPPED_POINTS of points 28..55 and the POINT_MAP packet of " + frag_text(0) +
                    " first, before the STREAM_INFO: all held (11.2), released in arrival order (11.1) when it "
                    "arrives, the records then held unplaced until the fragment holding their rank is taken in; then "
                    "the whole stream again (those 5 packets duplicates); decodes as valid/map",
                file);
    }
    {
        Packets file = stream;
        std::string what;
        uint32_t sequence = 1000;
        for (size_t i = 0; i < n_frags; ++i) {
            // Another root level and Rice parameter that still fit the packet size.
            bool found = false;
            for (unsigned F = kMapLevel + 1; F-- > 0 && !found;)
                for (unsigned k : {3u, 2u, 1u, 0u, 4u, 5u}) {
                    if (F == frags[i].root_level && k == frags[i].rice) continue;
                    PointMapFragment f = frags[i];
                    f.root_level = uint8_t(F);
                    f.rice = uint8_t(k);
                    const Packet p = m.map_packet(f, sequence);
                    if (p.size() > m.info.packet_size) continue;
                    file.push_back(p);
                    what += (i ? ", " : "") + std::to_string(F) + "/" + std::to_string(k) + " (" +
                            std::to_string(p.size()) + " bytes)";
                    found = true;
                    ++sequence;
                    break;
                }
            if (!found) std::exit(1);
        }
        w.write("unusual", "map_fragments_reencoded",
                mapped_desc + ", then (sequence 1000..) each fragment again, coded with another root_level / rice: " +
                    what + ": duplicates (spec 23.3: the same first_rank, cells and counts, whatever root_level and "
                           "rice); decodes as valid/map",
                file);
    }
    {
        // Runs of object 0's points cut as no sender cuts (at most 28 a packet), out of order, one overlapping.
        std::vector<std::pair<uint32_t, uint32_t>> runs;
        const uint32_t lengths[] = {1, 7, 28, 17, 3, 25, 13, 27, 9, 21, 28, 11, 19, 5, 26, 2, 4};
        uint32_t at = 0;
        for (size_t i = 0; at < kMapPoints; ++i) {
            const uint32_t n = std::min(lengths[i % std::size(lengths)], kMapPoints - at);
            runs.push_back({at, n});
            at += n;
        }
        Rng rng(231);
        for (size_t i = runs.size(); i > 1; --i) std::swap(runs[i - 1], runs[rng.below(i)]);
        runs.insert(runs.begin() + 3, {100, 28});  // overlaps the runs around it
        Packets file = m.base();
        file.insert(file.end(), plain.begin(), plain.end());
        std::string what;
        uint32_t sequence = 1000;
        for (auto [first, count] : runs) {
            file.push_back(m.points_packet(first, count, sequence++));
            what += (what.empty() ? "" : ", ") + run_text(first, count);
        }
        w.write("unusual", "map_odd_batches",
                mapped_desc + ", with object 0's points in MAPPED_POINTS packets of runs no sender cuts (sequence "
                              "1000..): " + what + " (spec 23.4: a batch MAY hold any run of consecutive indices; "
                              "the rank of each point depends on its index alone); decodes as valid/map",
                file);
    }
    {
        // Object 0 without a map, sent as POINTS, its STREAM_INFO saying 1.6 with 48-byte entries.
        StreamInfo plain_info = mapped_info();
        plain_info.objects[0].map_level = 0;
        plain_info.objects[0].map_batch = 0;
        Stream s;
        s.info = plain_info;
        Rng rng(230);
        for (const ObjectInfo& o : plain_info.objects) s.contents.push_back(make_content(plain_info, o, rng));
        packetize_stream(plain_info, s.contents, kStreamId, s.packets);
        mark_version_1_0(s.packets);
        Packet& si = s.packets.stream_info[0];
        std::vector<uint8_t> payload = payload_of(si);
        if (get16(si, kHeaderSize + 2) != 44 || payload.size() != 32 + 2 * 44) std::exit(1);
        std::vector<uint8_t> grown(payload.begin(), payload.begin() + 32);
        const uint8_t tails[2][4] = {{kMapLevel, 0, uint8_t(kMapBatch), 0}, {14, 0xFF, 0, 0}};
        for (size_t i = 0; i < 2; ++i) {
            grown.insert(grown.end(), payload.begin() + long(32 + 44 * i), payload.begin() + long(32 + 44 * (i + 1)));
            grown.insert(grown.end(), tails[i], tails[i] + 4);
        }
        grown[2] = 48;  // entry_size
        si = with_payload(si, grown);
        set_minor(si, 6);
        w.write("unusual", "map_entry_1_6",
                "the two objects of the mapped stream (object 0's points from the generator's sphere, not in pairs) "
                "without a map, object 0's points in POINTS packets (1.0), with a STREAM_INFO that says 1.6 and has "
                "48-byte entries whose bytes 44..47 are 05 00 1C 00 (object 0: what map_level 5, map_batch 28 would be) and 0E FF 00 00 (object 1: map_level 14, which would be "
                "malformed): a packet that says 1.6 has no map fields (spec 23.1, 9: bytes an older encoder appended "
                "are never read as them), so both objects have map_level 0 and their POINTS packets are taken",
                s.all());
    }
    {
        // Records recovered while their fragment has not arrived: held unplaced, placed when it arrives.
        Packets file = m.packets.stream_info;
        file.insert(file.end(), m.packets.ellipsoids.begin(), m.packets.ellipsoids.end());
        file.insert(file.end(), plain.begin(), plain.end());
        const RepairBlock& b0 = m.blocks[0];
        for (uint32_t j = 1; j < b0.source_count(); ++j) file.push_back(mapped[j]);
        file.push_back(m.repair(0, b0.source_count()));
        for (size_t i = b0.source_count(); i < mapped.size(); ++i) file.push_back(mapped[i]);
        file.insert(file.end(), m.packets.maps.begin(), m.packets.maps.end());
        w.write("unusual", "map_repair_before_map",
                mapped_desc + ", with the POINT_MAP packets last and the MAPPED_POINTS packet of points 0..27 lost: "
                              "block 0 (points " + run_text(b0.first_index, b0.point_count) + ") recovers those 28 "
                              "records from its row " + std::to_string(b0.source_count()) + " before any fragment has "
                              "arrived (spec 23.5: a source batch is held when its records are, placed or not), and "
                              "holds them unplaced like the others until the fragments arrive; decodes as valid/map but "
                              "for the counters, points_recovered 28 and the block",
                numbered(file));
    }
    {
        // A point set at 16 bits mapped at level 15: D = 1, Morton codes of 45 bits.
        ObjectInfo o = make_object({-2, -2, -2}, 4, 0, 40, kAttrColor, ObjectKind::PointSet);
        o.map_level = 15;
        o.map_batch = 7;
        StreamInfo info = default_info({o}, 200);
        info.position_bits = 16;
        const MapStream s = map_stream(info, 232);
        std::string what;
        for (const PointMapFragment& f : s.fragments)
            what += (what.empty() ? "" : ", ") + run_text(f.first_rank, f.point_total) + " (root_level " +
                    std::to_string(f.root_level) + ", " + std::to_string(f.cells.size()) + " cells)";
        w.write("unusual", "map_level_15",
                "a point set (kind 1) of 40 points with RGB colour, position_bits 16, mapped at map_level 15 = "
                "position_bits - 1 (spec 23.1): offsets of D = 1 bit per coordinate, mapped records of 3 + 24 = 27 "
                "bits, Morton codes of 45 bits (above 2^32), 15 levels of masks; map_batch 7 (6 batches, the last of 5); " +
                    std::to_string(s.fragments.size()) + " fragments: " + what + "; packet size 200, packets in stream order",
                s.all());
    }
    {
        // Level 1 (8 cells), batch 1 (rank = index), points cut into 3 packets of 10 by the generator.
        ObjectInfo o = make_object({-1, -1, -1}, 2, 2, 30, 0);
        o.map_level = 1;
        o.map_batch = 1;
        StreamInfo info = default_info({o}, 200);
        const MapStream s = map_stream(info, 233);
        Packets file = s.base();
        for (uint32_t first : {20u, 0u, 10u}) file.push_back(s.points_packet(first, 10, uint32_t(file.size())));
        std::string what;
        for (const MapCell& c : s.fragments.at(0).cells)
            what += (what.empty() ? "" : ", ") + std::to_string(c.code) + ": " + std::to_string(c.count);
        w.write("unusual", "map_level_1_batch_1",
                "one surface object (2 ellipsoids, 30 points without attributes, 14 bits) mapped at map_level 1 (8 "
                "cells, codes 0..7) with map_batch 1 (one batch per point: rank(i) = i, spec 23.2); its map one "
                "fragment of root_level " + std::to_string(s.fragments.at(0).root_level) + ", rice " +
                    std::to_string(s.fragments.at(0).rice) + ", cells (code: count) " + what +
                    "; its points in MAPPED_POINTS packets of 20..29, 0..9, 10..19 (cut by the generator: 13-bit "
                    "offsets, 39-bit records)",
                file);
    }

    // ---- faulty: POINT_MAP (spec 23.3) ----
    const Packet& frag1 = m.packets.maps[1];
    const Packet& last_frag = m.packets.maps.back();
    const std::string copy1 = mapped_desc + ", then (sequence 1000) a copy of the POINT_MAP packet of " + frag_text(1);
    auto frag1_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet p = frag1;
        edit(p);
        reseal(p);
        return p;
    };
    auto frag1_payload = [&](const std::function<void(std::vector<uint8_t>&)>& edit) {
        std::vector<uint8_t> payload = payload_of(frag1);
        edit(payload);
        return with_payload(frag1, payload);
    };
    w.write("faulty", "map_payload_short",
            copy1 + " cut to a payload of 11 bytes: rejected, malformed payload (spec 23.3, step 11: shorter than 12 bytes)",
            appended(frag1_payload([](std::vector<uint8_t>& p) { p.resize(11); })));
    const Packet total_zero = frag1_edited([](Packet& p) { put32(p, kMapPointTotal, 0); });
    w.write("faulty", "map_point_total_zero",
            copy1 + " with point_total 0: rejected, malformed payload (spec 23.3, step 11)", appended(total_zero));
    w.write("faulty", "map_rice_16",
            copy1 + " with rice 16: rejected, malformed payload (spec 23.3, step 11: rice above 15)",
            appended(frag1_edited([](Packet& p) { p[kMapRice] = 16; })));
    w.write("faulty", "map_root_count_zero",
            copy1 + " with root_count 0: rejected, malformed payload (spec 23.3, step 11)",
            appended(frag1_edited([](Packet& p) { put16(p, kMapRootCount, 0); })));
    w.write("faulty", "map_malformed_before_stream_info",
            "the copy of map_point_total_zero (sequence 1000) first, before the STREAM_INFO of " + mapped_desc +
                ": rejected when it arrives, malformed payload (spec 23.3: step 11 is made whether or not a stream "
                "info has arrived, before the packet can be held); nothing held",
            before_info(total_zero));
    w.write("faulty", "map_unknown_object",
            copy1 + " sent for object 2 of the 2-object stream: rejected, unknown object (11.1 step 12)",
            appended(frag1_edited([](Packet& p) { put16(p, 16, 2); })));
    w.write("faulty", "map_unmapped_object",
            copy1 + " sent for object 1, whose map_level is 0: rejected, malformed payload (spec 23.3, step 13: the "
                    "object's map_level is 0)",
            appended(frag1_edited([](Packet& p) { put16(p, 16, 1); })));
    w.write("faulty", "map_root_level_past_level",
            copy1 + " with root_level 6 where object 0's map_level is 5: rejected, malformed payload (spec 23.3, step "
                    "13: root_level > map_level)",
            appended(frag1_edited([](Packet& p) { p[kMapRootLevel] = kMapLevel + 1; })));
    {
        // Two roots of level 5 (cells), the second below the first.
        const MapCell a = frags[0].cells.at(0), b = frags[0].cells.at(1);
        PointMapFragment f;
        f.first_rank = 0;
        f.point_total = a.count + b.count;
        f.root_level = kMapLevel;
        f.rice = 0;
        f.cells = {b, a};
        w.write("faulty", "map_roots_not_increasing",
                mapped_desc + ", then (sequence 1000) a POINT_MAP packet of object 0 with root_level 5 (each root a "
                              "cell) and 2 roots, cell " + std::to_string(b.code) + " (count " + std::to_string(b.count) +
                    ") then cell " + std::to_string(a.code) + " (count " + std::to_string(a.count) +
                    "), first_rank 0: rejected, malformed payload (spec 23.3, step 13: a root's code not greater "
                    "than the previous root's)",
                appended(m.map_packet(f, 1000)));
    }
    {
        // One root of level 4, its mask 0: 12 bits of code, then 8 zero bits.
        const uint64_t root = frags[0].cells.at(0).code >> 3;
        std::vector<uint8_t> payload(12, 0);
        payload[4] = 1;           // point_total 1
        payload[8] = kMapLevel - 1;  // root_level 4
        payload[10] = 1;          // root_count 1
        const uint32_t bits = uint32_t(root);  // 12 bits, then the mask's 8 zero bits
        payload.push_back(uint8_t(bits));
        payload.push_back(uint8_t(bits >> 8));
        payload.push_back(0);
        w.write("faulty", "map_mask_zero",
                mapped_desc + ", then (sequence 1000) a POINT_MAP packet of object 0, first_rank 0, point_total 1, "
                              "root_level 4, rice 0, one root (code " + std::to_string(root) + ") whose mask is 0 "
                              "(a payload of 15 bytes: 20 bits of tree): rejected, malformed payload (spec 23.3, step "
                              "13: a mask is 0)",
                appended(with_payload(frag1, payload)));
    }
    w.write("faulty", "map_bits_end_early",
            copy1 + " without the last byte of its payload: rejected, malformed payload (spec 23.3, step 13: the bits "
                    "end before the tree does)",
            appended(frag1_payload([](std::vector<uint8_t>& p) { p.pop_back(); })));
    w.write("faulty", "map_counts_not_summing",
            copy1 + " with point_total one more than its counts add up to: rejected, malformed payload (spec 23.3, step "
                    "13)",
            appended(frag1_edited([&](Packet& p) { put32(p, kMapPointTotal, frags[1].point_total + 1); })));
    w.write("faulty", "map_trailing_byte",
            copy1 + " with one byte (00) more after the last byte of its tree: rejected, malformed payload (spec 23.3, "
                    "step 13: payload_length is not 12 + ceil(b / 8))",
            appended(frag1_payload([](std::vector<uint8_t>& p) { p.push_back(0); })));
    const Packet past = [&] {
        Packet p = last_frag;
        put32(p, kMapFirstRank, frags.back().first_rank + 1);
        reseal(p);
        return p;
    }();
    const std::string past_text = "a copy of the POINT_MAP packet of " + frag_text(n_frags - 1) + " with first_rank " +
                                  std::to_string(frags.back().first_rank + 1) + ": its ranks end at 240, past point_count 240";
    w.write("faulty", "map_ranks_past_point_count",
            mapped_desc + ", then (sequence 1000) " + past_text + ": rejected, index out of range (spec 23.3, step 14)",
            appended(past));
    w.write("faulty", "map_held_out_of_range",
            past_text + " (sequence 1000), first, before the STREAM_INFO of " + mapped_desc +
                ": held (its fixed fields are well formed), then, when the STREAM_INFO releases it, rejected, index "
                "out of range (11.1 step 14)",
            before_info(past));
    {
        // The same first rank and cells as fragment 1, two counts moved.
        PointMapFragment f = frags[1];
        size_t a = 0;
        while (a < f.cells.size() && f.cells[a].count < 2) ++a;
        if (a == f.cells.size()) a = 0;
        const size_t b = a + 1 < f.cells.size() ? a + 1 : a - 1;
        if (f.cells[a].count < 2) {
            f.cells[a].count += 1;
            f.cells[b].count -= 1;
        } else {
            f.cells[a].count -= 1;
            f.cells[b].count += 1;
        }
        w.write("faulty", "map_fragment_contradicts",
                mapped_desc + ", then (sequence 1000) a POINT_MAP packet with the first_rank, point_total and cells of " +
                    frag_text(1) + " but the counts of cells " + std::to_string(frags[1].cells[a].code) + " and " +
                    std::to_string(frags[1].cells[b].code) + " " + std::to_string(f.cells[a].count) + " and " +
                    std::to_string(f.cells[b].count) + " where they are " + std::to_string(frags[1].cells[a].count) +
                    " and " + std::to_string(frags[1].cells[b].count) +
                    ": not a duplicate (other counts), and its ranks overlap the kept fragment's: rejected, stream "
                    "mismatch (spec 23.3, step 15)",
                appended(m.map_packet(f, 1000)));
    }
    {
        // Fragment 1 lost; a copy of it one rank early overlaps fragment 0's last rank (its cells lie above).
        Packets file = without({maps_at + 1});
        Packet p = frag1;
        put32(p, kMapFirstRank, frags[1].first_rank - 1);
        reseal(p);
        restamp_packet(p, 1000);
        file.push_back(p);
        w.write("faulty", "map_fragment_overlaps",
                mapped_desc + ", with the POINT_MAP packet of " + frag_text(1) + " lost, then (sequence 1000) that "
                              "packet with first_rank " + std::to_string(frags[1].first_rank - 1) +
                    ": its cells lie above fragment 0's and below fragment 2's, its ranks below fragment 2's, but its "
                    "first rank is fragment 0's last: rejected, stream mismatch (spec 23.3, step 15: not entirely on "
                    "one side of a kept fragment, in ranks and in cells together); the points of fragment 1's ranks "
                    "stay unplaced, the map incomplete",
                file);
    }
    {
        // Fragment 1 lost; a fragment in its ranks whose cells are fragment 0's first cells.
        PointMapFragment f;
        f.first_rank = frags[1].first_rank;
        f.point_total = frags[1].point_total;
        f.root_level = kMapLevel;
        f.rice = 0;
        uint32_t left = f.point_total;
        // At most 8 cells: 1 point each, the rest in the last.
        for (size_t i = 0; i < frags[0].cells.size() && left > 0; ++i) {
            const uint32_t c = (i == 7 || i + 1 == frags[0].cells.size() || left == 1) ? left : 1;
            f.cells.push_back({frags[0].cells[i].code, c});
            left -= c;
        }
        if (left != 0) std::exit(1);
        f.rice = 0;
        for (unsigned k = 0; k <= 15; ++k) {
            f.rice = uint8_t(k);
            if (m.map_packet(f, 1000).size() <= m.info.packet_size) break;
        }
        Packets file = without({maps_at + 1});
        file.push_back(m.map_packet(f, 1000));
        w.write("faulty", "map_fragment_cells_misordered",
                mapped_desc + ", with the POINT_MAP packet of " + frag_text(1) + " lost, then (sequence 1000) a POINT_MAP "
                              "packet of fragment 1's ranks (first_rank " + std::to_string(f.first_rank) + ", point_total " +
                    std::to_string(f.point_total) + ") whose " + std::to_string(f.cells.size()) +
                    " cells are fragment 0's first ones (root_level 5, rice " + std::to_string(f.rice) +
                    "): its ranks lie above fragment 0's, its cells do not: rejected, stream mismatch (spec 23.3, step "
                    "15); the map stays incomplete",
                file);
    }
    {
        const uint32_t lo = frags[1].first_rank, hi = lo + frags[1].point_total;
        uint32_t unplaced = 0;
        for (uint32_t i = 0; i < kMapPoints; ++i) {
            const uint32_t r = mapped_rank(i, kMapPoints, kMapBatch);
            unplaced += r >= lo && r < hi;
        }
        w.write("faulty", "map_fragment_missing",
                mapped_desc + ", with the POINT_MAP packet of " + frag_text(1) +
                    " lost: no rejection; the " + std::to_string(unplaced) +
                    " points whose ranks it holds stay held but not placed (spec 23.4: not shown, not received), the "
                    "map is not complete: the object is not complete and the stream does not conform (spec 23.6)",
                without({maps_at + 1}));
    }

    // ---- faulty: MAPPED_POINTS (spec 23.4) ----
    const std::string mp_copy = mapped_desc + ", then (sequence 1000) a copy of the MAPPED_POINTS packet of points ";
    {
        std::vector<uint8_t> payload = payload_of(mapped[0]);
        payload.resize(7);
        w.write("faulty", "map_points_payload_short",
                "a copy of the MAPPED_POINTS packet of points 0..27 (sequence 1000) cut to a payload of 7 bytes, too "
                "short for its fixed fields, first, before the STREAM_INFO of " + mapped_desc +
                    ": held (its checks need the object's entry, spec 11.1), then, when the STREAM_INFO releases it, "
                    "rejected, malformed payload (spec 23.4, step 13: shorter than 8 bytes)",
                before_info(with_payload(mapped[0], payload)));
    }
    {
        std::vector<uint8_t> payload = payload_of(mapped[0]);
        payload.push_back(0);
        w.write("faulty", "map_points_length_mismatch",
                mp_copy + "0..27 with one byte (00) more: rejected, malformed payload (spec 23.4: payload_length is not "
                          "8 + ceil(count * B_m / 8))",
                appended(with_payload(mapped[0], payload)));
    }
    {
        Packet p = mapped[0];
        put32(p, kHeaderSize, 0xFFFFFFFFu - (kMapBatch - 1));
        reseal(p);
        w.write("faulty", "map_points_index_overflow",
                mp_copy + "0..27 with first_index 4294967268 = 2^32 - 28: first_index + count = 2^32 > 2^32 - 1: "
                          "rejected, malformed payload (spec 23.4, step 13)",
                appended(p));
    }
    {
        Packet p = mapped.back();
        put32(p, kHeaderSize, kMapPoints - 15);
        reseal(p);
        w.write("faulty", "map_points_index_out_of_range",
                mp_copy + "224..239 with first_index 225: its last point 240 is not below point_count 240: rejected, "
                          "index out of range (spec 23.4, step 14)",
                appended(p));
    }
    {
        Packet p = plain.at(0);
        p[5] = kMapMinor;
        p[6] = uint8_t(PacketType::MappedPoints);
        reseal(p);
        w.write("faulty", "map_points_for_unmapped_object",
                mapped_desc + ", then (sequence 1000) object 1's first POINTS packet with its type made MAPPED_POINTS "
                              "(and its version 1.7): object 1's map_level is 0: rejected, malformed payload (spec 23.4, "
                              "step 13)",
                appended(p));
    }
    {
        ObjectInfo unmapped = m.info.objects[0];
        unmapped.map_level = 0;
        unmapped.map_batch = 0;
        PointBatch batch;
        batch.first_index = 0;
        batch.points.assign(m.contents[0].points.begin(), m.contents[0].points.begin() + 21);
        PacketHeader h;
        h.version_minor = 0;
        h.type = uint8_t(PacketType::Points);
        h.stream_id = kStreamId;
        h.sequence = 1000;
        h.object_id = 0;
        w.write("faulty", "map_points_for_mapped_object",
                mapped_desc + ", then (sequence 1000) a POINTS packet (1.0) of object 0's points 0..20 as POINTS records "
                              "(their whole 14-bit positions and normals: 62 bits, a well-formed POINTS payload): "
                              "object 0's map_level is 4: rejected, malformed payload (spec 23.4, step 13)",
                appended(write_packet(h, encode_points_payload(batch, m.info, unmapped))));
    }

    // ---- faulty: the entry's map fields (spec 23.1) ----
    auto info_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet p = info;
        edit(p);
        reseal(p);
        return appended(p);
    };
    const std::string si_copy = mapped_desc + ", then (sequence 1000) a copy of its STREAM_INFO with ";
    w.write("faulty", "map_entry_level_at_position_bits",
            si_copy + "object 0's map_level 14 = position_bits: rejected, malformed payload (spec 23.1: map_level >= "
                      "position_bits)",
            info_edited([](Packet& p) { p[entry_map_level(0)] = 14; }));
    w.write("faulty", "map_entry_batch_zero",
            si_copy + "object 0's map_batch 0 (its map_level 5): rejected, malformed payload (spec 23.1: map_level > 0 "
                      "with map_batch 0)",
            info_edited([](Packet& p) { put16(p, entry_map_batch(0), 0); }));
    w.write("faulty", "map_entry_batch_without_level",
            si_copy + "object 1's map_batch 5 (its map_level 0): rejected, malformed payload (spec 23.1: map_level 0 "
                      "with map_batch != 0)",
            info_edited([](Packet& p) { put16(p, entry_map_batch(1), 5); }));
    w.write("faulty", "map_entry_level_contradicts",
            si_copy + "object 0's map_level 4 where the accepted one says 5: rejected, stream mismatch (spec 23.1, 5.4)",
            info_edited([](Packet& p) { p[entry_map_level(0)] = 4; }));
    w.write("faulty", "map_entry_batch_contradicts",
            si_copy + "object 0's map_batch 29 where the accepted one says 28: rejected, stream mismatch (spec 23.1, 5.4)",
            info_edited([](Packet& p) { put16(p, entry_map_batch(0), 29); }));
    w.write("faulty", "map_entry_in_1_6_packet",
            si_copy + "its version 1.6: its map fields are not read, so object 0's entry has map_level 0 and map_batch "
                      "0 (spec 23.1), which contradicts the accepted 5 and 28: rejected, stream mismatch (spec 23.1: an "
                      "entry without them comparing as map_level = 0, map_batch = 0)",
            info_edited([](Packet& p) { p[5] = 6; }));

    // ---- faulty: repair over mapped records (spec 23.5) ----
    {
        const RepairBlock& b0 = m.blocks[0];
        Packet p = m.repair(0, b0.source_count());
        std::vector<uint8_t> payload = payload_of(p);
        payload.resize(8 + (size_t{kMapBatch} * 62 + 7) / 8, 0);
        w.write("faulty", "map_repair_symbol_length",
                mapped_desc + ", then (sequence 1000) block 0's POINTS_REPAIR packet of row " +
                    std::to_string(b0.source_count()) + " with its symbol zero-padded to ceil(28 x 62 / 8) = 217 bytes, "
                    "the length for POINTS records of 62 bits (the packet, 249 bytes, is also larger than packet size "
                    "200): rejected, malformed payload (spec 23.5: B is the mapped record size B_m = 47: 165 bytes)",
                appended(with_payload(p, payload)));
    }
    {
        // Fragment 1 lost; records of its ranks recovered and held unplaced.
        const RepairBlock& b0 = m.blocks[0];
        Packets file = m.packets.stream_info;
        file.insert(file.end(), m.packets.ellipsoids.begin(), m.packets.ellipsoids.end());
        for (size_t i = 0; i < n_frags; ++i)
            if (i != 1) file.push_back(m.packets.maps[i]);
        file.insert(file.end(), plain.begin(), plain.end());
        for (uint32_t j = 1; j < b0.source_count(); ++j) file.push_back(mapped[j]);
        file.push_back(m.repair(0, b0.source_count()));
        for (size_t i = b0.source_count(); i < mapped.size(); ++i) file.push_back(mapped[i]);
        w.write("faulty", "map_repair_fragment_missing",
                mapped_desc + ", with the POINT_MAP packet of " + frag_text(1) + " and the MAPPED_POINTS packet of "
                              "points 0..27 lost: block 0 recovers those 28 records from its row " +
                    std::to_string(b0.source_count()) + " (spec 23.5); those whose rank fragment 1 holds stay held "
                    "but not placed with the other records of its ranks; no rejection; the map is not complete, the "
                    "stream does not conform (spec 23.6)",
                numbered(file));
    }
}


// ------------------------------------------------------------------------------------------------
// Format 1.8: surface normals (NORMALS, spec 24). The surface-normals stream, at packet size 200, 14-bit
// positions and 10-bit normals: object 0, a lumpy sphere (an octahedron subdivided three times: 258 points,
// 512 triangles; each vertex moved by up to 0.03 along each axis) without normals in its records, mapped at
// level 5 with batch 49 (mapped records of 3 x 9 = 27 bits), with an exact layer and surface normals;
// object 1, the panel of the exact-layer stream (56 points with texture coordinates, 65 triangles, a hole,
// a UV seam and a fin; its middle vertex used by no triangle) with an exact layer and surface normals, not
// mapped; object 2, a point set (20 points with RGB colour). The normal entries are the reference
// encoder's (spec 24.5, tolerance 2 degrees) for "original" normals that are each point's surface normal
// (spec 24.3, over the quantized positions) where it is defined and the point's index is not a multiple
// of 3, and the mesh's own normal otherwise (the sphere's: the direction of the vertex before it was
// moved; the panel's: (0, 0, 1), the fin's tip (0, -1, 0)). In file order: the STREAM_INFO (1.8), the
// ELLIPSOIDS (1.0), the POINT_MAP (1.7), the MAPPED_POINTS (1.7) and POINTS (1.0) packets as the packetizer
// interleaves them, the CONNECTIVITY packets (1.3) of objects 0 and 1, the NORMALS packets (1.8) of
// objects 0 and 1; sequence numbers count the packets in that order.

constexpr uint16_t kNormalsPacketSize = 200;
constexpr uint8_t kNormalsMapLevel = 5;
constexpr uint16_t kNormalsMapBatch = 49;  // floor((200 - 32) * 8 / 27)
constexpr double kNormalsTolerance = 2.0;  // degrees (spec 24.5)

// The reference encoder's normal entries (spec 24.5): a point's normal is left to its surface when its
// surface normal is defined, |S| is at least a tenth of the sum of the angles, and it is within the
// tolerance of the original normal; otherwise the original normal is sent.
std::vector<NormalEntry> reference_normal_entries(const StreamInfo& info,
                                                  const std::vector<std::array<uint32_t, 3>>& positions,
                                                  const std::vector<Triangle>& triangles,
                                                  const std::vector<std::array<float, 3>>& originals) {
    const SurfaceNormals sn = surface_normals(positions, triangles);
    std::vector<NormalEntry> out(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        const std::array<float, 3>& a = sn.normal[i];
        const std::array<float, 3>& b = originals[i];
        const double la = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
        const double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
        bool surface = sn.condition[i] >= 0.1f && la > 0 && lb > 0;
        if (surface) {
            const double dot = (double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]) / (la * lb);
            surface = std::acos(std::clamp(dot, -1.0, 1.0)) * 180 / M_PI <= kNormalsTolerance;
        }
        if (!surface) {
            out[i].sent = true;
            out[i].normal = encode_octahedral(b, info.normal_bits);
        }
    }
    return out;
}

struct NormalsStream {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    std::vector<std::vector<Triangle>> triangles;  // per object: the exact triangle list a decoder decodes
    std::vector<std::vector<uint8_t>> coded;       // per object: the coded connectivity (empty: none)
    // In file order, numbered in that order from 0: the STREAM_INFO, ELLIPSOIDS, POINT_MAP packets, the
    // MAPPED_POINTS and POINTS packets, the CONNECTIVITY packets, the NORMALS packets.
    Packets info_packets, ellipsoids, maps, points, connectivity, normals;

    Packets all() const {
        Packets out = info_packets;
        for (const Packets* p : {&ellipsoids, &maps, &points, &connectivity, &normals})
            out.insert(out.end(), p->begin(), p->end());
        return out;
    }
    // Everything but the NORMALS packets.
    Packets without_normals() const {
        Packets out = info_packets;
        for (const Packets* p : {&ellipsoids, &maps, &points, &connectivity}) out.insert(out.end(), p->begin(), p->end());
        return out;
    }
    static Packets of(const Packets& packets, uint16_t object) {
        Packets out;
        for (const Packet& p : packets)
            if (get16(p, 16) == object) out.push_back(p);
        return out;
    }
    NormalsRun run_of(const Packet& p) const {
        NormalsRun run;
        if (decode_normals_payload(payload_of(p), info.normal_bits, run) != Error::Ok) {
            std::cerr << "make_vectors: a NORMALS packet does not decode\n";
            std::exit(1);
        }
        return run;
    }
    // The entries of points [first, first + count) of `object` as one run.
    NormalsRun run(uint16_t object, uint32_t first, uint32_t count) const {
        NormalsRun r;
        r.first_index = first;
        r.entries.assign(contents[object].normals.begin() + first, contents[object].normals.begin() + first + count);
        return r;
    }
    Packet packet(const NormalsRun& run, uint32_t sequence, uint16_t object) const {
        return write_packet(skippable_header(PacketType::Normals, kSurfaceNormalsMinor, kStreamId, sequence, object),
                            encode_normals_payload(run, info.normal_bits));
    }
    size_t sent_count(uint16_t object) const {
        size_t n = 0;
        for (const NormalEntry& e : contents[object].normals) n += e.sent;
        return n;
    }
};

// With `flat_fin`, the panel's fin is flattened: its tip (the panel's last point before the points are
// shuffled) moved to the quantized position 2 q0 - q1 of its edge's points 0 and 1, on their line, so that
// the fin triangle is degenerate (m = 0 at each corner, spec 24.3) and the tip, which no other triangle
// uses, has an undefined surface normal.
NormalsStream normals_stream(uint8_t normal_bits = 10, bool flat_fin = false) {
    NormalsStream s;
    ObjectInfo o0 = make_object({-1, -1, -1}, 2, 8, 258, 0);
    o0.exact_layer = true;
    o0.surface_normals = true;
    o0.map_level = kNormalsMapLevel;
    o0.map_batch = kNormalsMapBatch;
    ObjectInfo o1 = make_object({1, -1, -1}, 2, 8, 56, kAttrTexcoord);
    o1.exact_layer = true;
    o1.surface_normals = true;
    s.info = default_info({o0, o1, make_object({-1, 2, -1}, 1, 0, 20, kAttrColor, ObjectKind::PointSet)}, kNormalsPacketSize);
    s.info.normal_bits = normal_bits;
    Rng rng(240);
    std::vector<ExactMesh> meshes = {exact_sphere(rng, 3, 0.03), exact_panel()};
    if (flat_fin) {
        const ObjectInfo& o = s.info.objects[1];
        SurfacePoint& tip = meshes[1].points.back();
        const QuantizedPoint q0 = quantize_point(meshes[1].points[0], s.info, o);
        const QuantizedPoint q1 = quantize_point(meshes[1].points[1], s.info, o);
        std::array<uint32_t, 3> target;
        const double steps = double((1u << s.info.position_bits) - 1);
        for (int k = 0; k < 3; ++k) {
            target[k] = 2 * q0.position[k] - q1.position[k];
            tip.position[k] = float(o.frame.origin[k] + target[k] * double(o.frame.scale) / steps);
        }
        if (quantize_point(tip, s.info, o).position != target) {
            std::cerr << "make_vectors: the flattened fin's tip does not quantize to 2 q0 - q1\n";
            std::exit(1);
        }
    }
    shuffle_points(meshes[1], rng);
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        const ObjectInfo& o = s.info.objects[i];
        ObjectContent c = make_content(s.info, o, rng);  // ellipsoids (and the point set's points)
        s.triangles.emplace_back();
        s.coded.emplace_back();
        if (i < meshes.size()) {
            ExactMesh m = meshes[i];
            if (m.points.size() != o.point_count) {
                std::cerr << "make_vectors: normals mesh " << i << " has " << m.points.size() << " points\n";
                std::exit(1);
            }
            c.points.clear();
            for (const SurfacePoint& p : m.points) c.points.push_back(quantize_point(p, s.info, o));
            if (o.mapped()) {
                // Index order for the map (spec 23.2): the points and the triangles renumbered.
                const std::vector<uint32_t> order = mapped_order(c.points, s.info.position_bits, o.map_level, o.map_batch);
                std::vector<uint32_t> new_of(order.size());
                std::vector<QuantizedPoint> points;
                std::vector<SurfacePoint> mesh_points;
                for (uint32_t k = 0; k < order.size(); ++k) {
                    points.push_back(c.points[order[k]]);
                    mesh_points.push_back(m.points[order[k]]);
                    new_of[order[k]] = k;
                }
                c.points = points;
                m.points = mesh_points;
                for (Triangle& t : m.triangles)
                    for (uint32_t& v : t) v = new_of[v];
            }
            std::vector<std::array<uint32_t, 3>> positions;
            for (const QuantizedPoint& q : c.points) positions.push_back(q.position);
            if (encode_connectivity(positions, m.triangles, s.coded[i], s.triangles[i]) != Error::Ok) {
                std::cerr << "make_vectors: encode_connectivity (normals) failed\n";
                std::exit(1);
            }
            c.triangle_count = uint32_t(m.triangles.size());
            const SurfaceNormals sn = surface_normals(positions, m.triangles);
            std::vector<std::array<float, 3>> originals;
            for (size_t k = 0; k < positions.size(); ++k) {
                const bool defined = sn.normal[k] != std::array<float, 3>{0, 0, 0};
                originals.push_back(defined && k % 3 != 0 ? sn.normal[k] : m.points[k].normal);
            }
            c.normals = reference_normal_entries(s.info, positions, m.triangles, originals);
        }
        s.contents.push_back(std::move(c));
    }
    StreamPackets packets;
    if (Error e = packetize_stream(s.info, s.contents, kStreamId, packets); e != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream (normals) failed: " << error_name(e) << "\n";
        std::exit(1);
    }
    for (Packet& p : packets.ellipsoids) set_minor(p, 0);
    for (Packet& p : packets.points)
        if (p[6] == uint8_t(PacketType::Points)) set_minor(p, 0);
    Packets connectivity;
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        if (s.coded[i].empty()) continue;
        Packets out;
        if (packetize_connectivity(s.info, uint16_t(i), s.contents[i].triangle_count, s.coded[i], kStreamId, 0, out) !=
            Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity (normals) failed\n";
            std::exit(1);
        }
        connectivity.insert(connectivity.end(), out.begin(), out.end());
    }
    uint32_t sequence = 0;
    auto number = [&](Packets p) {
        for (Packet& q : p) restamp_packet(q, sequence++);
        return p;
    };
    s.info_packets = number(packets.stream_info);
    s.ellipsoids = number(packets.ellipsoids);
    s.maps = number(packets.maps);
    s.points = number(packets.points);
    s.connectivity = number(connectivity);
    s.normals = number(packets.normals);
    return s;
}

// Offsets in a NORMALS packet (header included), spec 24.2; in a STREAM_INFO packet of 48-byte entries, the
// kind, attributes and flags of entry i (spec 5.2).
constexpr size_t kNormalsFirst = kHeaderSize, kNormalsCount = kHeaderSize + 4, kNormalsSent = kHeaderSize + 6,
                 kNormalsBits = kHeaderSize + 8;
constexpr size_t entry_kind(size_t i) { return kHeaderSize + 32 + 48 * i + 24; }
constexpr size_t entry_attributes(size_t i) { return kHeaderSize + 32 + 48 * i + 25; }
constexpr size_t entry_flags(size_t i) { return kHeaderSize + 32 + 48 * i + 26; }

// A NORMALS payload written as given: the header fields, then `flags` (one bit each) and the `normals`
// (u, v pairs of `bits` bits), padded to a whole byte.
std::vector<uint8_t> raw_normals_payload(uint32_t first, uint16_t count, uint16_t sent, const std::vector<bool>& flags,
                                         const std::vector<std::array<uint32_t, 2>>& normals, unsigned bits) {
    std::vector<uint8_t> out(8);
    for (int i = 0; i < 4; ++i) out[i] = uint8_t(first >> (8 * i));
    out[4] = uint8_t(count);
    out[5] = uint8_t(count >> 8);
    out[6] = uint8_t(sent);
    out[7] = uint8_t(sent >> 8);
    uint64_t acc = 0;
    int have = 0;
    auto put = [&](uint32_t v, unsigned n) {
        for (unsigned b = 0; b < n; ++b) {
            acc |= uint64_t((v >> b) & 1) << have;
            if (++have == 8) {
                out.push_back(uint8_t(acc));
                acc = 0;
                have = 0;
            }
        }
    };
    for (bool f : flags) put(f ? 1 : 0, 1);
    for (const auto& n : normals) {
        put(n[0], bits);
        put(n[1], bits);
    }
    if (have) out.push_back(uint8_t(acc));
    return out;
}

std::string entries_text(const std::vector<NormalEntry>& entries) {
    size_t sent = 0;
    for (const NormalEntry& e : entries) sent += e.sent;
    return std::to_string(sent) + " sent, " + std::to_string(entries.size() - sent) + " left to the surface";
}

void normals_vectors(Writer& w) {
    const NormalsStream s = normals_stream();
    const Packets stream = s.all();
    const Packets n0 = NormalsStream::of(s.normals, 0), n1 = NormalsStream::of(s.normals, 1);
    const Packets points1 = NormalsStream::of(s.points, 1);
    if (s.info_packets.size() != 1 || n0.size() < 2 || n1.size() != 1 || points1.size() != 3 ||
        NormalsStream::of(s.connectivity, 1).size() != 1) {
        std::cerr << "make_vectors: the surface-normals stream takes " << s.info_packets.size() << " STREAM_INFO, "
                  << n0.size() << " + " << n1.size() << " NORMALS and " << points1.size()
                  << " POINTS packets of object 1, not 1, at least 2 + 1 and 3\n";
        std::exit(1);
    }
    const unsigned bits = s.info.normal_bits;
    const Packet& info = s.info_packets[0];
    const Packet& last0 = n0.back();
    const Packet& only1 = n1[0];
    const NormalsRun run1 = s.run_of(only1), last_run0 = s.run_of(last0);
    auto run_text_of = [&](const Packet& p) {
        const NormalsRun r = s.run_of(p);
        return "points " + run_text(r.first_index, r.entries.size()) + ", " + entries_text(r.entries);
    };
    std::string n0_text;
    for (size_t i = 0; i < n0.size(); ++i) n0_text += (i ? "; " : "") + run_text_of(n0[i]);
    const std::string desc =
        "the surface-normals stream (format 1.8, spec 24; packet size 200): object 0, a lumpy sphere of 258 points "
        "without normals in their records and 512 triangles, mapped at map_level 5 with map_batch 49, with an exact "
        "layer and surface normals (entries: " + entries_text(s.contents[0].normals) + "; its NORMALS packets: " + n0_text +
        "); object 1, the panel of the exact-layer stream (56 points with texture coordinates, 65 triangles), with "
        "an exact layer and surface normals (" + run_text_of(only1) + ", in one NORMALS packet); object 2, a point set "
        "of 20 points with RGB colour; STREAM_INFO and NORMALS packets say 1.8, POINT_MAP and MAPPED_POINTS 1.7, "
        "CONNECTIVITY 1.3, ELLIPSOIDS and POINTS 1.0";
    auto appended = [&](Packet p, Packets base) {
        restamp_packet(p, 1000);
        base.push_back(p);
        return base;
    };
    auto after_stream = [&](Packet p) { return appended(std::move(p), stream); };
    auto before_info = [&](Packet p) {
        restamp_packet(p, 1000);
        Packets out = {p};
        out.insert(out.end(), stream.begin(), stream.end());
        return out;
    };
    // The stream with `packet` replaced by `by` (at its place, with its sequence number).
    auto replaced = [&](const Packet& packet, Packet by) {
        Packets out = stream;
        for (Packet& p : out)
            if (p == packet) {
                restamp_packet(by, get32(p, 12));
                p = by;
            }
        return out;
    };
    // The stream without the packets in `lost`.
    auto without = [&](const Packets& lost) {
        Packets out;
        for (const Packet& p : stream)
            if (std::find(lost.begin(), lost.end(), p) == lost.end()) out.push_back(p);
        return out;
    };

    // ---- valid ----
    w.write("valid", "normals",
            desc + ", packets in stream order: both surface objects exact, every normal entry held (normals complete), "
                   "each point's surface normal listed (spec 24.3; object 1's middle vertex, used by no triangle, "
                   "undefined: its normal is sent)",
            stream);
    {
        // Object 1's POINTS packets as the source batches of one repair block (spec 17: records without a normal).
        const ObjectInfo& o1 = s.info.objects[1];
        const uint16_t batch = uint16_t(point_batch_size(s.info, o1));
        const std::vector<RepairBlock> blocks = plan_repair_blocks(o1.point_count, batch, 3);
        Packets rows;
        if (blocks.size() != 1 ||
            packetize_repairs(s.info, 1, s.contents[1].points, blocks, 1, kStreamId, 0, rows) != Error::Ok || rows.size() != 1) {
            std::cerr << "make_vectors: packetize_repairs (normals) failed\n";
            std::exit(1);
        }
        Packets file;
        for (const Packet& p : stream) {
            if (p == points1[1]) continue;
            file.push_back(p);
            if (p == points1[2]) file.push_back(rows[0]);
        }
        w.write("valid", "normals_repair",
                desc + ", with object 1's POINTS packet of points 20..39 lost and, after its last POINTS packet, the "
                       "POINTS_REPAIR packet of row 3 of its one block (points 0..55, batch " + std::to_string(batch) +
                       ", k 3; records of 3 x 14 + 2 x 12 = 66 bits, no normal: spec 24.4, 17) (renumbered in file "
                       "order): the block recovers points 20..39; decodes as valid/normals but for the counters, "
                       "points_recovered and repair_blocks",
                numbered(file));
    }

    // ---- unusual ----
    {
        Packets file = {n0.back(), only1, n0.front()};
        file.insert(file.end(), stream.begin(), stream.end());
        w.write("unusual", "normals_before_stream_info",
                desc + ", with object 0's last NORMALS packet, object 1's and object 0's first (their own sequence "
                       "numbers) first, before the STREAM_INFO: all held (spec 24.2, 11.2), released in arrival order "
                       "when it arrives (11.1) and accepted, before any point has arrived (24.2: entries and points are "
                       "held apart, by index); their copies in the stream are duplicates; decodes as valid/normals",
                file);
    }
    {
        // Object 0's entries in runs no sender cuts, out of order; single-point runs (sent_count 0 and 1), a run
        // that overlaps others, and a copy of one run (the same payload, another sequence number).
        const std::vector<NormalEntry>& e0 = s.contents[0].normals;
        const uint32_t lengths[] = {1, 7, 41, 17, 3, 25, 13, 27, 9, 21, 44, 11, 19, 5, 26};
        std::vector<std::pair<uint32_t, uint32_t>> runs;
        for (uint32_t at = 0, i = 0; at < e0.size(); ++i) {
            const uint32_t n = std::min<uint32_t>(lengths[i % std::size(lengths)], uint32_t(e0.size()) - at);
            runs.push_back({at, n});
            at += n;
        }
        Rng rng(241);
        for (size_t i = runs.size(); i > 1; --i) std::swap(runs[i - 1], runs[rng.below(i)]);
        uint32_t surface_one = 0, sent_one = 0;
        while (e0[surface_one].sent) ++surface_one;
        while (!e0[sent_one].sent) ++sent_one;
        runs.insert(runs.begin(), {sent_one, 1});
        runs.insert(runs.begin(), {surface_one, 1});
        runs.insert(runs.begin() + 5, {120, 40});  // overlaps the runs around it
        const std::pair<uint32_t, uint32_t> copy = runs[7];
        runs.push_back(copy);  // a byte-identical copy
        Packets file = s.without_normals();
        std::string what;
        uint32_t sequence = 1000;
        for (auto [first, count] : runs) {
            const Packet p = s.packet(s.run(0, first, count), sequence++, 0);
            if (p.size() > kNormalsPacketSize) std::exit(1);
            file.push_back(p);
            what += (what.empty() ? "" : ", ") + run_text(first, count);
        }
        file.push_back(only1);
        w.write("unusual", "normals_runs_reordered",
                desc + ", with object 0's normal entries in NORMALS packets (sequence 1000..) of runs no sender cuts, "
                       "out of order: " + what + " (the first a point left to the surface, sent_count 0, the second a "
                       "point whose normal is sent, count 1 and sent_count 1; 120..159 overlaps the runs around it with "
                       "the same entries; the last a copy of the eighth), then object 1's NORMALS packet: a packet that "
                       "brings an entry not held is accepted, one that does not a duplicate (spec 24.2); decodes as "
                       "valid/normals but for the counters",
                file);
    }
    {
        // Padding bits set to 1 (spec 24.2: a decoder MUST NOT require them to be zero).
        Packets file = stream;
        std::string what;
        for (Packet& p : file) {
            if (p[6] != uint8_t(PacketType::Normals)) continue;
            const NormalsRun r = s.run_of(p);
            size_t sent = 0;
            for (const NormalEntry& e : r.entries) sent += e.sent;
            const size_t used = r.entries.size() + 2 * bits * sent;
            if (used % 8 == 0) continue;
            p[kHeaderSize + 8 + used / 8] |= uint8_t(0xFF << (used % 8));
            reseal(p);
            what += (what.empty() ? "" : "; ") + std::string("object ") + std::to_string(get16(p, 16)) + "'s run of points " +
                    run_text(r.first_index, r.entries.size()) + " (" + std::to_string(8 - used % 8) + " padding bits)";
        }
        if (what.empty()) std::exit(1);
        w.write("unusual", "normals_padding_nonzero",
                desc + ", with the padding bits after the last sent normal set to 1 in the NORMALS packets that have "
                       "any (resealed): " + what + " (spec 24.2: a decoder MUST NOT require the padding bits to be "
                       "zero); decodes as valid/normals",
                file);
    }
    {
        Packets file = s.without_normals();
        set_minor(file[0], 7);
        w.write("unusual", "normals_flag_in_1_7_stream",
                desc + ", without its NORMALS packets and with its STREAM_INFO saying 1.7: bit 9 of an entry's flags "
                       "is reserved in 1.7 and not read (spec 24.1, 9), so objects 0 and 1 have no surface normals: "
                       "objects without normals (their records carry none, attributes bit 0 clear), exact, as a 1.7 "
                       "encoder that set a reserved bit would send them",
                file);
    }
    {
        const NormalsStream s16 = normals_stream(16);
        std::string what;
        for (const Packet& p : s16.normals) {
            const NormalsRun r = s16.run_of(p);
            what += (what.empty() ? "" : "; ") + std::string("object ") + std::to_string(get16(p, 16)) + ", points " +
                    run_text(r.first_index, r.entries.size()) + ", " + entries_text(r.entries) + " (" +
                    std::to_string(p.size()) + " bytes)";
        }
        w.write("unusual", "normals_16_bit",
                "the surface-normals stream made at normal_bits 16 (the largest: sent normals of 2 x 16 bits; the "
                "same points, triangles and entries, the sent normals quantized at 16 bits), packets in stream order; "
                "its NORMALS packets: " + what,
                s16.all());
    }

    // ---- faulty: decoded without a rejection, but not complete or not conforming (spec 24.4) ----
    w.write("faulty", "normals_incomplete",
            desc + ", with object 0's last NORMALS packet (" + run_text_of(last0) + ") lost: no rejection; object 0's "
                   "normal entries not complete (spec 24.4: complete only when the entries of all its points are "
                   "held); the stream is not complete and does not conform",
            without({last0}));
    w.write("faulty", "normals_connectivity_lost",
            desc + ", with object 1's CONNECTIVITY packet lost: no rejection; object 1 holds every point and every "
                   "normal entry but is not exact (spec 19.4), so no surface normal is listed (its surface null; a "
                   "receiver shows its estimate, 24.4); the stream is not complete",
            without(NormalsStream::of(s.connectivity, 1)));
    {
        // Object 1's middle vertex, which no triangle uses (its surface normal undefined; the reference
        // encoder sends its normal), left to the surface: it is not part of the exact object (spec 19.4), so
        // the recording conforms (spec 24.4, 11.5).
        std::vector<std::array<uint32_t, 3>> positions;
        for (const QuantizedPoint& q : s.contents[1].points) positions.push_back(q.position);
        const std::vector<char> defined = surface_normal_defined(positions, s.triangles[1]);
        uint32_t lone = 0;
        while (lone < defined.size() && defined[lone]) ++lone;
        if (lone == defined.size() || !s.contents[1].normals[lone].sent) std::exit(1);
        for (const Triangle& t : s.triangles[1])
            if (t[0] == lone || t[1] == lone || t[2] == lone) std::exit(1);
        NormalsRun r = run1;
        r.entries[lone - r.first_index] = NormalEntry{};
        w.write("unusual", "normals_unused_point_left_to_surface",
                desc + ", with object 1's NORMALS packet re-encoded with the entry of point " + std::to_string(lone) +
                    " (the panel's middle vertex, which no triangle uses: its surface normal is undefined, spec 24.3) "
                    "\"left to the surface\" instead of sent: point " + std::to_string(lone) + "'s surface normal is "
                    "listed as null; the point is not part of the exact object (spec 19.4), so the recording conforms "
                    "(spec 24.4: only a point that a triangle of the exact layer uses must not be left to an undefined "
                    "surface normal)",
                replaced(only1, s.packet(r, 0, 1)));
    }
    {
        // The panel's fin flattened: the tip, used by the degenerate fin triangle alone, has an undefined surface
        // normal (spec 24.3: no triangle contributes).
        const NormalsStream flat = normals_stream(10, true);
        std::vector<std::array<uint32_t, 3>> positions;
        for (const QuantizedPoint& q : flat.contents[1].points) positions.push_back(q.position);
        const std::vector<char> defined = surface_normal_defined(positions, flat.triangles[1]);
        std::vector<uint32_t> undefined_used;
        for (uint32_t i = 0; i < defined.size(); ++i) {
            if (defined[i]) continue;
            for (const Triangle& t : flat.triangles[1])
                if (t[0] == i || t[1] == i || t[2] == i) {
                    undefined_used.push_back(i);
                    break;
                }
        }
        const Packets flat_normals1 = NormalsStream::of(flat.normals, 1);
        if (undefined_used.size() != 1 || flat_normals1.size() != 1 || !flat.contents[1].normals[undefined_used[0]].sent)
            std::exit(1);
        const uint32_t tip = undefined_used[0];
        const std::string flat_desc =
            "the surface-normals stream with the panel's fin flattened (object 1; its tip, point " + std::to_string(tip) +
            ", moved onto the line of its edge: the quantized position 2 q0 - q1 of the edge's points, so that the fin "
            "triangle has m = 0 at each corner, spec 24.3): the tip, which no other triangle uses, has an undefined "
            "surface normal, and the reference encoder sends its normal (spec 24.5); the points 0 and 1 of the grid get "
            "theirs from the grid's triangles alone (object 1: " + entries_text(flat.contents[1].normals) + ")";
        w.write("unusual", "normals_degenerate_triangle",
                flat_desc + ", packets in stream order: both surface objects exact (a degenerate triangle is a triangle "
                            "of the exact layer, spec 19.2), the tip's surface normal listed as null (undefined), its "
                            "entry sent; the recording conforms",
                flat.all());
        NormalsRun r = flat.run_of(flat_normals1[0]);
        r.entries[tip - r.first_index] = NormalEntry{};
        Packets file = flat.all();
        for (Packet& p : file)
            if (p == flat_normals1[0]) {
                Packet q = flat.packet(r, 0, 1);
                restamp_packet(q, get32(p, 12));
                p = q;
            }
        w.write("faulty", "normals_surface_undefined",
                flat_desc + ", with object 1's NORMALS packet re-encoded with the tip's entry \"left to the surface\" "
                            "instead of sent: no rejection (the packet is well formed); the tip's surface normal listed "
                            "as null (undefined); the recording does not conform (spec 24.4, 11.5: no point of the exact "
                            "layer left to its surface whose surface normal is undefined; a receiver shows (0, 0, 1) there)",
                file);
    }

    // ---- faulty: the entry's flag (spec 24.1, 5.3, 5.4) ----
    const std::string si_copy = desc + ", then (sequence 1000) a copy of its STREAM_INFO with ";
    auto info_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet p = info;
        edit(p);
        reseal(p);
        return after_stream(p);
    };
    w.write("faulty", "normals_entry_point_set",
            si_copy + "object 2's (the point set's, no ellipsoids) flags 0x0300 (bits 8 and 9): rejected, malformed "
                      "payload (spec 24.1: an entry with the surface-normals flag MUST have kind 0)",
            info_edited([](Packet& p) { put16(p, entry_flags(2), 0x0300); }));
    w.write("faulty", "normals_entry_without_exact_layer",
            si_copy + "object 0's flags 0x0200 (bit 8 cleared, bit 9 set): rejected, malformed payload (spec 24.1: an "
                      "entry with the surface-normals flag MUST have bit 8, an exact layer)",
            info_edited([](Packet& p) { put16(p, entry_flags(0), 0x0200); }));
    w.write("faulty", "normals_entry_with_normal_attribute",
            si_copy + "object 0's attributes 1 (bit 0, normal, set): rejected, malformed payload (spec 24.1: an entry "
                      "with the surface-normals flag MUST have attributes bit 0 clear)",
            info_edited([](Packet& p) { p[entry_attributes(0)] = 1; }));
    w.write("faulty", "normals_entry_flag_contradicts",
            si_copy + "object 0's flags 0x0100 (bit 9 cleared: a well-formed entry without surface normals) where the "
                      "accepted one says 0x0300: rejected, stream mismatch (spec 24.1, 5.4: the flag is compared)",
            info_edited([](Packet& p) { put16(p, entry_flags(0), 0x0100); }));
    w.write("faulty", "normals_entry_in_1_7_packet",
            si_copy + "its version 1.7: bit 9 is not read from it (spec 24.1, 9), so objects 0 and 1 have no surface "
                      "normals there, which contradicts the accepted entries: rejected, stream mismatch (5.4)",
            info_edited([](Packet& p) { p[5] = 7; }));
    {
        Packets file = stream;
        set_minor(file[0], 7);
        w.write("faulty", "normals_flag_in_1_7_packet",
                desc + ", with its STREAM_INFO saying 1.7: bit 9 is not read (spec 24.1, 9), so objects 0 and 1 have "
                       "no surface normals (decoded as objects without normals, exact), and each NORMALS packet is "
                       "rejected, malformed payload (spec 24.2, step 13: the object does not have surface normals)",
                file);
    }

    // ---- faulty: NORMALS packets (spec 24.2) ----
    const std::string copy1 = desc + ", then (sequence 1000) a copy of object 1's NORMALS packet (" + run_text_of(only1) + ")";
    auto only1_edited = [&](const std::function<void(Packet&)>& edit) {
        Packet p = only1;
        edit(p);
        reseal(p);
        return p;
    };
    auto only1_payload = [&](const std::function<void(std::vector<uint8_t>&)>& edit) {
        std::vector<uint8_t> payload = payload_of(only1);
        edit(payload);
        return with_payload(only1, payload);
    };
    w.write("faulty", "normals_payload_short",
            copy1 + " cut to a payload of 7 bytes: rejected, malformed payload (spec 24.2, step 11: shorter than 8 bytes)",
            after_stream(only1_payload([](std::vector<uint8_t>& p) { p.resize(7); })));
    const Packet count_zero = with_payload(only1, raw_normals_payload(0, 0, 0, {}, {}, bits));
    w.write("faulty", "normals_count_zero",
            desc + ", then (sequence 1000) a NORMALS packet of object 1 with first_index 0, count 0, sent_count 0 and "
                   "no bits (an 8-byte payload, the length 8 + ceil((0 + 0) / 8) agrees): rejected, malformed payload "
                   "(spec 24.2, step 11: count 0)",
            after_stream(count_zero));
    {
        std::array<uint32_t, 2> u{};
        for (const NormalEntry& e : run1.entries)
            if (e.sent) {
                u = e.normal;
                break;
            }
        // Before the STREAM_INFO, so that the step matters: its flags cannot add up to sent_count, so step 13
        // would reject it too, but only once its entry has arrived (a decoder that left the check to step 13
        // would hold it).
        w.write("faulty", "normals_sent_count_past_count",
                "a NORMALS packet of object 1 (sequence 1000) with first_index 0, count 1, sent_count 2, its one flag 1 "
                "and two normals (" + std::to_string(u[0]) + ", " + std::to_string(u[1]) + " each; a payload of 8 + "
                "ceil((1 + 2 x 2 x 10) / 8) = 14 bytes, the length agrees) first, before the STREAM_INFO of " + desc +
                    ": rejected when it arrives, malformed payload (spec 24.2, step 11, whether or not a stream info "
                    "has arrived: sent_count > count); nothing held",
                before_info(with_payload(only1, raw_normals_payload(0, 1, 2, {true}, {u, u}, bits))));
    }
    w.write("faulty", "normals_index_overflow",
            copy1 + " with first_index " + std::to_string(uint64_t(1) << 32) + " - " + std::to_string(run1.entries.size()) +
                " = " + std::to_string((uint64_t(1) << 32) - run1.entries.size()) + ": first_index + count = 2^32 > 2^32 - 1 "
                "(0 in 32-bit arithmetic): rejected, malformed payload (spec 24.2, step 11: computed without overflow)",
            after_stream(only1_edited([&](Packet& p) { put32(p, kNormalsFirst, uint32_t((uint64_t(1) << 32) - run1.entries.size())); })));
    w.write("faulty", "normals_malformed_before_stream_info",
            "the NORMALS packet of normals_count_zero (sequence 1000) first, before the STREAM_INFO of " + desc +
                ": rejected when it arrives, malformed payload (spec 24.2: step 11 is made whether or not a stream info "
                "has arrived, before the packet can be held); nothing held",
            before_info(count_zero));
    const Packet unknown = only1_edited([](Packet& p) { put16(p, 16, 3); });
    w.write("faulty", "normals_unknown_object",
            copy1 + " sent for object 3 of the 3-object stream: rejected, unknown object (spec 24.2, 11.1 step 12)",
            after_stream(unknown));
    w.write("faulty", "normals_held_unknown_object",
            "the copy of normals_unknown_object (object 3, sequence 1000) first, before the STREAM_INFO of " + desc +
                ": held (its fixed fields are well formed; spec 24.2, 11.2), then rejected when the STREAM_INFO is "
                "accepted, unknown object (11.1: held packets naming an object beyond the table are rejected first)",
            before_info(unknown));
    w.write("faulty", "normals_object_without_flag",
            desc + ", then (sequence 1000) a NORMALS packet of object 1's entries of points 0..19 sent for object 2 "
                   "(the point set, 20 points, no surface normals): rejected, malformed payload (spec 24.2, step 13: "
                   "the object does not have surface normals)",
            after_stream(s.packet(s.run(1, 0, 20), 0, 2)));
    w.write("faulty", "normals_length_mismatch",
            copy1 + " with one byte (00) more: rejected, malformed payload (spec 24.2, step 13: payload_length is not "
                    "8 + ceil((count + 2 N sent_count) / 8))",
            after_stream(only1_payload([](std::vector<uint8_t>& p) { p.push_back(0); })));
    {
        // A flag of value 1 made 0: the flags then add up to sent_count - 1 (the length still agrees).
        size_t k = 0;
        while (!run1.entries[k].sent) ++k;
        w.write("faulty", "normals_flags_not_sent_count",
                copy1 + " with the flag of point " + std::to_string(run1.first_index + k) + " (its first point whose "
                        "normal is sent) made 0 (the length, which depends on count and sent_count, still agrees): "
                        "rejected, malformed payload (spec 24.2, step 13: the number of flags of value 1 is not sent_count)",
                after_stream(only1_edited([&](Packet& p) { p[kNormalsBits + k / 8] &= uint8_t(~(1u << (k % 8))); })));
    }
    const Packet past = [&] {
        Packet p = last0;
        put32(p, kNormalsFirst, last_run0.first_index + 1);
        reseal(p);
        return p;
    }();
    w.write("faulty", "normals_index_out_of_range",
            desc + ", then (sequence 1000) a copy of object 0's last NORMALS packet (" + run_text_of(last0) +
                ") with first_index " + std::to_string(last_run0.first_index + 1) + ": its last point 258 is not below "
                "point_count 258: rejected, index out of range (spec 24.2, step 14)",
            after_stream(past));
    w.write("faulty", "normals_held_out_of_range",
            "the copy of normals_index_out_of_range (sequence 1000) first, before the STREAM_INFO of " + desc +
                ": held (its fixed fields are well formed), then, when the STREAM_INFO releases it, rejected, index out "
                "of range (11.1 step 14)",
            before_info(past));
    {
        size_t k = 0;
        while (!run1.entries[k].sent) ++k;
        NormalsRun r = run1;
        r.entries[k].normal[0] ^= 1;
        w.write("faulty", "normals_entry_contradicts",
                desc + ", then (sequence 1000) object 1's NORMALS packet re-encoded with the u of point " +
                    std::to_string(run1.first_index + k) + "'s sent normal " + std::to_string(r.entries[k].normal[0]) +
                    " where it is " + std::to_string(run1.entries[k].normal[0]) + ": rejected, stream mismatch (spec "
                    "24.2, step 15: each entry identical to the one held, both sent with the same u and v)",
                after_stream(s.packet(r, 0, 1)));
        NormalsRun r2 = run1;
        r2.entries[k] = NormalEntry{};
        w.write("faulty", "normals_surface_contradicts_sent",
                desc + ", then (sequence 1000) object 1's NORMALS packet re-encoded with point " +
                    std::to_string(run1.first_index + k) + "'s entry \"left to the surface\" where the held one is "
                    "sent (sent_count one less, " + std::to_string(2 * bits) + " bits shorter): rejected, stream "
                    "mismatch (spec 24.2, step 15)",
                after_stream(s.packet(r2, 0, 1)));
        size_t j = 0;
        while (run1.entries[j].sent) ++j;
        NormalsRun r3 = run1;
        r3.entries[j].sent = true;
        r3.entries[j].normal = {uint32_t((1u << bits) / 2), uint32_t((1u << bits) / 2)};
        w.write("faulty", "normals_sent_contradicts_surface",
                desc + ", then (sequence 1000) object 1's NORMALS packet re-encoded with point " +
                    std::to_string(run1.first_index + j) + "'s entry sent, (" + std::to_string(r3.entries[j].normal[0]) +
                    ", " + std::to_string(r3.entries[j].normal[1]) + "), where the held one is \"left to the surface\": "
                    "rejected, stream mismatch (spec 24.2, step 15)",
                after_stream(s.packet(r3, 0, 1)));
    }
    {
        // Right after object 0's first NORMALS packet, a run across its end with its first entry changed.
        const NormalsRun first_run = s.run_of(n0[0]);
        const uint32_t end = first_run.first_index + uint32_t(first_run.entries.size());
        NormalsRun r = s.run(0, end - 4, 12);
        r.entries[0].sent = !r.entries[0].sent;
        r.entries[0].normal = r.entries[0].sent ? std::array<uint32_t, 2>{uint32_t((1u << bits) / 2), 0} : std::array<uint32_t, 2>{};
        Packets file;
        for (const Packet& p : stream) {
            file.push_back(p);
            if (p == n0[0]) file.push_back(s.packet(r, 1000, 0));
        }
        w.write("faulty", "normals_contradicts_partly_new",
                desc + ", with, right after object 0's first NORMALS packet (points " +
                    run_text(first_run.first_index, first_run.entries.size()) + ") and before the second, a NORMALS "
                    "packet (sequence 1000) of points " + run_text(end - 4, 12) + " whose entry of point " +
                    std::to_string(end - 4) + " is " + (r.entries[0].sent ? "sent" : "\"left to the surface\"") +
                    " where the held one is " + (r.entries[0].sent ? "\"left to the surface\"" : "sent") +
                    ": rejected, stream mismatch (spec 24.2: nothing of the packet is kept: the entries of points " +
                    run_text(end, 8) + ", not held then, arrive with the next packet)",
                file);
    }
}

}  // namespace

// ---- Format 1.10: cameras and punctual lights (spec 26) ----

// The viewed room: one object (6 ellipsoids, 40 points with normals, packet size 200) shown by node
// 0 'Room'; node 1 'Eye' (child of 0) with camera 0; node 2 'Top' with camera 1 and light 0; node 3
// 'Bulb' (child of 0) with light 1; node 4 'Lamp' (child of 3) with light 2. Camera 2 is named by no
// node.
SceneDescription viewed_room() {
    SceneDescription s;
    auto node = [&](const char* name, uint16_t parent, uint16_t mesh, uint16_t camera, uint16_t light, float y) {
        SceneNode n;
        n.index = uint16_t(s.nodes.size());
        n.name = name;
        n.parent = parent;
        n.mesh = mesh;
        n.camera = camera;
        n.light = light;
        n.translation = {0, y, 0};
        s.nodes.push_back(n);
    };
    node("Room", kNone, 0, kNone, kNone, 0);
    node("Eye", 0, kNone, 0, kNone, 1.5f);
    node("Top", kNone, kNone, 1, 0, 10);
    node("Bulb", 0, kNone, kNone, 1, 2.5f);
    node("Lamp", 3, kNone, kNone, 2, -0.5f);
    SceneMesh mesh;
    mesh.index = 0;
    mesh.name = "Room";
    mesh.primitives.push_back({0, kNone});
    s.meshes = {mesh};
    SceneCamera eye;
    eye.name = "Eye camera";
    eye.projection = CameraProjection::Perspective;
    eye.a = 1.5f, eye.b = 0.8f, eye.znear = 0.1f, eye.zfar = 100;
    SceneCamera top;
    top.name = "Plan";
    top.projection = CameraProjection::Orthographic;
    top.a = 2, top.b = 1.5f, top.znear = 0, top.zfar = 50;
    SceneCamera spare;  // infinite, without aspect ratio, named by no node
    spare.projection = CameraProjection::Perspective;
    spare.a = 0, spare.b = 1.2f, spare.znear = 0.05f, spare.zfar = 0;
    s.cameras = {eye, top, spare};
    SceneLight sun;
    sun.name = "Sun";
    sun.type = LightType::Directional;
    sun.color = {1, 0.9f, 0.75f};
    sun.intensity = 3;
    SceneLight bulb;
    bulb.name = "Bulb";
    bulb.type = LightType::Point;
    bulb.color = {1, 1, 1};
    bulb.intensity = 40;
    bulb.range = 10;
    SceneLight lamp;
    lamp.name = "Lamp";
    lamp.type = LightType::Spot;
    lamp.color = {0.5f, 0.5f, 1};
    lamp.intensity = 25;
    lamp.inner_cone = 0.2f, lamp.outer_cone = 0.6f;
    s.lights = {sun, bulb, lamp};
    return s;
}

struct ViewedStream {
    Stream geometry;
    ScenePackets scene;  // SCENE, CAMERA and LIGHT packets
    Packets all() const {
        Packets out = geometry.all();
        out.insert(out.end(), scene.scene.begin(), scene.scene.end());
        out.insert(out.end(), scene.cameras_lights.begin(), scene.cameras_lights.end());
        return out;
    }
};

ViewedStream make_viewed_stream(const SceneDescription& scene) {
    ViewedStream s;
    StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 6, 40, kAttrNormal)}, 200);
    Rng rng(101);
    s.geometry.contents.push_back(make_content(info, info.objects[0], rng));
    s.geometry.info = info;
    if (packetize_stream(info, s.geometry.contents, kStreamId, s.geometry.packets) != Error::Ok ||
        packetize_scene(scene, 200, kStreamId, uint32_t(s.geometry.all().size()), s.scene) != Error::Ok) {
        std::cerr << "make_vectors: packetize failed (cameras and lights)\n";
        std::exit(1);
    }
    return s;
}

// `stream`, then a copy of its packet `k` (sequence 900) with `edit` made to it (resealed).
Packets with_edited_copy(const Packets& stream, size_t k, const std::function<void(Packet&)>& edit) {
    Packets sent = stream;
    Packet p = stream[k];
    restamp_packet(p, 900);
    edit(p);
    reseal(p);
    sent.push_back(p);
    return sent;
}

// A CAMERA or LIGHT packet (format 1.10, stream-level, skippable) around a payload as given; another
// stream-level type of a later version with `minor`.
Packet viewed_packet(PacketType type, const std::vector<uint8_t>& payload, uint32_t sequence, uint8_t minor = kCameraLightMinor) {
    PacketHeader h;
    h.version_minor = minor;
    h.type = uint8_t(type);
    h.flags = kFlagSkippable;
    h.stream_id = kStreamId;
    h.sequence = sequence;
    h.object_id = kStreamObjectId;
    return write_packet(h, payload);
}

void camera_light_vectors(Writer& w) {
    const SceneDescription scene = viewed_room();
    const ViewedStream base = make_viewed_stream(scene);
    const Packets stream = base.all();
    const Packets geometry = base.geometry.all();
    const size_t scene_at = geometry.size(), viewed_at = scene_at + base.scene.scene.size();
    if (base.scene.cameras_lights.size() != 6) {
        std::cerr << "make_vectors: the room takes " << base.scene.cameras_lights.size() << " CAMERA and LIGHT packets, not 6\n";
        std::exit(1);
    }
    const std::string room =
        "the viewed room of valid/camera_light (format 1.10: 5 nodes, node 0 'Room' showing mesh 0 of object 0; "
        "3 cameras, 3 lights in 6 CAMERA and LIGHT packets), packets in stream order";
    w.write("valid", "camera_light",
            "format 1.10 (spec 26): a room: object 0 (6 ellipsoids, 40 points with normals, packet size 200) shown by "
            "node 0 'Room'; node 1 'Eye' (under 0) with camera 0, node 2 'Top' with camera 1 and light 0, node 3 "
            "'Bulb' (under 0) with light 1, node 4 'Lamp' (under 3) with light 2 (their SCENE packets say 1.10); "
            "camera 0 'Eye camera' perspective (aspect ratio 1.5, yfov 0.8, znear 0.1, zfar 100), camera 1 'Plan' "
            "orthographic (xmag 2, ymag 1.5, znear 0, zfar 50), camera 2 (no name) perspective without aspect ratio "
            "and infinite (zfar 0), named by no node; light 0 'Sun' directional (colour 1, 0.9, 0.75, intensity 3), "
            "light 1 'Bulb' point (intensity 40, range 10), light 2 'Lamp' spot (colour 0.5, 0.5, 1, intensity 25, "
            "cone angles 0.2 and 0.6); every camera and light shown, on its nodes",
            stream);

    // ---- unusual ----
    {
        Packets sent(stream.begin() + long(viewed_at), stream.end());
        sent.insert(sent.end(), stream.begin(), stream.begin() + long(viewed_at));
        w.write("unusual", "camera_light_before_scene",
                "the packets of the viewed room with the 6 CAMERA and LIGHT packets first, before the STREAM_INFO and "
                "the SCENE packets: stream-level, accepted at once (spec 26.2, 26.3); decodes as valid/camera_light",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t i = scene_at; i < viewed_at; ++i) {
            sent[i][5] = kMorphMinor;  // 1.6: the records' camera and light fields are bytes of a later version
            reseal(sent[i]);
        }
        w.write("unusual", "camera_light_scene_1_6",
                room + ", with its SCENE packets saying 1.6 instead of 1.10: the bytes after each node record's skin "
                       "field (0xFFFF) are fields of a later version, ignored (spec 26.1), so no node has a camera or "
                       "a light; the 6 CAMERA and LIGHT packets are accepted and shown on no node",
                sent);
    }
    {
        Packets sent = stream;
        SceneCamera wide = scene.cameras[0];
        wide.index = 0, wide.camera_count = 3;
        wide.b = std::bit_cast<float>(0x40490FDAu);  // the largest f32 below pi
        SceneLight open = scene.lights[2];
        open.index = 2, open.light_count = 3;
        open.inner_cone = 0;
        open.outer_cone = std::bit_cast<float>(0x3FC90FDAu);  // the largest f32 not above pi / 2
        sent[viewed_at] = viewed_packet(PacketType::Camera, encode_camera_payload(wide), get32(sent[viewed_at], 12));
        sent[viewed_at + 5] = viewed_packet(PacketType::Light, encode_light_payload(open), get32(sent[viewed_at + 5], 12));
        Packet again = sent[viewed_at + 3];  // light 0 again, its range -0: the same number as 0
        put32(again, kHeaderSize + 24, 0x80000000u);
        reseal(again);
        restamp_packet(again, 900);
        sent.push_back(again);
        w.write("unusual", "camera_light_limits",
                room + ", with camera 0's yfov the largest f32 below pi (40490FDA, 3.1415925) and light 2's cone "
                       "angles 0 and the largest f32 not above pi / 2 (3FC90FDA): accepted (spec 26.2 rule 5, 26.3 "
                       "rule 7); and light 0 again (sequence 900) with range -0 (80000000): 0 as a number, so the "
                       "same light, a duplicate",
                sent);
    }

    // ---- faulty ----
    auto camera_edit = [&](size_t k, const std::function<void(Packet&)>& edit) {
        return with_edited_copy(stream, viewed_at + k, edit);
    };
    const size_t C = kHeaderSize;  // payload offsets below
    struct Case {
        const char* name;
        size_t packet;  // 0..2 cameras, 3..5 lights
        const char* what;
        std::function<void(Packet&)> edit;
        const char* reason;
    };
    const std::vector<Case> cases = {
        {"camera_yfov_nan", 0, "camera 0 again with yfov a quiet NaN (7FC00000)", [&](Packet& p) { put32(p, C + 12, 0x7FC00000u); }, "malformed payload (spec 26.2 rule 4)"},
        {"camera_yfov_pi", 0, "camera 0 again with yfov the f32 nearest pi (40490FDB, above pi)", [&](Packet& p) { put32(p, C + 12, 0x40490FDBu); }, "malformed payload (spec 26.2 rule 5: yfov >= pi)"},
        {"camera_znear_zero", 0, "camera 0 (perspective) again with znear 0", [&](Packet& p) { put32(p, C + 16, 0); }, "malformed payload (spec 26.2 rule 5: znear <= 0)"},
        {"camera_zfar_at_znear", 1, "camera 1 (orthographic) again with zfar 0, equal to its znear", [&](Packet& p) { put32(p, C + 20, 0); }, "malformed payload (spec 26.2 rule 6: zfar <= znear)"},
        {"camera_xmag_negative", 1, "camera 1 (orthographic) again with xmag -2", [&](Packet& p) { put32(p, C + 8, std::bit_cast<uint32_t>(-2.0f)); }, "malformed payload (spec 26.2 rule 6: xmag <= 0)"},
        {"camera_projection_2", 2, "camera 2 again with projection 2", [&](Packet& p) { p[C + 4] = 2; }, "malformed payload (spec 26.2 rule 3)"},
        {"camera_index_past_count", 2, "camera 2 again with index 3, its camera_count", [&](Packet& p) { p[C] = 3; }, "malformed payload (spec 26.2 rule 2)"},
        {"camera_length", 0, "camera 0 again with name_length 9 for its 10-byte name", [&](Packet& p) { p[C + 5] = 9; }, "malformed payload (spec 26.2 rule 1)"},
        {"camera_count_differs", 2, "camera 2 again with camera_count 65535", [&](Packet& p) { p[C + 2] = 0xFF, p[C + 3] = 0xFF; }, "stream mismatch (spec 26.2: the same camera_count in every CAMERA packet)"},
        {"camera_differs", 0, "camera 0 again with yfov 0.9 instead of 0.8", [&](Packet& p) { put32(p, C + 12, std::bit_cast<uint32_t>(0.9f)); }, "stream mismatch (spec 26.2: a camera received twice is identical)"},
        {"light_type_3", 3, "light 0 again with light_type 3", [&](Packet& p) { p[C + 4] = 3; }, "malformed payload (spec 26.3 rule 3)"},
        {"light_color_above_1", 3, "light 0 again with a red of 1.5", [&](Packet& p) { put32(p, C + 8, std::bit_cast<uint32_t>(1.5f)); }, "malformed payload (spec 26.3 rule 5)"},
        {"light_intensity_infinite", 4, "light 1 again with intensity +infinity (7F800000)", [&](Packet& p) { put32(p, C + 20, 0x7F800000u); }, "malformed payload (spec 26.3 rule 4)"},
        {"light_directional_range", 3, "light 0 (directional) again with range 5", [&](Packet& p) { put32(p, C + 24, std::bit_cast<uint32_t>(5.0f)); }, "malformed payload (spec 26.3 rule 6)"},
        {"light_point_cone", 4, "light 1 (point) again with outer_cone_angle 0.5", [&](Packet& p) { put32(p, C + 32, std::bit_cast<uint32_t>(0.5f)); }, "malformed payload (spec 26.3 rule 6)"},
        {"light_cones_out_of_order", 5, "light 2 (spot) again with inner_cone_angle 0.6, equal to its outer one", [&](Packet& p) { put32(p, C + 28, std::bit_cast<uint32_t>(0.6f)); }, "malformed payload (spec 26.3 rule 7)"},
        {"light_outer_above_half_pi", 5, "light 2 (spot) again with outer_cone_angle the f32 nearest pi / 2 (3FC90FDB, above pi / 2)", [&](Packet& p) { put32(p, C + 32, 0x3FC90FDBu); }, "malformed payload (spec 26.3 rule 7)"},
    };
    for (const Case& c : cases)
        w.write("faulty", c.name,
                room + ", then " + c.what + " (sequence 900): rejected as " + c.reason + "; the rest decodes as valid/camera_light",
                camera_edit(c.packet, c.edit));
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(viewed_at + 4));
        w.write("faulty", "light_missing",
                room + ", without the LIGHT packet of light 1: node 3 'Bulb' is shown without its light (spec 26.4); "
                       "the stream is not complete (light 1 of 3 missing), so the recording does not conform",
                sent);
    }
    {
        Packets sent(stream.begin(), stream.begin() + long(viewed_at));
        for (size_t k = 0; k < 6; ++k) {
            Packet p = stream[viewed_at + k];
            p[C + 2] = 0xFF, p[C + 3] = 0xFF;  // camera_count or light_count 65535
            reseal(p);
            sent.push_back(p);
        }
        w.write("faulty", "camera_light_count_huge",
                room + ", with camera_count and light_count 65535 in every CAMERA and LIGHT packet: accepted (a decoder "
                       "allocates nothing for the records that did not arrive, spec 26.2), every camera and light "
                       "shown, but cameras 3..65534 and lights 3..65534 are missing: the stream is not complete and "
                       "does not conform",
                sent);
    }
    {
        Packets sent = edit_node(stream, 1, [](SceneNode& n) { n.camera = 7; });
        for (size_t i = scene_at; i < viewed_at; ++i) {
            sent[i][5] = kCameraLightMinor;
            reseal(sent[i]);
        }
        w.write("faulty", "node_camera_past_table",
                room + ", with node 1's record naming camera 7, past the 3 cameras of the CAMERA packets: the SCENE "
                       "packet is accepted (spec 26.1: the field is not checked there) and node 1 is shown without a "
                       "camera (spec 26.4), but the recording does not conform",
                sent);
    }
}

// ---- Format 1.12: extras (spec 28) ----

// The room of the camera vectors with the extras of 7 targets: the asset, the scene, node 1 'Eye'
// (escapes, a surrogate pair, a null), node 3 'Bulb' (a 400-byte text in 3 fragments at packet size
// 200), mesh 0 (a string), camera 2 (a number) and light 0 (an array).
std::vector<SceneExtras> room_extras() {
    std::string long_text = "{\"description\":\"";
    while (long_text.size() < 390) long_text += "A bulb hangs from the ceiling of the room. ";
    long_text = long_text.substr(0, 390) + "\",\"watts\":60}";
    return {{ExtrasTarget::Asset, 0, "{\"copyright\":\"ellicast vectors\",\"tags\":[\"room\",\"lights\"]}"},
            {ExtrasTarget::Scene, 0, "{\"level\":3}"},
            {ExtrasTarget::Node, 1,
             "{\"id\":\"eye-1\",\"visible\":true,\"offset\":[0,1.5e-3,-2],\"note\":null,"
             "\"label\":\"caf\\u00e9 \\ud83d\\ude00\"}"},
            {ExtrasTarget::Node, 3, long_text},
            {ExtrasTarget::Mesh, 0, "\"the room's walls\""},
            {ExtrasTarget::Camera, 2, " 42 "},
            {ExtrasTarget::Light, 0, "[true,false,null]"}};
}

// An EXTRAS packet (format 1.12, stream-level, skippable) around a fragment as given.
Packet extras_packet(const ExtrasFragment& f, uint32_t sequence) {
    return viewed_packet(PacketType::Extras, encode_extras_payload(f), sequence, kExtrasMinor);
}

// The fragment of `e`'s text [from, to) with its description (text_count `count`).
ExtrasFragment extras_fragment(const SceneExtras& e, uint16_t count, size_t from, size_t to) {
    ExtrasFragment f;
    f.kind = e.kind;
    f.index = e.index;
    f.text_count = count;
    f.text_size = uint32_t(e.text.size());
    f.text_crc = crc32c(reinterpret_cast<const uint8_t*>(e.text.data()), e.text.size());
    f.offset = uint32_t(from);
    f.data.assign(e.text.begin() + long(from), e.text.begin() + long(to));
    return f;
}

// EXTRAS packets of `texts` as given (no check: faulty texts too), each cut into fragments of at most
// `per_packet` bytes, numbered from `sequence`; text_count `count`.
Packets extras_packets(const std::vector<SceneExtras>& texts, uint16_t count, size_t per_packet, uint32_t sequence) {
    Packets out;
    for (const SceneExtras& e : texts)
        for (size_t offset = 0; offset < e.text.size(); offset += per_packet)
            out.push_back(extras_packet(extras_fragment(e, count, offset, std::min(e.text.size(), offset + per_packet)),
                                        sequence++));
    return out;
}

void extras_vectors(Writer& w) {
    SceneDescription scene = viewed_room();
    scene.extras = room_extras();
    const ViewedStream base = make_viewed_stream(scene);
    Packets stream = base.all();
    const size_t extras_at = stream.size();
    stream.insert(stream.end(), base.scene.extras.begin(), base.scene.extras.end());
    constexpr size_t kPer = 200 - kPacketOverhead - kExtrasHeaderSize;  // 156 text bytes a packet
    // The reference packetizer's packets are the ones the spec's rules make of these texts.
    if (base.scene.extras.size() != 9 ||
        base.scene.extras != extras_packets(scene.extras, 7, kPer, get32(base.scene.extras[0], 12))) {
        std::cerr << "make_vectors: the room's extras are not the 9 EXTRAS packets expected\n";
        std::exit(1);
    }
    const std::string room =
        "the room of valid/extras (the viewed room of valid/camera_light with 7 extras texts in 9 EXTRAS packets "
        "at its end: the asset, the scene, node 1, node 3 in 3 fragments, mesh 0, camera 2, light 0)";
    w.write("valid", "extras",
            "format 1.12 (spec 28): the viewed room of valid/camera_light with the extras of 7 targets in 9 EXTRAS "
            "packets after its CAMERA and LIGHT packets (text_count 7): the asset (an object), the scene ({\"level\":3}), "
            "node 1 (an object with escapes, a surrogate pair and a null), node 3 (403 bytes in 3 fragments of 156, "
            "156 and 91 bytes), mesh 0 (a string), camera 2 (the number 42 with spaces around it) and light 0 (an "
            "array); every text complete",
            stream);

    // ---- unusual ----
    {
        Packets extras(stream.begin() + long(extras_at), stream.end());
        std::reverse(extras.begin(), extras.end());
        Packets sent;
        for (const Packet& p : extras) {
            sent.push_back(p);
            sent.push_back(p);  // the same packet again: a duplicate
        }
        sent.insert(sent.end(), stream.begin(), stream.begin() + long(extras_at));
        w.write("unusual", "extras_first",
                "the packets of valid/extras with its 9 EXTRAS packets first, in reverse order (node 3's fragments "
                "last first), each sent twice in a row, then the rest: every second copy a duplicate (spec 28.1 "
                "check 3); decodes as valid/extras",
                sent);
    }
    {
        const SceneExtras& bulb = scene.extras[3];
        Packets sent(stream.begin(), stream.begin() + long(extras_at));
        const Packets singles = extras_packets({scene.extras[0], scene.extras[1], scene.extras[2], scene.extras[4],
                                                scene.extras[5], scene.extras[6]},
                                               7, kPer, 100);
        sent.insert(sent.end(), singles.begin(), singles.end());
        // Node 3's text re-cut: [0, 100), [60, 210), [10, 50) (nothing new), [200, 340), [300, 403).
        for (const auto& [from, to] : std::vector<std::pair<size_t, size_t>>{{0, 100}, {60, 210}, {10, 50}, {200, 340}, {300, 403}})
            sent.push_back(extras_packet(extras_fragment(bulb, 7, from, to), uint32_t(200 + sent.size())));
        w.write("unusual", "extras_overlapping",
                "the room with its extras sent otherwise: the 6 one-fragment texts, then node 3's 403-byte text cut "
                "into fragments of bytes 0..99, 60..209, 10..49, 200..339 and 300..402: overlapping bytes are kept from their "
                "first copy (spec 28.1), the fragment of bytes 10..49 brings none and is a duplicate; decodes as "
                "valid/extras",
                sent);
    }
    {
        Packets sent = stream;
        for (size_t i = extras_at; i < sent.size(); ++i) {
            sent[i][kHeaderSize + 1] = 0xFF;  // reserved
            sent[i][kHeaderSize + 6] = 0xAB, sent[i][kHeaderSize + 7] = 0xCD;
            reseal(sent[i]);
        }
        w.write("unusual", "extras_reserved",
                room + ", with the reserved bytes 1 and 6..7 of every EXTRAS payload set (FF, AB CD): ignored "
                       "(spec 28.1); decodes as valid/extras",
                sent);
    }
    {
        std::string deepest(32, '[');
        deepest += std::string(32, ']');
        std::vector<SceneExtras> texts = scene.extras;
        texts[1].text = deepest;  // the scene's text: arrays 32 deep, the most allowed
        Packets sent(stream.begin(), stream.begin() + long(extras_at));
        const Packets extras = extras_packets(texts, 7, kPer, uint32_t(sent.size()));
        sent.insert(sent.end(), extras.begin(), extras.end());
        w.write("unusual", "extras_deepest",
                room + ", with the scene's text 32 arrays nested (the value depth 1, the innermost depth 32): "
                       "acceptable (spec 28.1); every text complete",
                sent);
    }

    // ---- faulty ----
    const size_t E = kHeaderSize;  // payload offsets below
    auto appended = [&](size_t k, const std::function<void(Packet&)>& edit) {
        return with_edited_copy(stream, extras_at + k, edit);
    };
    struct Case {
        const char* name;
        size_t packet;  // 0 asset, 1 scene, 2 node 1, 3..5 node 3, 6 mesh 0, 7 camera 2, 8 light 0
        const char* what;
        std::function<void(Packet&)> edit;
        const char* reason;
    };
    const std::vector<Case> cases = {
        {"extras_short", 0, "the asset's packet again with its payload cut to the 20 bytes of fixed fields",
         [&](Packet& p) {
             const std::vector<uint8_t> payload = payload_of(p);
             p = with_payload(p, std::vector<uint8_t>(payload.begin(), payload.begin() + 20));
         },
         "malformed payload (spec 28.1 rule 1)"},
        {"extras_kind_11", 6, "mesh 0's packet again with target_kind 11", [&](Packet& p) { p[E] = 11; }, "malformed payload (spec 28.1 rule 2)"},
        {"extras_scene_index_1", 1, "the scene's packet again with target_index 1", [&](Packet& p) { p[E + 2] = 1; }, "malformed payload (spec 28.1 rule 2)"},
        {"extras_text_count_zero", 1, "the scene's packet again with text_count 0", [&](Packet& p) { p[E + 4] = 0; }, "malformed payload (spec 28.1 rule 3)"},
        {"extras_text_size_huge", 3, "node 3's first fragment again with text_size 65537", [&](Packet& p) { put32(p, E + 8, 65537); }, "malformed payload (spec 28.1 rule 4)"},
        {"extras_past_text", 5, "node 3's last fragment (91 bytes) again at offset 313, so that it ends at 404, past the 403-byte text", [&](Packet& p) { put32(p, E + 16, 313); }, "malformed payload (spec 28.1 rule 5)"},
        {"extras_count_differs", 7, "camera 2's packet again with text_count 8", [&](Packet& p) { p[E + 4] = 8; }, "stream mismatch (spec 28.1 check 1)"},
        {"extras_crc_differs", 8, "light 0's packet again with another text_crc", [&](Packet& p) { put32(p, E + 12, get32(p, E + 12) ^ 1); }, "stream mismatch (spec 28.1 check 2: another description)"},
        {"extras_one_too_many", 6, "mesh 0's packet again as the text of node 2 (target_kind 2, index 2), an eighth target of a stream that announced 7", [&](Packet& p) { p[E] = 2, p[E + 2] = 2; }, "stream mismatch (spec 28.1 check 2: more targets than text_count)"},
    };
    for (const Case& c : cases)
        w.write("faulty", c.name,
                room + ", then " + c.what + " (sequence 900): rejected as " + c.reason + "; the rest decodes as valid/extras",
                appended(c.packet, c.edit));
    // Texts that pass every packet check but not the checks of a whole text (spec 28.1 checks 5 and 6).
    auto with_scene_text = [&](const std::string& text, bool wrong_crc) {
        std::vector<SceneExtras> texts = scene.extras;
        texts[1].text = text;
        Packets sent(stream.begin(), stream.begin() + long(extras_at));
        Packets extras = extras_packets(texts, 7, kPer, uint32_t(sent.size()));
        if (wrong_crc) {
            put32(extras[1], E + 12, get32(extras[1], E + 12) ^ 0x80000000u);
            reseal(extras[1]);
        }
        sent.insert(sent.end(), extras.begin(), extras.end());
        return sent;
    };
    w.write("faulty", "extras_crc_wrong",
            room + ", with the scene's one fragment carrying a text_crc that is not its text's: it completes the text, "
                   "whose CRC-32C does not match: rejected as stream mismatch (spec 28.1 check 5) and its bytes "
                   "discarded; the scene's text is held without a byte, not complete, so the stream is not complete",
            with_scene_text("{\"level\":3}", true));
    w.write("faulty", "extras_not_json",
            room + ", with the scene's text {\"level\":} (its CRC-32C right): the fragment that completes it is "
                   "rejected as malformed payload (spec 28.1 check 6: not one JSON text) and its bytes discarded",
            with_scene_text("{\"level\":}", false));
    w.write("faulty", "extras_duplicate_name",
            room + ", with the scene's text {\"a\":1,\"a\":2}: rejected as malformed payload when complete (spec "
                   "28.1 check 6: rule 6 of 18.2, two members of one name) and its bytes discarded",
            with_scene_text("{\"a\":1,\"a\":2}", false));
    w.write("faulty", "extras_too_deep",
            room + ", with the scene's text 33 arrays nested: rejected as malformed payload when complete (spec "
                   "28.1 check 6: deeper than 32) and its bytes discarded",
            with_scene_text(std::string(33, '[') + std::string(33, ']'), false));
    w.write("faulty", "extras_nan",
            room + ", with the scene's text {\"level\":NaN}: rejected as malformed payload when complete (spec 28.1 "
                   "check 6: NaN is no JSON) and its bytes discarded",
            with_scene_text("{\"level\":NaN}", false));
    {
        Packets sent = stream;
        sent.erase(sent.begin() + long(extras_at + 4));  // node 3's middle fragment
        w.write("faulty", "extras_fragment_missing",
                room + ", without node 3's middle fragment (bytes 156..311): node 3's text holds 247 of its 403 "
                       "bytes and is not complete (node 3 is written without extras, spec 28.3); no rejection, but "
                       "the stream is not complete, so the recording does not conform",
                sent);
    }
    {
        std::vector<SceneExtras> texts = scene.extras;
        texts[2].index = 9;  // node 1's text, for a node 9 of a 5-node table
        Packets sent(stream.begin(), stream.begin() + long(extras_at));
        const Packets extras = extras_packets(texts, 7, kPer, uint32_t(sent.size()));
        sent.insert(sent.end(), extras.begin(), extras.end());
        w.write("faulty", "extras_target_past_table",
                room + ", with node 1's text sent as node 9's, past the SCENE packets' node_count 5: every packet "
                       "accepted (spec 28.1 does not check the index against the table), the text shown on no "
                       "element (28.3), but the recording does not conform",
                sent);
    }
}

// ---- Format 1.13: required extensions (spec 29) ----

// A REQUIRED_EXTENSION packet (format 1.13, stream-level, skippable).
Packet required_packet(uint8_t count, uint8_t index, const std::string& name, uint32_t sequence) {
    return viewed_packet(PacketType::RequiredExtension, encode_required_extension_payload({count, index, name}), sequence,
                         kRequiredExtensionMinor);
}

void required_extension_vectors(Writer& w) {
    SceneDescription scene = viewed_room();
    scene.required_extensions = {"KHR_materials_unlit", "KHR_texture_transform"};
    const ViewedStream base = make_viewed_stream(scene);
    Packets stream = base.all();
    const size_t names_at = stream.size();
    const uint32_t sequence = uint32_t(names_at);
    // The reference packetizer's packets are the ones spec 29.1 makes of these names.
    const Packets expected = {required_packet(2, 0, "KHR_materials_unlit", sequence),
                              required_packet(2, 1, "KHR_texture_transform", sequence + 1)};
    if (base.scene.required_extensions != expected) {
        std::cerr << "make_vectors: the room's required extensions are not the 2 REQUIRED_EXTENSION packets expected\n";
        std::exit(1);
    }
    stream.insert(stream.end(), expected.begin(), expected.end());
    const Packets room(stream.begin(), stream.begin() + long(names_at));
    const std::string what =
        "the room of valid/required_extensions (the viewed room of valid/camera_light, then 2 REQUIRED_EXTENSION "
        "packets, name_count 2: KHR_materials_unlit at index 0, KHR_texture_transform at index 1)";
    w.write("valid", "required_extensions",
            "format 1.13 (spec 29): the viewed room of valid/camera_light with 2 REQUIRED_EXTENSION packets after its "
            "CAMERA and LIGHT packets (name_count 2): KHR_materials_unlit (index 0) and KHR_texture_transform (index "
            "1); every name held",
            stream);

    // ---- unusual ----
    {
        Packets sent;
        for (size_t k = stream.size(); k-- > names_at;) {
            Packet p = stream[k];
            p[kHeaderSize + 2] = 0xAB, p[kHeaderSize + 3] = 0xCD;  // reserved
            reseal(p);
            sent.push_back(p);
            sent.push_back(p);  // the same packet again: a duplicate
        }
        sent.insert(sent.end(), room.begin(), room.end());
        w.write("unusual", "required_extensions_first",
                "the packets of valid/required_extensions with its 2 REQUIRED_EXTENSION packets first, index 1 "
                "before index 0, each with its reserved bytes 2..3 set to AB CD (ignored) and sent twice in a row "
                "(every second copy a duplicate, spec 29.1 comparison 2), then the room; decodes as "
                "valid/required_extensions",
                sent);
    }
    {
        Packets sent = room;
        const std::string longest = "EXT_" + std::string(60, 'z');  // 64 bytes, the longest name
        sent.push_back(required_packet(3, 2, longest, 13));
        sent.push_back(required_packet(3, 0, "X", 14));  // 1 byte, the shortest
        sent.push_back(required_packet(3, 1, "x", 15));  // another name: case counts
        w.write("unusual", "required_extensions_limits",
                "the room, then 3 REQUIRED_EXTENSION packets of name_count 3: index 2 a 64-byte name (EXT_ and 60 "
                "times z, a 68-byte payload, the longest spec 29.1 allows), index 0 the 1-byte name X (a 5-byte "
                "payload, the shortest), index 1 the name x (another name than X: names compare byte for byte); "
                "every name held",
                sent);
    }

    // ---- faulty ----
    const size_t E = kHeaderSize;
    struct Case {
        const char* name;
        size_t packet;  // 0 KHR_materials_unlit, 1 KHR_texture_transform
        const char* what;
        std::function<void(Packet&)> edit;
        const char* reason;
    };
    auto renamed = [](const std::string& name) {
        return [name](Packet& p) {
            std::vector<uint8_t> payload = payload_of(p);
            payload.resize(4);
            payload.insert(payload.end(), name.begin(), name.end());
            p = with_payload(p, payload);
        };
    };
    const std::vector<Case> cases = {
        {"required_extension_short", 0, "index 0's packet again with its payload cut to its 4 bytes of fixed fields (no name)",
         [&](Packet& p) {
             const std::vector<uint8_t> payload = payload_of(p);
             p = with_payload(p, std::vector<uint8_t>(payload.begin(), payload.begin() + 4));
         },
         "malformed payload (spec 29.1 rule 1)"},
        {"required_extension_too_long", 1, "index 1's packet again with a 65-byte name (EXT_ and 61 times z; a 69-byte payload)",
         renamed("EXT_" + std::string(61, 'z')), "malformed payload (spec 29.1 rule 1)"},
        {"required_extension_count_zero", 0, "index 0's packet again with name_count 0", [&](Packet& p) { p[E] = 0; },
         "malformed payload (spec 29.1 rule 2)"},
        {"required_extension_index_past", 1, "index 1's packet again with name_index 2, not below name_count 2",
         [&](Packet& p) { p[E + 1] = 2; }, "malformed payload (spec 29.1 rule 2)"},
        {"required_extension_bad_byte", 0, "index 0's packet again with the name KHR-materials_unlit (a hyphen)",
         renamed("KHR-materials_unlit"), "malformed payload (spec 29.1 rule 3)"},
        {"required_extension_count_differs", 1, "index 1's packet again with name_count 3", [&](Packet& p) { p[E] = 3; },
         "stream mismatch (spec 29.1 comparison 1)"},
        {"required_extension_name_differs", 1, "index 1's packet again with the name KHR_texture_basisu",
         renamed("KHR_texture_basisu"), "stream mismatch (spec 29.1 comparison 2)"},
    };
    for (const Case& c : cases)
        w.write("faulty", c.name,
                what + ", then " + c.what + " (sequence 900): rejected as " + c.reason +
                    "; the rest decodes as valid/required_extensions",
                with_edited_copy(stream, names_at + c.packet, c.edit));
    {
        Packets sent = room;
        sent.push_back(stream[names_at]);
        sent.push_back(required_packet(2, 1, "KHR_materials_unlit", 900));
        sent.push_back(stream[names_at + 1]);
        w.write("faulty", "required_extension_listed_twice",
                "the room, index 0's packet (KHR_materials_unlit), then a packet of index 1 with the name "
                "KHR_materials_unlit again (sequence 900): rejected as stream mismatch (spec 29.1 comparison 3: the "
                "name is held at index 0), then index 1's own packet (KHR_texture_transform), accepted; decodes as "
                "valid/required_extensions but for the rejection",
                sent);
    }
    {
        Packets sent = room;
        sent.push_back(stream[names_at]);
        w.write("faulty", "required_extension_missing",
                what + ", without index 1's packet: no rejection; 1 of 2 names held, so the stream is not complete "
                       "and the recording does not conform (spec 29.2)",
                sent);
    }
}

// ---- Format 1.14: further texture-coordinate sets (spec 30) ----

// The texture-coordinate stream (packet size 160): object 0, a surface of 40 points with texture
// coordinates and two further sets (TEXCOORD_1 at 12 bits, TEXCOORD_2 at 8); object 1, a point set of
// 12 points with texture coordinates and colour and one further set (16 bits, a range of scale 0 in v);
// object 2, a surface of 10 points without texture coordinates.
struct TexcoordsStream {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    Packets base, points, texcoords;  // the STREAM_INFO and ELLIPSOIDS packets; POINTS; TEXCOORDS
    Packets all() const {
        Packets out = base;
        out.insert(out.end(), points.begin(), points.end());
        out.insert(out.end(), texcoords.begin(), texcoords.end());
        return out;
    }
};

TexcoordsStream texcoords_stream() {
    TexcoordsStream s;
    s.info = default_info({make_object({-1, -1, -1}, 2, 4, 40, kAttrTexcoord),
                           make_object({1, -1, -1}, 2, 0, 12, kAttrTexcoord | kAttrColor, ObjectKind::PointSet),
                           make_object({-1, 2, -1}, 1, 3, 10, 0)},
                          160);
    Rng rng(1400);
    for (const ObjectInfo& o : s.info.objects) s.contents.push_back(make_content(s.info, o, rng));
    auto set = [&](size_t points, uint8_t bits, std::array<float, 2> origin, std::array<float, 2> scale) {
        TexcoordSet t;
        t.range = {bits, origin, scale};
        const uint32_t max = (1u << bits) - 1;
        for (size_t i = 0; i < points; ++i)
            t.records.push_back({uint16_t(rng.uniform() * max + 0.5), uint16_t(scale[1] > 0 ? rng.uniform() * max + 0.5 : 0)});
        return t;
    };
    s.contents[0].texcoord_sets = {set(40, 12, {-0.5f, 0}, {2, 1}), set(40, 8, {0, 0.25f}, {0.5f, 0.5f})};
    s.contents[1].texcoord_sets = {set(12, 16, {3, 0.75f}, {1, 0})};
    StreamPackets packets;
    if (Error e = packetize_stream(s.info, s.contents, kStreamId, packets); e != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream (texcoords) failed: " << error_name(e) << "\n";
        std::exit(1);
    }
    uint32_t sequence = 0;
    auto number = [&](Packets p) {
        for (Packet& q : p) restamp_packet(q, sequence++);
        return p;
    };
    Packets base = packets.stream_info;
    base.insert(base.end(), packets.ellipsoids.begin(), packets.ellipsoids.end());
    s.base = number(base);
    s.points = number(packets.points);
    s.texcoords = number(packets.texcoords);
    return s;
}

// A TEXCOORDS payload written as given (spec 30.1): the fixed fields, then the records at `bits`.
std::vector<uint8_t> raw_texcoords_payload(uint32_t first, uint16_t count, uint8_t set, uint8_t set_count, uint8_t bits,
                                           std::array<float, 2> origin, std::array<float, 2> scale,
                                           const std::vector<std::array<uint16_t, 2>>& records) {
    TexcoordsRun run;
    run.first_index = first;
    run.set = set;
    run.set_count = set_count;
    run.range = {bits, origin, scale};
    run.records = records;
    std::vector<uint8_t> out = encode_texcoords_payload(run);
    out[4] = uint8_t(count);
    out[5] = uint8_t(count >> 8);
    return out;
}

void texcoords_vectors(Writer& w) {
    const TexcoordsStream s = texcoords_stream();
    const Packets stream = s.all();
    // Object 0: set 1 in 2 packets (36 + 4 records of 24 bits), set 2 in 1 (40 of 16); object 1: 1 (12 of 32).
    if (s.texcoords.size() != 4 || get16(s.texcoords[3], 16) != 1) {
        std::cerr << "make_vectors: the texture-coordinate stream has " << s.texcoords.size()
                  << " TEXCOORDS packets, not 4 with object 1's last\n";
        std::exit(1);
    }
    const size_t first_texcoords = s.base.size() + s.points.size();
    const std::string desc =
        "the texture-coordinate stream (format 1.14, spec 30; packet size 160): object 0, a surface of 4 ellipsoids "
        "and 40 points with texture coordinates and 2 further sets (TEXCOORD_1: 12 bits, origin (-0.5, 0), scale (2, 1), "
        "points 0..35 and 36..39 in 2 TEXCOORDS packets; TEXCOORD_2: 8 bits, origin (0, 0.25), scale (0.5, 0.5), one "
        "packet); object 1, a point set of 12 points with texture coordinates and RGB colour and 1 further set "
        "(TEXCOORD_1: 16 bits, origin (3, 0.75), scale (1, 0), one packet); object 2, a surface of 3 ellipsoids and 10 "
        "points without texture coordinates; the 4 TEXCOORDS packets (skippable, saying 1.14) after the POINTS packets";

    // ---- valid ----
    w.write("valid", "texcoords", desc + ", in stream order: every record of every set held", stream);

    // ---- unusual ----
    {
        // The TEXCOORDS packets first (held until the stream info), in reverse, each twice, reserved bytes set.
        Packets sent;
        for (size_t k = s.texcoords.size(); k-- > 0;) {
            Packet p = s.texcoords[k];
            p[kHeaderSize + 9] = 0x5A, p[kHeaderSize + 10] = 0xA5, p[kHeaderSize + 11] = 0xFF;
            reseal(p);
            sent.push_back(p);
            sent.push_back(p);
        }
        sent.insert(sent.end(), s.base.begin(), s.base.end());
        sent.insert(sent.end(), s.points.begin(), s.points.end());
        w.write("unusual", "texcoords_before_stream_info",
                desc + ", with the 4 TEXCOORDS packets first, last to first, each with its reserved bytes 9..11 set to "
                       "5A A5 FF (ignored) and sent twice in a row: held until the STREAM_INFO arrives (spec 11.2), then "
                       "taken in the order they arrived (the second copy of each a duplicate); decodes as valid/texcoords "
                       "but for the counters and the packets' outcomes",
                sent);
    }
    {
        // The extremes: 16 bits over the widest finite range, 4 bits, runs of one record.
        TexcoordsStream t = texcoords_stream();
        t.contents[0].texcoord_sets[1].range.bits = 4;
        for (auto& r : t.contents[0].texcoord_sets[1].records) r = {uint16_t(r[0] & 15), uint16_t(r[1] & 15)};
        t.contents[0].texcoord_sets[0].range = {16, {-1e30f, 0}, {2e30f, 0}};
        for (auto& r : t.contents[0].texcoord_sets[0].records) r[1] = 0xFFFF;
        StreamPackets packets;
        if (packetize_stream(t.info, t.contents, kStreamId, packets) != Error::Ok) {
            std::cerr << "make_vectors: packetize_stream (texcoords limits) failed\n";
            std::exit(1);
        }
        Packets file = packets.stream_info;
        for (const Packets* p : {&packets.ellipsoids, &packets.points, &packets.texcoords})
            file.insert(file.end(), p->begin(), p->end());
        // And object 1's set as runs of one record each, the last first.
        Packets ones;
        for (uint32_t i = 12; i-- > 0;) {
            const auto& set = t.contents[1].texcoord_sets[0];
            PacketHeader h;
            h.version_minor = kTexcoordsMinor;
            h.type = uint8_t(PacketType::Texcoords);
            h.flags = kFlagSkippable;
            h.stream_id = kStreamId;
            h.object_id = 1;
            ones.push_back(write_packet(h, raw_texcoords_payload(i, 1, 1, 1, 16, set.range.origin, set.range.scale,
                                                                 {set.records[i]})));
        }
        Packets kept;
        for (const Packet& p : file)
            if (!(p[6] == uint8_t(PacketType::Texcoords) && get16(p, 16) == 1)) kept.push_back(p);
        kept.insert(kept.end(), ones.begin(), ones.end());
        w.write("unusual", "texcoords_limits",
                "the texture-coordinate stream with object 0's TEXCOORD_1 at 16 bits over origin (-1e30, 0) and scale "
                "(2e30, 0) (the largest range whose end is finite in f32: -1e30 + 2e30 = 1e30; v of every record 65535 "
                "over a scale of 0, dequantized to the origin) and its TEXCOORD_2 at 4 bits (the fewest), and object 1's "
                "set sent as 12 TEXCOORDS packets of one record each (count 1), point 11 first; every record held",
                numbered(kept));
    }

    // ---- faulty ----
    const size_t E = kHeaderSize;
    struct Case {
        const char* name;
        size_t packet;  // index into s.texcoords
        const char* what;
        std::function<void(Packet&)> edit;
        const char* reason;
    };
    auto payload_edit = [](std::function<void(std::vector<uint8_t>&)> f) {
        return [f](Packet& p) {
            std::vector<uint8_t> payload = payload_of(p);
            f(payload);
            p = with_payload(p, payload);
        };
    };
    auto put_f32_at = [](std::vector<uint8_t>& payload, size_t at, float v) {
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        for (int i = 0; i < 4; ++i) payload[at + i] = uint8_t(bits >> (8 * i));
    };
    const std::vector<Case> cases = {
        {"texcoords_short", 2, "object 0's TEXCOORD_2 packet cut to 27 bytes of payload",
         payload_edit([](std::vector<uint8_t>& p) { p.resize(27); }), "malformed payload (spec 30.1 step 11: shorter than 28 bytes)"},
        {"texcoords_count_zero", 2, "object 0's TEXCOORD_2 packet with count 0 and no records",
         payload_edit([](std::vector<uint8_t>& p) { p.resize(28), p[4] = 0, p[5] = 0; }), "malformed payload (spec 30.1 step 11: count 0)"},
        {"texcoords_set_count_zero", 2, "object 0's TEXCOORD_2 packet with set_count 0", [&](Packet& p) { p[E + 7] = 0; },
         "malformed payload (spec 30.1 step 11: set_count 0)"},
        {"texcoords_set_count_eight", 2, "object 0's TEXCOORD_2 packet with set_count 8", [&](Packet& p) { p[E + 7] = 8; },
         "malformed payload (spec 30.1 step 11: set_count above 7)"},
        {"texcoords_set_zero", 2, "object 0's TEXCOORD_2 packet with set 0", [&](Packet& p) { p[E + 6] = 0; },
         "malformed payload (spec 30.1 step 11: set 0)"},
        {"texcoords_set_past_count", 2, "object 0's TEXCOORD_2 packet with set 3, above its set_count 2",
         [&](Packet& p) { p[E + 6] = 3; }, "malformed payload (spec 30.1 step 11: set above set_count)"},
        {"texcoords_bits_three", 2, "object 0's TEXCOORD_2 packet with bits 3 (its 80 bytes of records re-cut to 30)",
         payload_edit([](std::vector<uint8_t>& p) { p[8] = 3, p.resize(28 + 30); }),
         "malformed payload (spec 30.1 step 11: bits below 4)"},
        {"texcoords_bits_seventeen", 2, "object 0's TEXCOORD_2 packet with bits 17 and count 4 (its records re-cut to the 17 bytes 4 records of 34 bits take)",
         payload_edit([](std::vector<uint8_t>& p) { p[8] = 17, p[4] = 4, p[5] = 0, p.resize(28 + 17); }),
         "malformed payload (spec 30.1 step 11: bits above 16)"},
        {"texcoords_run_past_index", 2, "object 0's TEXCOORD_2 packet with first_index 4294967290 (a run of 40 past 2^32 - 1)",
         payload_edit([](std::vector<uint8_t>& p) { p[0] = 0xFA, p[1] = p[2] = p[3] = 0xFF; }),
         "malformed payload (spec 30.1 step 11: first_index + count > 2^32 - 1)"},
        {"texcoords_origin_nan", 2, "object 0's TEXCOORD_2 packet with origin u NaN",
         payload_edit([&](std::vector<uint8_t>& p) { put_f32_at(p, 12, std::numeric_limits<float>::quiet_NaN()); }),
         "malformed payload (spec 30.1 step 11: a range component not finite)"},
        {"texcoords_scale_negative", 2, "object 0's TEXCOORD_2 packet with scale v -0.5",
         payload_edit([&](std::vector<uint8_t>& p) { put_f32_at(p, 24, -0.5f); }),
         "malformed payload (spec 30.1 step 11: a negative scale)"},
        {"texcoords_end_infinite", 2, "object 0's TEXCOORD_2 packet with origin u 3e38 and scale u 1e38 (finite each, their sum rounds to infinity in f32)",
         payload_edit([&](std::vector<uint8_t>& p) { put_f32_at(p, 12, 3e38f), put_f32_at(p, 20, 1e38f); }),
         "malformed payload (spec 30.1 step 11: origin + scale infinite)"},
        {"texcoords_length", 2, "object 0's TEXCOORD_2 packet with one byte more",
         payload_edit([](std::vector<uint8_t>& p) { p.push_back(0); }), "malformed payload (spec 30.1 step 11: the length)"},
        {"texcoords_no_texcoord_attribute", 2, "object 0's TEXCOORD_2 packet sent as object 2's (which carries no texture coordinates; its 40 records past object 2's 10 points too)",
         [&](Packet& p) { put16(p, 16, 2); }, "malformed payload (spec 30.1 step 13: the object carries no texture coordinates)"},
        {"texcoords_index_past", 3, "object 1's TEXCOORDS packet with first_index 1 (points 1..12 of 12)",
         [&](Packet& p) { p[E] = 1; }, "index out of range (spec 30.1 step 14)"},
        {"texcoords_set_count_differs", 2, "object 0's TEXCOORD_2 packet with set_count 3",
         [&](Packet& p) { p[E + 7] = 3; }, "stream mismatch (spec 30.1 step 15: set_count)"},
        {"texcoords_range_differs", 1, "object 0's second TEXCOORD_1 packet (points 36..39) with origin v 0.125",
         payload_edit([&](std::vector<uint8_t>& p) { put_f32_at(p, 16, 0.125f); }),
         "stream mismatch (spec 30.1 step 15: the set's range)"},
        {"texcoords_record_differs", 3, "object 1's TEXCOORDS packet with the u of point 0's record one higher",
         payload_edit([](std::vector<uint8_t>& p) { p[28] = uint8_t(p[28] + 1); if (p[28] == 0) p[29] = uint8_t(p[29] + 1); }),
         "stream mismatch (spec 30.1 step 15: a record)"},
    };
    for (const Case& c : cases)
        w.write("faulty", c.name,
                desc + ", then " + c.what + " (sequence 900): rejected as " + c.reason + "; the rest decodes as valid/texcoords",
                with_edited_copy(stream, first_texcoords + c.packet, c.edit));
    {
        Packets sent(stream.begin(), stream.begin() + long(first_texcoords + 1));
        sent.insert(sent.end(), stream.begin() + long(first_texcoords + 2), stream.end());
        w.write("faulty", "texcoords_missing",
                desc + ", without object 0's second TEXCOORD_1 packet (points 36..39): no rejection; object 0's "
                       "TEXCOORD_1 holds 36 of 40 records, so the object is not complete and the recording does not "
                       "conform (spec 30.2)",
                sent);
    }
}

// Format 1.11: vertices carried by the exact layer (EXACT_MESH, EXACT_MESH_REPAIR, spec 27). The
// exact-layer stream's sphere and panel (section 19's vectors) at packet size 256, each sending only
// part of its vertices as points: the sphere (normals) its first 33 points in the shuffled order, the
// panel (normals and texture coordinates) its first 28 and its unused middle vertex; the exact layer
// carries the others. STREAM_INFO says 1.3 as in the exact vectors, EXACT_MESH and EXACT_MESH_REPAIR
// packets 1.11, the others 1.0.
struct MeshLayerStream {
    StreamInfo info;
    std::vector<ObjectContent> contents;
    std::vector<std::vector<uint8_t>> coded;
    std::vector<uint32_t> triangle_count, carried_count;
    Packets info_packets, ellipsoids, points;
    std::vector<Packets> layer;  // per object
    Packets all() const {
        Packets out = info_packets;
        out.insert(out.end(), ellipsoids.begin(), ellipsoids.end());
        out.insert(out.end(), points.begin(), points.end());
        for (const Packets& c : layer) out.insert(out.end(), c.begin(), c.end());
        return out;
    }
};

MeshLayerStream mesh_layer_stream() {
    MeshLayerStream s;
    Rng rng(70);
    std::vector<ExactMesh> meshes = {exact_sphere(rng), exact_panel()};
    const std::array<size_t, 2> kept = {33, 28};
    std::vector<ObjectInfo> objects = {make_object({-1, -1, -1}, 2, 8, 0, kAttrNormal),
                                       make_object({1, -1, -1}, 2, 8, 0, kAttrNormal | kAttrTexcoord),
                                       make_object({-1, 2, -1}, 1, 0, 20, kAttrColor, ObjectKind::PointSet)};
    // The points each mesh keeps and the vertices it carries (the unused middle vertex stays a point).
    std::vector<std::vector<SurfacePoint>> sent(2), carried(2);
    std::vector<std::vector<Triangle>> triangles(2);
    for (size_t i = 0; i < 2; ++i) {
        ExactMesh& m = meshes[i];
        shuffle_points(m, rng);
        std::vector<char> used(m.points.size(), 0);
        for (const Triangle& t : m.triangles)
            for (uint32_t v : t) used[v] = 1;
        std::vector<uint32_t> index(m.points.size());
        for (uint32_t v = 0; v < m.points.size(); ++v)
            if (v < kept[i] || !used[v]) {
                index[v] = uint32_t(sent[i].size());
                sent[i].push_back(m.points[v]);
            } else {
                index[v] = 0x80000000u | uint32_t(carried[i].size());
                carried[i].push_back(m.points[v]);
            }
        for (Triangle t : m.triangles) {
            for (uint32_t& v : t) v = (index[v] & 0x80000000u) ? uint32_t(sent[i].size()) + (index[v] & 0xFFFFFFFu) : index[v];
            triangles[i].push_back(t);
        }
        objects[i].point_count = uint32_t(sent[i].size());
    }
    s.info = default_info(objects, 256);
    s.info.objects[0].exact_layer = true;
    s.info.objects[1].exact_layer = true;
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        const ObjectInfo& o = s.info.objects[i];
        ObjectContent c = make_content(s.info, o, rng);
        s.coded.emplace_back();
        s.triangle_count.push_back(0);
        s.carried_count.push_back(0);
        if (i < 2) {
            c.points.clear();
            std::vector<QuantizedPoint> vertices;
            for (const SurfacePoint& p : sent[i]) c.points.push_back(quantize_point(p, s.info, o));
            vertices = c.points;
            for (const SurfacePoint& p : carried[i]) vertices.push_back(quantize_point(p, s.info, o));
            std::vector<Triangle> decoded;
            std::vector<uint32_t> order;
            if (encode_exact_mesh(vertices, c.points.size(), triangles[i], s.info, o, s.coded[i], decoded, order) !=
                Error::Ok) {
                std::cerr << "make_vectors: encode_exact_mesh failed\n";
                std::exit(1);
            }
            s.triangle_count[i] = uint32_t(triangles[i].size());
            s.carried_count[i] = uint32_t(carried[i].size());
        }
        s.contents.push_back(std::move(c));
    }
    StreamPackets packets;
    if (packetize_stream(s.info, s.contents, kStreamId, packets) != Error::Ok) {
        std::cerr << "make_vectors: packetize_stream failed\n";
        std::exit(1);
    }
    mark_version_1_0(packets);
    for (Packet& p : packets.stream_info) {
        p[5] = 3;  // its entries use flags bit 8 (format 1.3)
        reseal(p);
    }
    s.info_packets = packets.stream_info;
    s.ellipsoids = packets.ellipsoids;
    s.points = packets.points;
    uint32_t sequence = uint32_t(s.info_packets.size() + s.ellipsoids.size() + s.points.size());
    for (size_t i = 0; i < s.info.objects.size(); ++i) {
        Packets out;
        if (!s.coded[i].empty() && packetize_connectivity(s.info, uint16_t(i), s.triangle_count[i], s.coded[i], kStreamId,
                                                          sequence, out, s.carried_count[i]) != Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity (EXACT_MESH) failed\n";
            std::exit(1);
        }
        sequence += uint32_t(out.size());
        s.layer.push_back(out);
    }
    return s;
}

// Offsets in an EXACT_MESH packet (header included), spec 27.1.
constexpr size_t kMeshTriangles = kHeaderSize, kMeshCarried = kHeaderSize + 4, kMeshSize = kHeaderSize + 8,
                 kMeshCrc = kHeaderSize + 12, kMeshOffset = kHeaderSize + 16, kMeshData = kHeaderSize + 20;

void exact_mesh_vectors(Writer& w) {
    const MeshLayerStream s = mesh_layer_stream();
    const Packets good = s.all();
    const std::string what =
        "the carried-vertices stream of valid/exact_mesh (the lumpy sphere of valid/exact with " +
        std::to_string(s.info.objects[0].point_count) + " of its 66 vertices sent as points and " +
        std::to_string(s.carried_count[0]) + " carried by its exact layer, the panel with " +
        std::to_string(s.info.objects[1].point_count) + " points and " + std::to_string(s.carried_count[1]) +
        " carried vertices, and the point set)";
    w.write("valid", "exact_mesh",
            "format 1.11, vertices carried by the exact layer (spec 27): " + what +
                "; objects 0 and 1 announce an exact layer (flags bit 8) sent in EXACT_MESH packets after the points, "
                "whose coded mesh introduces each carried vertex (position as a displacement from the parallelogram "
                "prediction, normal as direct bits, texture coordinates as a displacement from the prediction over the gate's) where a triangle first uses it; every "
                "object exact, `connectivity` listing `mesh`, `carried_count`, the triangles over points and carried "
                "vertices, and the carried vertices",
            good);
    const size_t layer0 = s.info_packets.size() + s.ellipsoids.size() + s.points.size();
    const size_t pieces0 = s.layer[0].size();
    {
        // Object 0's coded mesh with its first piece lost and brought back by a repair row (spec 27.1, 19.5).
        Packets repairs;
        if (packetize_connectivity_repairs(s.info, 0, s.triangle_count[0], s.coded[0], 2, kStreamId, 500, repairs,
                                           s.carried_count[0]) != Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity_repairs (EXACT_MESH_REPAIR) failed\n";
            std::exit(1);
        }
        Packets file(good.begin(), good.begin() + long(layer0));
        file.insert(file.end(), s.layer[0].begin() + 1, s.layer[0].end());
        file.push_back(repairs[1]);
        file.insert(file.end(), s.layer[1].begin(), s.layer[1].end());
        w.write("unusual", "exact_mesh_repair",
                what + ", with object 0's first EXACT_MESH piece lost (of " + std::to_string(pieces0) +
                    ") and its second EXACT_MESH_REPAIR row (row " + std::to_string(pieces0 + 1) +
                    ") sent instead: the missing source symbol is solved for (spec 27.1, 19.5); every object exact, "
                    "object 0's coded mesh `recovered`",
                file);
    }
    {
        Packets file = s.layer[1];
        const Packets rest = {good.begin(), good.begin() + long(layer0 + pieces0)};
        file.insert(file.end(), rest.begin(), rest.end());
        w.write("unusual", "exact_mesh_before_stream_info",
                what + ", with object 1's EXACT_MESH packet first, before the STREAM_INFO: held (spec 27, 11.2), "
                       "released when the STREAM_INFO arrives and accepted; every object exact",
                file);
    }
    // Faulty: one defect each.
    auto defective = [&](const std::function<void(Packet&)>& edit) {
        Packet p = good[layer0];
        put32(p, 12, 1000);
        edit(p);
        reseal(p);
        return p;
    };
    struct MeshEdit {
        const char* name;
        std::string description;
        std::function<void(Packet&)> edit;
    };
    const std::vector<MeshEdit> edits = {
        {"exact_mesh_carried_zero",
         "a copy of object 0's first EXACT_MESH packet (sequence 1000, after the stream) with carried_count 0: "
         "malformed payload (spec 27.1: an EXACT_MESH layer carries at least one vertex)",
         [](Packet& p) { put32(p, kMeshCarried, 0); }},
        {"exact_mesh_short",
         "a copy of object 0's first EXACT_MESH packet (sequence 1000, after the stream) cut to its first 18 payload "
         "bytes: malformed payload (spec 27.1: shorter than 20 bytes)",
         [](Packet& p) { p = with_payload(p, std::vector<uint8_t>(p.begin() + kHeaderSize, p.begin() + kHeaderSize + 18)); }},
        {"exact_mesh_carried_contradicts",
         "a copy of object 0's first EXACT_MESH packet (sequence 1000, after the stream) with carried_count one more "
         "than its other packets say: stream mismatch (spec 27.1: the description holds carried_count)",
         [&](Packet& p) { put32(p, kMeshCarried, s.carried_count[0] + 1); }},
        {"exact_mesh_too_many_triangles",
         "a copy of object 0's first EXACT_MESH packet (sequence 1000, after the stream) with triangle_count 8 * "
         "(point_count + carried_count) + 1: malformed payload (spec 27.1)",
         [&](Packet& p) {
             put32(p, kMeshTriangles, 8 * (s.info.objects[0].point_count + s.carried_count[0]) + 1);
         }},
    };
    for (const MeshEdit& e : edits) {
        Packets file = good;
        file.push_back(defective(e.edit));
        w.write("faulty", e.name, what + ", with " + e.description, file);
    }
    {
        // The other kind of exact layer for the same object: a CONNECTIVITY packet of object 0 after its
        // EXACT_MESH packets (its bytes those of the coded mesh).
        Packets file = good;
        ConnectivityPiece piece;
        piece.triangle_count = s.triangle_count[0];
        piece.coded_size = uint32_t(s.coded[0].size());
        piece.coded_crc = crc32c(s.coded[0].data(), s.coded[0].size());
        piece.offset = 0;
        piece.data.assign(s.coded[0].begin(), s.coded[0].begin() + std::min<size_t>(s.coded[0].size(), 100));
        PacketHeader h;
        h.version_minor = kConnectivityMinor;
        h.type = uint8_t(PacketType::Connectivity);
        h.flags = kFlagSkippable;
        h.stream_id = kStreamId;
        h.sequence = 1000;
        h.object_id = 0;
        file.push_back(write_packet(h, encode_connectivity_payload(piece)));
        w.write("faulty", "exact_mesh_mixed_kinds",
                what + ", with a CONNECTIVITY packet of object 0 (sequence 1000, after the stream; the first 100 bytes "
                       "of its coded mesh): stream mismatch (spec 27.1: one kind of exact layer per object, fixed by "
                       "the first packet taken); object 0 stays exact",
                file);
    }
    {
        // Carried vertices in an object with surface normals (spec 27.3): the panel of the normals vectors
        // (texture coordinates, normals left to the surface where they agree with it, one in three of
        // its vertices sending its own), the first 28 of its shuffled vertices and every vertex whose
        // normal is sent as points, the others carried; each carried vertex shown with its surface normal.
        ObjectInfo o = make_object({1, -1, -1}, 2, 8, 0, kAttrTexcoord);
        o.exact_layer = true;
        o.surface_normals = true;
        StreamInfo info = default_info({o}, kNormalsPacketSize);
        Rng prng(241);
        ExactMesh m = exact_panel();
        shuffle_points(m, prng);
        const ObjectInfo& oi = info.objects[0];
        std::vector<QuantizedPoint> all;
        std::vector<std::array<uint32_t, 3>> positions;
        for (const SurfacePoint& p : m.points) {
            all.push_back(quantize_point(p, info, oi));
            positions.push_back(all.back().position);
        }
        const SurfaceNormals sn = surface_normals(positions, m.triangles);
        std::vector<std::array<float, 3>> originals;
        for (size_t k = 0; k < positions.size(); ++k) {
            const bool defined = sn.normal[k] != std::array<float, 3>{0, 0, 0};
            originals.push_back(defined && k % 3 != 0 ? sn.normal[k] : m.points[k].normal);
        }
        const std::vector<NormalEntry> entries = reference_normal_entries(info, positions, m.triangles, originals);
        std::vector<char> used(all.size(), 0);
        for (const Triangle& t : m.triangles)
            for (uint32_t v : t) used[v] = 1;
        ObjectContent content = make_content(info, oi, prng);  // its ellipsoids
        std::vector<QuantizedPoint> carried;
        std::vector<uint32_t> index(all.size());
        for (uint32_t v = 0; v < all.size(); ++v)
            if (v < 28 || !used[v] || entries[v].sent) {
                index[v] = uint32_t(content.points.size());
                content.points.push_back(all[v]);
                content.normals.push_back(entries[v]);
            } else {
                index[v] = 0x80000000u | uint32_t(carried.size());
                carried.push_back(all[v]);
            }
        std::vector<Triangle> triangles;
        for (Triangle t : m.triangles) {
            for (uint32_t& v : t)
                v = (index[v] & 0x80000000u) ? uint32_t(content.points.size()) + (index[v] & 0xFFFFFFFu) : index[v];
            triangles.push_back(t);
        }
        info.objects[0].point_count = uint32_t(content.points.size());
        std::vector<QuantizedPoint> vertices = content.points;
        vertices.insert(vertices.end(), carried.begin(), carried.end());
        std::vector<uint8_t> coded;
        std::vector<Triangle> decoded;
        std::vector<uint32_t> order;
        if (encode_exact_mesh(vertices, content.points.size(), triangles, info, info.objects[0], coded, decoded, order) !=
            Error::Ok) {
            std::cerr << "make_vectors: encode_exact_mesh (surface normals) failed\n";
            std::exit(1);
        }
        StreamPackets packets;
        if (packetize_stream(info, {content}, kStreamId, packets) != Error::Ok) {
            std::cerr << "make_vectors: packetize_stream (surface normals) failed\n";
            std::exit(1);
        }
        for (Packet& p : packets.ellipsoids) set_minor(p, 0);
        for (Packet& p : packets.points) set_minor(p, 0);
        Packets file = packets.stream_info;
        for (const Packets* group : {&packets.ellipsoids, &packets.points, &packets.normals})
            file.insert(file.end(), group->begin(), group->end());
        Packets layer;
        if (packetize_connectivity(info, 0, uint32_t(triangles.size()), coded, kStreamId, 0, layer,
                                   uint32_t(carried.size())) != Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity (surface normals) failed\n";
            std::exit(1);
        }
        file.insert(file.end(), layer.begin(), layer.end());
        for (size_t k = 0; k < file.size(); ++k) restamp_packet(file[k], uint32_t(k));
        size_t sent = 0;
        for (const NormalEntry& e : content.normals) sent += e.sent;
        w.write("valid", "exact_mesh_surface_normals",
                "format 1.11 with format 1.8's surface normals (spec 27.3): one surface object, the panel of the "
                "normals vectors (texture coordinates, surface normals: " + std::to_string(sent) + " of its " +
                    std::to_string(content.points.size()) + " points send their normal), with " +
                    std::to_string(carried.size()) + " of its vertices carried (those past the first 28 of its "
                    "shuffled order whose normal the surface gives back; a vertex whose normal is sent stays a point) "
                    "in " + std::to_string(layer.size()) + " EXACT_MESH packet(s) of " + std::to_string(coded.size()) +
                    " coded bytes after its NORMALS packets; STREAM_INFO and NORMALS say 1.8, EXACT_MESH 1.11, the "
                    "others 1.0; exact, `normals` `surface` listing the carried vertices after the points, each with "
                    "its surface normal (what a receiver shows it)",
                file);
    }
    {
        // The paths valid/exact_mesh does not take (spec 27.2): one object with RGBA colour, 4 points and
        // 20 carried vertices: a fan of 20 triangles around point 0 whose ring is carried (the first
        // triangle a seed of a known corner and two fresh ones; point 0's list C fills at 16), and a
        // second part, triangles (1, 2, 3) and (2, 1, ring vertex 5), whose gate 1 -> 2 names a carried
        // vertex that is no candidate there (no list holds it): a direct index.
        StreamInfo info = default_info({make_object({-1, -1, -1}, 2, 4, 4, kAttrColor | kAttrColorAlpha)}, 256);
        info.objects[0].exact_layer = true;
        Rng prng(71);
        ObjectContent content = make_content(info, info.objects[0], prng);
        auto point = [&](double x, double y, double z, double t) {
            SurfacePoint p;
            p.position = {float(x), float(y), float(z)};
            p.color = {float(t), float(1 - t), float(0.5 * t), float(0.25 + 0.5 * t)};
            return quantize_point(p, info, info.objects[0]);
        };
        std::vector<QuantizedPoint> vertices = {point(0, 0, 0.05, 0), point(0.6, 0.6, 0, 0.2), point(0.8, 0.6, 0, 0.4),
                                                point(0.7, 0.8, 0.05, 0.6)};
        content.points = vertices;
        std::vector<Triangle> triangles;
        for (uint32_t i = 0; i < 20; ++i) {
            const double angle = 2 * M_PI * i / 20;
            vertices.push_back(point(0.5 * std::cos(angle), 0.5 * std::sin(angle), 0.1 * std::sin(3 * angle), i / 20.0));
            triangles.push_back({0, 4 + i, 4 + (i + 1) % 20});
        }
        triangles.push_back({1, 2, 3});
        triangles.push_back({2, 1, 4 + 5});
        std::vector<uint8_t> coded;
        std::vector<Triangle> decoded;
        std::vector<uint32_t> order;
        if (encode_exact_mesh(vertices, 4, triangles, info, info.objects[0], coded, decoded, order) != Error::Ok) {
            std::cerr << "make_vectors: encode_exact_mesh (paths) failed\n";
            std::exit(1);
        }
        StreamPackets packets;
        if (packetize_stream(info, {content}, kStreamId, packets) != Error::Ok) {
            std::cerr << "make_vectors: packetize_stream (paths) failed\n";
            std::exit(1);
        }
        mark_version_1_0(packets);
        for (Packet& p : packets.stream_info) {
            p[5] = 3;
            reseal(p);
        }
        Packets file = packets.stream_info;
        file.insert(file.end(), packets.ellipsoids.begin(), packets.ellipsoids.end());
        file.insert(file.end(), packets.points.begin(), packets.points.end());
        Packets layer;
        if (packetize_connectivity(info, 0, uint32_t(triangles.size()), coded, kStreamId, uint32_t(file.size()), layer,
                                   20) != Error::Ok) {
            std::cerr << "make_vectors: packetize_connectivity (paths) failed\n";
            std::exit(1);
        }
        file.insert(file.end(), layer.begin(), layer.end());
        w.write("unusual", "exact_mesh_paths",
                "format 1.11 (spec 27.2), the paths valid/exact_mesh does not take: one surface object with RGBA colour "
                "(its carried vertices' four channels as direct bits), 4 points and 20 carried vertices, 22 triangles "
                "in one EXACT_MESH packet of " + std::to_string(coded.size()) + " coded bytes: a fan around point 0 "
                "whose ring is carried (its first triangle a seed of a known corner, point 0, and two fresh corners; "
                "point 0's neighbour list fills at 16 carried vertices, the last 4 of the ring not in it), and a second "
                "part seeded by the points 1, 2, 3 whose gate 1 -> 2 brings ring vertex 5, a carried vertex that is no "
                "candidate there (no neighbour list of points 1 or 2 holds it): a direct index; exact",
                file);
        // Faulty: a coded mesh whose first fresh vertex lies outside the frame (spec 27.2: unusable).
        VectorRangeEncoder rc;
        uint16_t fresh0 = 1024, sign = 1024;
        std::array<uint16_t, 18> length;
        length.fill(1024);
        rc.bit(fresh0, 1);
        for (int i = 0; i < 17; ++i) rc.bit(length[i], 0);
        rc.bit(length[17], 1);  // x: 17 significant bits, 2^16 or more from the frame's middle
        rc.bit(sign, 0);
        rc.direct(0xFFFF, 16);
        const std::vector<uint8_t> bad = rc.finish();
        ConnectivityPiece piece;
        piece.triangle_count = uint32_t(triangles.size());
        piece.carried_count = 20;
        piece.coded_size = uint32_t(bad.size());
        piece.coded_crc = crc32c(bad.data(), bad.size());
        piece.offset = 0;
        piece.data = bad;
        PacketHeader h;
        h.version_minor = kExactMeshMinor;
        h.type = uint8_t(PacketType::ExactMesh);
        h.flags = kFlagSkippable;
        h.stream_id = kStreamId;
        h.sequence = uint32_t(file.size() - layer.size());
        h.object_id = 0;
        Packets faulty(file.begin(), file.end() - long(layer.size()));
        faulty.push_back(write_packet(h, encode_connectivity_payload(piece, true)));
        w.write("faulty", "exact_mesh_out_of_frame",
                "the stream of unusual/exact_mesh_paths with its EXACT_MESH packet replaced by one whose coded mesh (" +
                    std::to_string(bad.size()) + " bytes, made by hand) starts a seed with a fresh corner whose x "
                    "displacement has 17 significant bits (131071 from the frame's middle): the packet is accepted and "
                    "the coded mesh complete, but its decode is unusable (spec 27.2: a fresh vertex outside 0 .. 2^P - 1); "
                    "not exact, the stream does not conform",
                faulty);
    }
    {
        // The coded mesh of object 0 with a carried_count one more than it introduces, in every EXACT_MESH
        // packet: each is well formed and agrees with the others, but the decode is unusable. (One less is
        // no faulty vector: the decoder then reads the last fresh vertex's bits as other symbols, which
        // may decode to some mesh; no check can tell it from the sender's.)
        Packets file(good.begin(), good.begin() + long(layer0));
        for (Packet p : s.layer[0]) {
            put32(p, kMeshCarried, s.carried_count[0] + 1);
            reseal(p);
            file.push_back(p);
        }
        file.insert(file.end(), s.layer[1].begin(), s.layer[1].end());
        w.write("faulty", "exact_mesh_unusable",
                what + ", with carried_count one more than object 0's coded mesh introduces in each of its EXACT_MESH "
                       "packets: every packet accepted, the coded mesh complete, but its decode unusable (spec 27.2: "
                       "fresh bits are read where the encoder wrote none; here the decoder, out of step with the "
                       "coded mesh, meets an unusable value before the end; another such edit could decode to some "
                       "other mesh, which no check could tell from the sender's); object 0 not exact, the stream does "
                       "not conform",
                file);
    }
}

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
    scene_vectors(w);
    signed_vectors(w);
    bound_manifest_vectors(w);
    repair_vectors(w);
    extensions_vectors(w);
    exact_vectors(w);
    exact_repair_vectors(w);
    animation_vectors(w);
    skin_vectors(w);
    morph_vectors(w);
    map_vectors(w);
    normals_vectors(w);
    camera_light_vectors(w);
    exact_mesh_vectors(w);
    extras_vectors(w);
    required_extension_vectors(w);
    texcoords_vectors(w);
    std::printf("%zu vectors, %zu bytes with their JSON\n", w.written.size(), w.total_bytes);
    return 0;
}
