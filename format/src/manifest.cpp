// MANIFEST payloads (format 1.2, spec section 16; scheme 2, format 1.9, section 25): the layout and the bytes a digest and a
// signature cover. No cryptography here: hashing and signing belong to the auth library, so the
// format library stays free of dependencies.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>

namespace ellicast {

using namespace detail;

std::vector<uint8_t> encode_manifest_payload(const ManifestPart& part) {
    std::vector<uint8_t> out;
    out.reserve(manifest_fixed_size(part.scheme) + part.digests.size() * kPacketDigestSize + kManifestSignatureSize);
    put_u8(out, part.scheme);
    put_u8(out, 0);
    put_u16(out, part.part);
    put_u16(out, part.part_count);
    put_u16(out, static_cast<uint16_t>(part.digests.size()));
    put_u32(out, part.packet_count);
    put_u32(out, part.first);
    out.insert(out.end(), part.key_id.begin(), part.key_id.end());
    if (part.scheme == kManifestSchemeBound) put_u32(out, part.content_id);
    for (const PacketDigest& d : part.digests) out.insert(out.end(), d.begin(), d.end());
    out.insert(out.end(), part.signature.begin(), part.signature.end());
    return out;
}

Error decode_manifest_payload(std::span<const uint8_t> payload, ManifestPart& out) {
    if (payload.empty()) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    ManifestPart m;
    m.scheme = p[0];
    if (!is_known_manifest_scheme(m.scheme)) {
        // A later scheme: its layout is not this one's; the caller skips the packet (spec 16.2).
        out = std::move(m);
        return Error::Ok;
    }
    const size_t fixed = manifest_fixed_size(m.scheme);
    if (payload.size() < fixed + kManifestSignatureSize) return Error::MalformedPayload;
    m.part = get_u16(p + 2);
    m.part_count = get_u16(p + 4);
    const uint16_t n = get_u16(p + 6);
    m.packet_count = get_u32(p + 8);
    m.first = get_u32(p + 12);
    std::copy(p + 16, p + 24, m.key_id.begin());
    if (m.scheme == kManifestSchemeBound) m.content_id = get_u32(p + 24);
    if (payload.size() != fixed + size_t{n} * kPacketDigestSize + kManifestSignatureSize)
        return Error::MalformedPayload;
    if (m.part_count == 0 || m.part >= m.part_count) return Error::MalformedPayload;
    if (uint64_t{m.first} + n > m.packet_count) return Error::MalformedPayload;
    m.digests.resize(n);
    for (size_t i = 0; i < n; ++i)
        std::copy_n(p + fixed + i * kPacketDigestSize, kPacketDigestSize, m.digests[i].begin());
    std::copy_n(p + fixed + size_t{n} * kPacketDigestSize, kManifestSignatureSize, m.signature.begin());
    out = std::move(m);
    return Error::Ok;
}

size_t digests_per_manifest_packet(size_t packet_size, uint8_t scheme) {
    packet_size = std::min(packet_size, kMaxPacketSize);
    const size_t fixed = kPacketOverhead + manifest_fixed_size(scheme) + kManifestSignatureSize;
    if (packet_size <= fixed) return 0;
    return std::min<size_t>((packet_size - fixed) / kPacketDigestSize, 0xFFFF);
}

std::vector<uint8_t> packet_digest_input(std::span<const uint8_t> packet) {
    if (packet.size() < kPacketOverhead) return {};
    const size_t body = kHeaderSize + get_u16(packet.data() + 18);
    if (body + kChecksumSize > packet.size()) return {};
    std::vector<uint8_t> out(packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(body));
    std::fill(out.begin() + 12, out.begin() + 16, uint8_t{0});
    return out;
}

std::vector<uint8_t> manifest_signed_message(std::span<const uint8_t> packet) {
    std::vector<uint8_t> body = packet_digest_input(packet);
    if (body.size() < kHeaderSize + kManifestFixedSize + kManifestSignatureSize) return {};
    std::vector<uint8_t> out(kManifestContext.begin(), kManifestContext.end());
    out.insert(out.end(), body.begin(), body.end() - static_cast<std::ptrdiff_t>(kManifestSignatureSize));
    return out;
}

}  // namespace ellicast
