// Packet header, checksum framing, and the names of types and errors.
#include "ellicast/format.h"

#include "bytes.h"

#include <bit>
#include <cstdio>

namespace ellicast {

static_assert(std::endian::native == std::endian::little, "the CRC fast paths assume a little-endian host");

using namespace detail;

std::string packet_type_name(uint8_t type) {
    switch (type) {
    case 0x01: return "STREAM_INFO";
    case 0x02: return "ELLIPSOIDS";
    case 0x03: return "POINTS";
    case 0x10: return "SCENE";
    case 0x11: return "MATERIAL";
    case 0x12: return "TEXTURE_FRAGMENT";
    case 0x13: return "MATERIAL_EXTENSIONS";
    case 0x14: return "ANIMATION";
    case 0x15: return "SKIN";
    case 0x20: return "MANIFEST";
    case 0x04: return "POINTS_REPAIR";
    case 0x05: return "CONNECTIVITY";
    case 0x06: return "CONNECTIVITY_REPAIR";
    case 0x07: return "JOINT_WEIGHTS";
    case 0x08: return "MORPH_DELTAS";
    case 0x09: return "MAPPED_POINTS";
    case 0x0A: return "POINT_MAP";
    case 0x0B: return "NORMALS";
    case 0x0C: return "EXACT_MESH";
    case 0x0D: return "EXACT_MESH_REPAIR";
    case 0x0E: return "TEXCOORDS";
    case 0x16: return "MORPH_ANIMATION";
    case 0x17: return "CAMERA";
    case 0x18: return "LIGHT";
    case 0x19: return "EXTRAS";
    case 0x1A: return "REQUIRED_EXTENSION";
    default: {
        char buf[24];
        std::snprintf(buf, sizeof buf, "UNKNOWN(0x%02X)", type);
        return buf;
    }
    }
}

bool is_known_packet_type(uint8_t type) {
    return (type >= 0x01 && type <= 0x0E) || (type >= 0x10 && type <= 0x1A) || type == 0x20;
}

const char* error_name(Error e) {
    switch (e) {
    case Error::Ok: return "ok";
    case Error::TooShort: return "too short for a packet";
    case Error::BadMagic: return "bad magic";
    case Error::UnsupportedMajor: return "unsupported major version";
    case Error::InvalidType: return "invalid packet type 0";
    case Error::Oversized: return "declared size over 65000 bytes";
    case Error::Truncated: return "truncated";
    case Error::LengthMismatch: return "bytes after the packet";
    case Error::BadChecksum: return "bad CRC-32C";
    case Error::UnknownCriticalType: return "unknown critical packet type";
    case Error::MalformedPayload: return "malformed payload";
    case Error::NoStreamInfo: return "no stream info for its object";
    case Error::UnknownObject: return "object id beyond the object table";
    case Error::IndexOutOfRange: return "index beyond the declared count";
    case Error::StreamMismatch: return "another stream or contradicting stream info";
    case Error::BadSignature: return "not an ellicast container (bad signature)";
    case Error::UnsupportedContainer: return "unsupported container version";
    case Error::IoError: return "I/O error";
    case Error::ManifestSignature: return "bad manifest signature";
    case Error::NotAuthenticated: return "not authenticated";
    }
    return "unknown error";
}

PacketHeader skippable_header(PacketType type, uint8_t minor, uint32_t stream_id, uint32_t sequence,
                              uint16_t object_id) {
    PacketHeader h;
    h.version_minor = minor;
    h.type = static_cast<uint8_t>(type);
    h.flags = kFlagSkippable;
    h.stream_id = stream_id;
    h.sequence = sequence;
    h.object_id = object_id;
    return h;
}

std::vector<uint8_t> write_packet(PacketHeader header, std::span<const uint8_t> payload) {
    std::vector<uint8_t> out;
    out.reserve(kPacketOverhead + payload.size());
    for (uint8_t b : kPacketMagic) out.push_back(b);
    put_u8(out, header.version_major);
    put_u8(out, header.version_minor);
    put_u8(out, header.type);
    put_u8(out, header.flags);
    put_u32(out, header.stream_id);
    put_u32(out, header.sequence);
    put_u16(out, header.object_id);
    put_u16(out, static_cast<uint16_t>(payload.size()));
    out.insert(out.end(), payload.begin(), payload.end());
    put_u32(out, crc32c(out.data(), out.size()));
    return out;
}

Error parse_packet_prefix(std::span<const uint8_t> bytes, PacketView& out) {
    if (bytes.size() < kPacketOverhead) return Error::TooShort;
    const uint8_t* p = bytes.data();
    for (size_t i = 0; i < kPacketMagic.size(); ++i)
        if (p[i] != kPacketMagic[i]) return Error::BadMagic;
    PacketHeader h;
    h.version_major = p[4];
    h.version_minor = p[5];
    h.type = p[6];
    h.flags = p[7];
    h.stream_id = get_u32(p + 8);
    h.sequence = get_u32(p + 12);
    h.object_id = get_u16(p + 16);
    h.payload_length = get_u16(p + 18);
    // Magic and version (bytes 0..5) keep their place in every major version; the rest of the
    // layout belongs to major version 1. Lengths are checked before the checksum so that the CRC
    // never reads past the input; every field after that is trusted only once the CRC matched.
    if (h.version_major != kFormatMajor) return Error::UnsupportedMajor;
    if (h.packet_size() > kMaxPacketSize) return Error::Oversized;
    if (h.packet_size() > bytes.size()) return Error::Truncated;
    const size_t body = kHeaderSize + h.payload_length;
    if (crc32c(p, body) != get_u32(p + body)) return Error::BadChecksum;
    if (h.type == 0) return Error::InvalidType;
    out.header = h;
    out.payload = bytes.subspan(kHeaderSize, h.payload_length);
    out.size = h.packet_size();
    return Error::Ok;
}

Error parse_packet(std::span<const uint8_t> bytes, PacketView& out) {
    PacketView view;
    Error e = parse_packet_prefix(bytes, view);
    if (e != Error::Ok) return e;
    if (view.size != bytes.size()) return Error::LengthMismatch;
    out = view;
    return Error::Ok;
}

}  // namespace ellicast

namespace ellicast {

namespace {
// Sets one u32 header field of a valid packet and reseals it.
bool set_header_u32(std::vector<uint8_t>& packet, size_t offset, uint32_t value) {
    PacketView view;
    if (parse_packet(packet, view) != Error::Ok) return false;
    detail::set_u32(packet.data() + offset, value);
    const size_t body = packet.size() - kChecksumSize;
    detail::set_u32(packet.data() + body, crc32c(packet.data(), body));
    return true;
}
}  // namespace

bool restamp_packet(std::vector<uint8_t>& packet, uint32_t sequence) { return set_header_u32(packet, 12, sequence); }

bool set_packet_stream_id(std::vector<uint8_t>& packet, uint32_t stream_id) {
    return set_header_u32(packet, 8, stream_id);
}

}  // namespace ellicast
