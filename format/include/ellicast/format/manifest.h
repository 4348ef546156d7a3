// Signed streams (format 1.2): the layout of the MANIFEST packets that sign a stream, and the digests
// they list. Follows spec/format.md section 16 (Format 1.2 addition: signed streams): 16.1 Packet
// digest; 16.2 MANIFEST payload; and section 25.1 (format 1.9: scheme 2, bound to a content).
//
// A MANIFEST packet lists 16-byte digests of other
// packets (SHA-256 of the packet without its checksum and with its sequence number zeroed,
// truncated) and an Ed25519 signature over itself. This library lays the bytes out and computes
// digests; signing and verifying are in the auth library (libsodium).
#pragma once

#include "ellicast/format/error.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace ellicast {

inline constexpr size_t kPacketDigestSize = 16;
inline constexpr size_t kManifestFixedSize = 24;       // scheme 1: the fields before the digests
inline constexpr size_t kBoundManifestFixedSize = 28;  // scheme 2: content_id after the key id
inline constexpr size_t kManifestSignatureSize = 64;
inline constexpr size_t kKeyIdSize = 8;
inline constexpr uint8_t kManifestSchemeEd25519 = 1;       // format 1.2: digests under a stream id
inline constexpr uint8_t kManifestSchemeBound = 2;         // format 1.9: and bound to a content id
// Whether a scheme's layout is known here (the others are skipped, spec 16.2).
inline constexpr bool is_known_manifest_scheme(uint8_t scheme) {
    return scheme == kManifestSchemeEd25519 || scheme == kManifestSchemeBound;
}
inline constexpr size_t manifest_fixed_size(uint8_t scheme) {
    return scheme == kManifestSchemeBound ? kBoundManifestFixedSize : kManifestFixedSize;
}
// What a signature signs: this ASCII context, then the packet without signature and checksum.
inline constexpr std::string_view kManifestContext = "ellicast manifest";

using PacketDigest = std::array<uint8_t, kPacketDigestSize>;

struct ManifestPart {
    uint8_t scheme = kManifestSchemeBound;
    uint16_t part = 0;
    uint16_t part_count = 1;
    uint32_t packet_count = 0;  // digests in all parts together
    uint32_t first = 0;         // index of digests[0] in the whole list
    std::array<uint8_t, kKeyIdSize> key_id{};
    uint32_t content_id = 0;  // scheme 2 only: the content the listed packets belong to (spec 25.1)
    std::vector<PacketDigest> digests;
    std::array<uint8_t, kManifestSignatureSize> signature{};
};

std::vector<uint8_t> encode_manifest_payload(const ManifestPart& part);
// MalformedPayload when the payload is empty, or (schemes 1 and 2) the length does not match
// digest_count, part_count is 0, part is not below it, or the digests run past packet_count. Another
// scheme is not an error: only `scheme` is set, and the caller skips such a packet (its layout is a
// later version's).
Error decode_manifest_payload(std::span<const uint8_t> payload, ManifestPart& out);
// Digests one MANIFEST packet of `packet_size` bytes and the given scheme can carry.
size_t digests_per_manifest_packet(size_t packet_size, uint8_t scheme = kManifestSchemeBound);
// The bytes a packet's digest hashes: header and payload with the sequence bytes zeroed (empty
// when `packet` is shorter than its header says).
std::vector<uint8_t> packet_digest_input(std::span<const uint8_t> packet);
// SHA-256 (FIPS 180-4) of `data`.
std::array<uint8_t, 32> sha256(std::span<const uint8_t> data);
// A packet's digest (spec 16.1): the first 16 bytes of SHA-256 of packet_digest_input(packet).
// `packet` must hold a whole packet (its header's length is trusted: parse it first).
PacketDigest packet_digest(std::span<const uint8_t> packet);
// A public key's id (spec 16.2): the first 8 bytes of SHA-256 of its 32 bytes.
std::array<uint8_t, kKeyIdSize> key_id_of(std::span<const uint8_t, 32> public_key);
// The message a MANIFEST packet's signature signs: kManifestContext, then the packet's digest
// input without the trailing signature (empty when the packet is too short to be a MANIFEST).
std::vector<uint8_t> manifest_signed_message(std::span<const uint8_t> packet);

}  // namespace ellicast
